#include "models/core/image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "models/core/atomic_file.h"
#include "models/core/error.h"
#include "shaders/display.h"

namespace coif {
namespace fs = std::filesystem;
using namespace OIIO;

Image::Image(int w, int h, int c, float fill) : width(w), height(h), channels(c) {
    if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide || (c != 3 && c != 4))
        throw Error::parameter("image", "invalid size " + std::to_string(w) + "x" + std::to_string(h) + "x" +
                                            std::to_string(c));
    pixels.assign(static_cast<size_t>(w) * h * c, fill);
}

float srgb_to_linear(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float tone_map_srgb(float linear, float exposure_scale) { return glsl::tone_map_srgb(linear, exposure_scale); }

Image read_image(const fs::path& path, ImageInfo* info) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(path, "", "no such file");
    if (fs::is_directory(path, ec)) throw Error(path, "", "is a folder, not an image");
    if (fs::file_size(path, ec) == 0) throw Error(path, "", "empty file");
    auto in = ImageInput::open(path.string());
    if (!in) throw Error(path, "", "cannot read as an image: " + OIIO::geterror());
    const ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxImageSide || spec.height > kMaxImageSide)
        throw Error(path, "header", "image size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                        " is outside 1.." + std::to_string(kMaxImageSide));
    if (spec.nchannels < 1 || spec.nchannels > 64)
        throw Error(path, "header", "unsupported channel count " + std::to_string(spec.nchannels));
    const int file_channels = spec.nchannels;
    std::vector<float> raw(static_cast<size_t>(spec.width) * spec.height * file_channels);
    if (!in->read_image(0, 0, 0, file_channels, TypeDesc::FLOAT, raw.data()))
        throw Error(path, "pixels", "cannot decode: " + in->geterror());
    const bool is_float = spec.format.is_floating_point();
    if (info) {
        info->floating_point = is_float;
        info->bits_per_channel = static_cast<int>(spec.format.size() * 8);
        info->format = in->format_name();
    }
    const std::string colorspace = spec.get_string_attribute("oiio:ColorSpace");
    const bool srgb = !is_float && (colorspace.empty() || Strutil::iequals(colorspace, "sRGB"));
    in->close();

    const int out_channels = (file_channels == 2 || file_channels >= 4) ? 4 : 3;
    Image img(spec.width, spec.height, out_channels);
    const size_t n = static_cast<size_t>(spec.width) * spec.height;
    for (size_t i = 0; i < n; ++i) {
        const float* s = raw.data() + i * file_channels;
        float* d = img.pixels.data() + i * out_channels;
        const bool grey = file_channels <= 2;
        for (int c = 0; c < 3; ++c) {
            const float v = grey ? s[0] : s[c];
            d[c] = srgb ? srgb_to_linear(v) : v;
        }
        if (out_channels == 4) d[3] = grey ? s[1] : s[3];
    }
    return img;
}

std::string image_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

void check_image_name(const fs::path& path) {
    const std::string ext = image_extension(path);
    if (ext != ".exr" && ext != ".png" && ext != ".hdr")
        throw Error(path, "", "unknown image extension '" + ext + "' (use .exr, .png or .hdr)");
}

void write_image(const fs::path& path, const Image& image, const WriteOptions& options) {
    if (image.width <= 0 || image.height <= 0 || (image.channels != 3 && image.channels != 4) ||
        image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels)
        throw Error(path, "", "refusing to write an empty or malformed image");
    check_image_name(path);
    const std::string ext = image_extension(path);

    // Encoded in memory, then written by write_file_atomic, which checks every write(2): OpenImageIO's own file
    // writers report no error when the disk fills up (a full tmpfs got 0-byte .exr and .png files with success).
    std::vector<unsigned char> encoded;
    {
        Filesystem::IOVecOutput memory(encoded);
        auto out = ImageOutput::create(path.string());
        if (!out) throw Error(path, "", "no writer for this format: " + OIIO::geterror());
        if (!out->supports("ioproxy")) throw Error(path, "", "this format's writer cannot encode into memory");
        if (!out->set_ioproxy(&memory)) throw Error(path, "", "cannot encode into memory: " + out->geterror());
        const int channels = ext == ".hdr" ? 3 : image.channels;
        const bool png = ext == ".png";
        ImageSpec spec(image.width, image.height, channels,
                       png ? TypeDesc::UINT8 : (ext == ".exr" && !options.full_float ? TypeDesc::HALF : TypeDesc::FLOAT));
        if (channels == 4) spec.alpha_channel = 3;
        if (ext == ".exr") spec.attribute("compression", "zip");
        if (!options.description.empty()) spec.attribute("ImageDescription", options.description);
        std::vector<float> data(static_cast<size_t>(image.width) * image.height * channels);
        const float scale = std::exp2(options.exposure);
        const size_t n = static_cast<size_t>(image.width) * image.height;
        for (size_t i = 0; i < n; ++i) {
            const float* s = image.pixels.data() + i * image.channels;
            float* d = data.data() + i * channels;
            for (int c = 0; c < channels; ++c) {
                float v = s[c];
                if (png) v = c == 3 ? std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f) : tone_map_srgb(v, scale);
                d[c] = v;
            }
        }
        if (png) spec.attribute("oiio:ColorSpace", "sRGB");
        if (!out->open(path.string(), spec)) throw Error(path, "", "cannot encode: " + out->geterror());
        if (!out->write_image(TypeDesc::FLOAT, data.data())) throw Error(path, "", "cannot encode: " + out->geterror());
        if (!out->close()) throw Error(path, "", "cannot encode: " + out->geterror());
    }
    if (encoded.empty()) throw Error(path, "", "the image encoded to no bytes");
    write_file_atomic(path, std::as_bytes(std::span<const unsigned char>(encoded)));
}

}  // namespace coif
