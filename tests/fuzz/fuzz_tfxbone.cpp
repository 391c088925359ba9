// AMD TressFX's .tfxbone strand-skinning reader (models/character.h parse_tfxbone).
#include <vector>

#include "models/character.h"
#include "tests/fuzz/fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::byte> bytes(reinterpret_cast<const std::byte*>(data), reinterpret_cast<const std::byte*>(data) + size);
    coif::fuzz::refused_or_parsed([&] { coif::parse_tfxbone(bytes, "fuzz.tfxbone"); });
    return 0;
}
