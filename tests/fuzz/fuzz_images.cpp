// coif's checks after OpenImageIO: the image wrapper (models/core/image.h read_image), environment maps
// (offline/envmap.h envmap_from_image) and absorption maps (models/absorption_map.h). OpenImageIO's own
// decoders are not ours, so the input is not fed to them raw: its bytes choose an image (size, channels,
// format) and its pixel values — any float, NaN and infinities included — which OpenImageIO writes and coif
// reads back through every check.
#include <cstring>

#include "models/absorption_map.h"
#include "models/core/image.h"
#include "offline/envmap.h"
#include "tests/fuzz/fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 4) return 0;
    const int width = 1 + data[0] % 16, height = 1 + data[1] % 16, channels = 3 + (data[2] & 1);
    const char* extension = (data[3] & 1) ? ".hdr" : ".exr";
    coif::Image image(width, height, channels);
    const std::size_t floats = std::min(image.pixels.size(), (size - 4) / sizeof(float));
    std::memcpy(image.pixels.data(), data + 4, floats * sizeof(float));
    const std::filesystem::path path = coif::fuzz::scratch_file("coif-fuzz-image-", extension);
    coif::WriteOptions wo;
    wo.full_float = true;
    try {
        coif::write_image(path, image, wo);
    } catch (const coif::Error&) {
        return 0;
    }
    coif::fuzz::refused_or_parsed([&] { (void)coif::read_image(path); });
    coif::fuzz::refused_or_parsed([&] { (void)coif::envmap_from_image(coif::read_image(path), path); });
    coif::fuzz::refused_or_parsed([&] { (void)coif::read_absorption_map(path, static_cast<std::size_t>(height)); });
    return 0;
}
