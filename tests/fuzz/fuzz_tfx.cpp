// AMD TressFX's .tfx strand reader (models/strands.h parse_tfx).
#include <vector>

#include "models/strands.h"
#include "tests/fuzz/fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::byte> bytes(reinterpret_cast<const std::byte*>(data), reinterpret_cast<const std::byte*>(data) + size);
    coif::fuzz::refused_or_parsed([&] { coif::parse_tfx(bytes, "fuzz.tfx"); });
    return 0;
}
