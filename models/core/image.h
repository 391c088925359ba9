#pragma once
// Images: linear floating-point pixels, read and written through OpenImageIO.
//
// In memory: `Image` holds width × height pixels of 3 (RGB) or 4 (RGBA) float channels, row-major,
// row 0 at the top, values linear (scene-referred). Alpha, when present, is straight (not premultiplied).
//
// Reading (`read_image`): .exr, .hdr, .png and anything else OpenImageIO reads. 8-bit/16-bit
// integer files (PNG, JPEG, ...) are decoded to [0,1] and converted from sRGB to linear when the file
// says it is sRGB (OpenImageIO's "oiio:ColorSpace", the default for PNG/JPEG). Grey files are expanded to RGB.
// `ImageInfo` tells the caller whether the source was floating point (HDR) or integer (LDR).
//
// Writing (`write_image`), always atomic (temp file in the same folder + rename):
//   .exr  linear, half float, ZIP compression (float with `WriteOptions::full_float`).
//   .hdr  linear Radiance RGBE (alpha dropped).
//   .png  8-bit, tone-mapped for display by the tone map below, alpha (if any) kept straight.
// The tone map (state it wherever PNGs are shown): c_out = sRGB_OETF(clamp(c · 2^exposure, 0, 1)),
// per channel, where sRGB_OETF is the IEC 61966-2-1 transfer function. That is: exposure in stops,
// then a hard clip, then sRGB encoding; no filmic curve, so what is white in the PNG is ≥ 1 in the EXR.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace coif {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 4;                // 3 (RGB) or 4 (RGBA)
    std::vector<float> pixels;       // width * height * channels, row 0 at the top

    Image() = default;
    Image(int width, int height, int channels, float fill = 0.0f);

    float* at(int x, int y) { return pixels.data() + (static_cast<size_t>(y) * width + x) * channels; }
    const float* at(int x, int y) const { return pixels.data() + (static_cast<size_t>(y) * width + x) * channels; }
    bool empty() const { return pixels.empty(); }
};

struct ImageInfo {
    bool floating_point = false;     // the file stored floats/halfs (HDR) rather than integers
    int bits_per_channel = 0;
    std::string format;              // OpenImageIO's format name, e.g. "openexr", "hdr", "png"
};

// Largest image coif reads or writes (per side); guards against absurd headers.
inline constexpr int kMaxImageSide = 32768;

// Throws coif::Error naming the file on any failure (missing, unreadable, corrupt, too large).
Image read_image(const std::filesystem::path& path, ImageInfo* info = nullptr);

struct WriteOptions {
    float exposure = 0.0f;           // stops, applied only to tone-mapped (PNG) output
    bool full_float = false;         // EXR: 32-bit float instead of half
    std::string description;         // stored as ImageDescription metadata when non-empty
};

// An image file name's extension, lower case (".png"): what write_image goes by.
std::string image_extension(const std::filesystem::path& path);
// Throws the coif::Error write_image throws for a name it cannot write (not .exr, .png or .hdr), so that a command
// can refuse it before any work.
void check_image_name(const std::filesystem::path& path);

// Throws coif::Error on an unknown extension, bad image, or failed write; never leaves a partial file.
void write_image(const std::filesystem::path& path, const Image& image, const WriteOptions& options = {});

// The PNG tone map above, for one linear channel value; exposure_scale = 2^exposure.
float tone_map_srgb(float linear, float exposure_scale);  // shaders/display.glsl: the viewer displays with the same
float srgb_to_linear(float encoded);

}  // namespace coif
