// GL only in online/ (STYLE.md, Filament's narrow backend): tools/ parses options and calls library functions,
// so its sources make no GL or GLFW call, name no GL type or constant and include neither epoxy nor GLFW.
// Comments and string literals are left out of the search (help texts may name GL_RENDERER).
// GCC 12 reports a false -Wmaybe-uninitialized inside <regex>'s automaton (a std::function moved from a
// temporary) when it inlines it under the sanitizer build's flags: the standard library's, not this file's. The
// warning is judged where the headers' text stands, so it is off for the whole file.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/test_data.h"

namespace coif {
namespace {
namespace fs = std::filesystem;

// `text` with every comment and string or character literal replaced by spaces (newlines kept, so that line
// numbers stay). Raw string literals are not used in tools/ and not handled.
std::string code_only(const std::string& text) {
    std::string out = text;
    enum { code, line_comment, block_comment, string, character } state = code;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i], next = i + 1 < text.size() ? text[i + 1] : '\0';
        const auto blank = [&](std::size_t k) { if (out[k] != '\n') out[k] = ' '; };
        switch (state) {
        case code:
            if (c == '/' && next == '/') state = line_comment;
            else if (c == '/' && next == '*') state = block_comment;
            else if (c == '"') state = string;
            else if (c == '\'') state = character;
            if (state != code) blank(i);
            break;
        case line_comment:
            if (c == '\n') state = code;
            else blank(i);
            break;
        case block_comment:
            blank(i);
            if (c == '*' && next == '/') { blank(i + 1); ++i; state = code; }
            break;
        case string:
        case character:
            blank(i);
            if (c == '\\') { blank(i + 1); ++i; }
            else if (c == (state == string ? '"' : '\'')) state = code;
            break;
        }
    }
    return out;
}

TEST(ToolsLayering, NoGlCallTypeConstantOrHeaderInTools) {
    // gl*/glfw* functions, GL*/GLFW* types and GL_*/GLFW_* constants, and the epoxy and GLFW headers.
    const std::regex gl(R"(\b(gl[A-Z]\w*|glfw\w*|GL_\w+|GLFW\w*|GL[a-z]\w*)\b|#\s*include\s*<(epoxy|GLFW)/)");
    std::vector<std::string> found;
    int files = 0;
    for (const auto& entry : fs::directory_iterator(test::source_dir() / "tools")) {
        const fs::path& p = entry.path();
        if (p.extension() != ".cpp" && p.extension() != ".h") continue;
        ++files;
        std::ifstream in(p);
        std::stringstream ss;
        ss << in.rdbuf();
        std::istringstream lines(code_only(ss.str()));
        std::string line;
        for (int n = 1; std::getline(lines, line); ++n) {
            std::smatch m;
            if (std::regex_search(line, m, gl)) found.push_back(p.filename().string() + ":" + std::to_string(n) + ": " + m.str());
        }
    }
    EXPECT_GT(files, 10) << "tools/ sources not found under " << test::source_dir();
    std::string list;
    for (const std::string& f : found) list += "  " + f + "\n";
    EXPECT_TRUE(found.empty()) << "GL in tools/ (move it into a library call in online/):\n" << list;
}

// The search itself: it finds a call, a constant and a header, and not what comments and strings say.
TEST(ToolsLayering, CodeOnlyDropsCommentsAndStrings) {
    const std::string text = "a(\"glFinish \\\" GL_X\"); // glFinish\nb; /* GL_RGBA\n */ c = '\"'; glFinish();";
    const std::string code = code_only(text);
    EXPECT_EQ(code.size(), text.size());
    EXPECT_EQ(std::count(code.begin(), code.end(), '\n'), 2);  // line numbers kept
    EXPECT_EQ(code.find("GL_"), std::string::npos) << code;
    EXPECT_EQ(code.find("glFinish"), code.rfind("glFinish")) << code;  // only the call is left
    EXPECT_NE(code.find("glFinish();"), std::string::npos) << code;
    EXPECT_NE(code.find("a("), std::string::npos) << code;
    EXPECT_NE(code.find(" c = "), std::string::npos) << code;
}

}  // namespace
}  // namespace coif
