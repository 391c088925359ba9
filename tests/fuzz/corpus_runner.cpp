// Runs a fuzz target (tests/fuzz/fuzz.h) over every file of the folders given, in name order: the default
// suite's regression run of each corpus. Fails when a folder is missing or empty, so it never passes on nothing.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "tests/fuzz/fuzz.h"

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s CORPUS_FOLDER...\n", argv[0]);
        return 2;
    }
    std::size_t inputs = 0;
    for (int a = 1; a < argc; ++a) {
        std::vector<std::filesystem::path> files;
        std::error_code ec;
        for (const auto& e : std::filesystem::directory_iterator(argv[a], ec))
            if (e.is_regular_file()) files.push_back(e.path());
        if (ec || files.empty()) {
            std::fprintf(stderr, "%s: no corpus files in %s\n", argv[0], argv[a]);
            return 1;
        }
        std::sort(files.begin(), files.end());
        for (const auto& f : files) {
            std::ifstream in(f, std::ios::binary);
            const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
            ++inputs;
        }
    }
    std::printf("%zu inputs ran without a crash\n", inputs);
    return 0;
}
