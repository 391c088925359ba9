// The hairstyle JSON reader (models/hair_style.h parse_style: validation, instance references resolved).
#include "models/hair_style.h"
#include "tests/fuzz/fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    coif::fuzz::refused_or_parsed([&] { coif::parse_style(coif::fuzz::text(data, size), "fuzz.json"); });
    return 0;
}
