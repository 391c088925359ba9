#pragma once
// What coif's fuzz targets share (tests/fuzz/README.md). Each target defines LLVMFuzzerTestOneInput; the
// same source is linked against libFuzzer (the `fuzz` preset, clang) and against corpus_runner.cpp (every
// build: the default suite runs each target over its corpus in tests/fuzz/corpus/<target>/, so a crash
// found once stays fixed).
//
// A target calls one parser with the input. A coif::Error is the parser refusing bad input: expected.
// Anything else — another exception, a crash, a sanitizer report, an allocation beyond libFuzzer's limit —
// is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <unistd.h>

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

// The input as a file, for parsers that read a path (one per process, rewritten for every input).
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const std::string& extension) {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("coif-fuzz-" + std::to_string(::getpid()) + extension);
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
