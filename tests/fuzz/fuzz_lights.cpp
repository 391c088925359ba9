// The SRBF lights JSON reader (offline/srbf_lights.h srbf_lights_from_json).
#include "offline/srbf_lights.h"
#include "tests/fuzz/fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    coif::fuzz::refused_or_parsed([&] { coif::srbf_lights_from_json(coif::fuzz::text(data, size), "fuzz.json"); });
    return 0;
}
