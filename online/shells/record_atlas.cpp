#include "online/shells/record_atlas.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "shaders/glsl_prelude.h"

namespace coif {
namespace glsl {
#include "shaders/gl/record_atlas.glsl"
}  // namespace glsl

static_assert(kAtlasParts == glsl::ATLAS_PARTS && kAtlasReCoefficients == glsl::ATLAS_RE_COEFFICIENTS);

namespace {

// The interior origin of a tile, as the shader computes it, in whole texels.
glm::ivec2 tile_origin(std::size_t tile, int tiles_per_row, int hrir_length, int views) {
    return glm::ivec2(glsl::atlas_tile_origin(static_cast<unsigned>(tile), tiles_per_row, hrir_length, views));
}

}  // namespace

int atlas_value_index(int part, int channel) { return glsl::atlas_value_index(part, channel); }

float thinned_alpha(float alpha, float c) { return glsl::thinned_alpha(alpha, c); }

std::vector<std::uint8_t> record_tiles(int views, int hrir_length, const std::array<glm::vec4, kAtlasParts>& lo,
                                       const std::array<glm::vec4, kAtlasParts>& scale,
                                       const std::function<AtlasTexels(int view, int x)>& values) {
    const int X = hrir_length, V = views, B = glsl::ATLAS_BORDER;
    std::vector<AtlasTexels> record(static_cast<std::size_t>(V) * X);
    for (int v = 0; v < V; ++v)
        for (int x = 0; x < X; ++x) record[static_cast<std::size_t>(v) * X + x] = values(v, x);
    std::vector<std::uint8_t> out(static_cast<std::size_t>(kAtlasParts) * (X + 2 * B) * (V + 2 * B) * 4);
    std::size_t at = 0;
    for (int part = 0; part < kAtlasParts; ++part)
        for (int py = 0; py < V + 2 * B; ++py)
            for (int px = 0; px < X + 2 * B; ++px) {
                const int v = (py - B + V) % V, x = (px - B + X) % X;  // periodic borders
                const AtlasTexels& t = record[static_cast<std::size_t>(v) * X + x];
                for (int ch = 0; ch < 4; ++ch) {
                    const float u = (t[part * 4 + ch] - lo[part][ch]) / scale[part][ch] * 255.0f;
                    out[at++] = static_cast<std::uint8_t>(std::clamp(std::lround(u), 0L, 255L));
                }
            }
    return out;
}

RecordAtlas place_record_tiles(std::size_t records, int views, int hrir_length, const std::array<glm::vec4, kAtlasParts>& lo,
                               const std::array<glm::vec4, kAtlasParts>& scale,
                               const std::function<const std::vector<std::uint8_t>&(std::size_t record)>& tiles) {
    const int X = hrir_length, V = views, B = glsl::ATLAS_BORDER;
    RecordAtlas a;
    a.views = V;
    a.hrir_length = X;
    a.lo = lo;
    a.scale = scale;
    const std::size_t count = records * kAtlasParts;
    // Square-ish: tiles_per_row · (X + 2B) ≈ tile_rows · (V + 2B).
    a.tiles_per_row = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count) * (V + 2 * B) / (X + 2 * B))));
    a.tiles_per_row = std::max(1, a.tiles_per_row);
    const int tile_rows = static_cast<int>((count + a.tiles_per_row - 1) / a.tiles_per_row);
    a.width = a.tiles_per_row * (X + 2 * B);
    a.height = std::max(1, tile_rows * (V + 2 * B));
    std::vector<std::uint8_t>& texels = a.texels.vector();
    texels.assign(static_cast<std::size_t>(a.width) * a.height * 4, 0);
    const std::size_t row_bytes = static_cast<std::size_t>(X + 2 * B) * 4;
    const std::size_t part_bytes = row_bytes * (V + 2 * B);
    for (std::size_t rec = 0; rec < records; ++rec) {
        const std::vector<std::uint8_t>& t = tiles(rec);
        if (t.size() != part_bytes * kAtlasParts) throw Error::parameter("record atlas", "a record's tiles are of another size");
        for (int part = 0; part < kAtlasParts; ++part) {
            const glm::ivec2 o = tile_origin(rec * kAtlasParts + part, a.tiles_per_row, X, V) - B;
            for (int py = 0; py < V + 2 * B; ++py)
                std::copy_n(t.begin() + static_cast<std::ptrdiff_t>(part * part_bytes + py * row_bytes), row_bytes,
                            texels.begin() + static_cast<std::ptrdiff_t>((static_cast<std::size_t>(o.y + py) * a.width + o.x) * 4));
        }
    }
    return a;
}

RecordAtlas pack_atlas(std::size_t records, int views, int hrir_length, const std::array<glm::vec4, kAtlasParts>& lo,
                       const std::array<glm::vec4, kAtlasParts>& scale,
                       const std::function<AtlasTexels(std::size_t, int, int)>& values) {
    std::vector<std::uint8_t> tile;
    return place_record_tiles(records, views, hrir_length, lo, scale, [&](std::size_t rec) -> const std::vector<std::uint8_t>& {
        tile = record_tiles(views, hrir_length, lo, scale, [&](int v, int x) { return values(rec, v, x); });
        return tile;
    });
}

float RecordAtlas::value(std::size_t record, int part, int channel, int view, int x) const {
    const glm::ivec2 o = tile_origin(record * kAtlasParts + part, tiles_per_row, hrir_length, views);
    const std::size_t at = (static_cast<std::size_t>(o.y + view) * width + o.x + x) * 4 + channel;
    return lo[part][channel] + scale[part][channel] * (texels.at(at) / 255.0f);
}

}  // namespace coif
