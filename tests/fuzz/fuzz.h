#pragma once
// What coif's fuzz targets share (tests/fuzz/README.md). Each target defines LLVMFuzzerTestOneInput; the
// same source is linked against libFuzzer (the `fuzz` preset, clang) and against corpus_runner.cpp (every
// build: the default suite runs each target over its corpus in tests/fuzz/corpus/<target>/, so a crash
// found once stays fixed).
//
// A target calls one parser with the input. A coif::Error is the parser refusing bad input: expected.
// Anything else — another exception, a crash, a sanitizer report, an allocation beyond libFuzzer's limit —
// is a bug.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <unistd.h>
#include <vector>

#include "models/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace coif::fuzz {

// Runs `parse` and swallows the coif::Error with which a parser refuses bad input.
template <class F>
void refused_or_parsed(F&& parse) {
    try {
        parse();
    } catch (const coif::Error&) {
    }
}

// This process's scratch file `<temp>/<stem><pid><extension>`, rewritten for every input and removed when the
// process exits normally (a crash leaves it, beside the input libFuzzer saves).
inline std::filesystem::path scratch_file(const std::string& stem, const std::string& extension) {
    struct Removed {
        std::vector<std::filesystem::path> paths;
        ~Removed() {
            std::error_code ec;
            for (const auto& p : paths) std::filesystem::remove(p, ec);
        }
    };
    static Removed removed;
    std::filesystem::path path = std::filesystem::temp_directory_path() / (stem + std::to_string(::getpid()) + extension);
    if (std::find(removed.paths.begin(), removed.paths.end(), path) == removed.paths.end()) removed.paths.push_back(path);
    return path;
}

// The input as a file, for parsers that read a path.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const std::string& extension) {
    const std::filesystem::path path = scratch_file("coif-fuzz-", extension);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (size && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    return path;
}

inline std::string_view text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

}  // namespace coif::fuzz
