#include "online/shells/record_atlas.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "shaders/glsl_prelude.h"

namespace coif {
namespace glsl {
#include "shaders/gl/record_atlas.glsl"
}  // namespace glsl

static_assert(kAtlasParts == glsl::ATLAS_PARTS);

namespace {

// The interior origin of a tile, as the shader computes it, in whole texels.
glm::ivec2 tile_origin(std::size_t tile, int tiles_per_row, int hrir_length, int views) {
    return glm::ivec2(glsl::atlas_tile_origin(static_cast<unsigned>(tile), tiles_per_row, hrir_length, views));
}

}  // namespace

RecordAtlas pack_record_atlas(const HrirDatabase& db) {
    const AngleGrids& g = db.params().grids;
    const int X = g.hrir_length, V = g.views, B = glsl::ATLAS_BORDER;
    RecordAtlas a;
    a.views = V;
    a.hrir_length = X;
    const std::size_t records = db.size();
    const std::size_t tiles = records * kAtlasParts;
    // Square-ish: tiles_per_row · (X + 2B) ≈ tile_rows · (V + 2B).
    a.tiles_per_row = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles) * (V + 2 * B) / (X + 2 * B))));
    a.tiles_per_row = std::max(1, a.tiles_per_row);
    const int tile_rows = static_cast<int>((tiles + a.tiles_per_row - 1) / a.tiles_per_row);
    a.width = a.tiles_per_row * (X + 2 * B);
    a.height = std::max(1, tile_rows * (V + 2 * B));

    std::vector<glm::vec4> values(static_cast<std::size_t>(a.width) * a.height, glm::vec4(0.0f));
    std::vector<std::uint8_t> part_of(values.size(), 0);  // which part each texel belongs to
    std::array<glm::vec4, kAtlasParts> hi{};
    a.lo.fill(glm::vec4(std::numeric_limits<float>::max()));
    hi.fill(glm::vec4(std::numeric_limits<float>::lowest()));
    a.mean_alpha.resize(records);
    a.mean_a0.resize(records);
    for (std::size_t rec = 0; rec < records; ++rec) {
        const std::vector<float> r = db.record(rec);
        double sa = 0, s0 = 0;
        for (int v = 0; v < V; ++v)
            for (int x = 0; x < X; ++x) {
                sa += r[g.alpha_offset(v) + x];
                s0 += r[g.re_offset(v, 0) + x];
            }
        a.mean_alpha[rec] = static_cast<float>(sa / (V * X));
        a.mean_a0[rec] = static_cast<float>(s0 / (V * X));
        for (int part = 0; part < kAtlasParts; ++part) {
            const glm::ivec2 o = tile_origin(rec * kAtlasParts + part, a.tiles_per_row, X, V) - B;
            for (int py = 0; py < V + 2 * B; ++py)
                for (int px = 0; px < X + 2 * B; ++px) {
                    const int v = (py - B + V) % V, x = (px - B + X) % X;  // periodic borders
                    glm::vec4 texel(0.0f);
                    for (int ch = 0; ch < 4; ++ch) {
                        const int value = glsl::atlas_value_index(part, ch);
                        if (value == 0) texel[ch] = r[g.alpha_offset(v) + x];
                        // re's first 9 coefficients; a database of a lower order leaves the rest zero, one of a
                        // higher order is read to order 4.
                        else if (value <= glsl::ATLAS_RE_COEFFICIENTS && value - 1 < g.coefficients())
                            texel[ch] = r[g.re_offset(v, value - 1) + x];
                    }
                    const std::size_t at = static_cast<std::size_t>(o.y + py) * a.width + o.x + px;
                    values[at] = texel;
                    part_of[at] = static_cast<std::uint8_t>(part);
                    a.lo[part] = glm::min(a.lo[part], texel);
                    hi[part] = glm::max(hi[part], texel);
                }
        }
    }
    for (int part = 0; part < kAtlasParts; ++part) {
        for (int ch = 0; ch < 4; ++ch)
            if (!(hi[part][ch] > a.lo[part][ch])) hi[part][ch] = a.lo[part][ch] + 1.0f;  // a constant (or unused) channel
        a.scale[part] = hi[part] - a.lo[part];
    }
    a.texels.resize(values.size() * 4);
    for (std::size_t t = 0; t < values.size(); ++t) {
        const int part = part_of[t];
        for (int ch = 0; ch < 4; ++ch) {
            const float u = (values[t][ch] - a.lo[part][ch]) / a.scale[part][ch] * 255.0f;
            a.texels[t * 4 + ch] = static_cast<std::uint8_t>(std::clamp(std::lround(u), 0L, 255L));
        }
    }
    const double sum_alpha = std::accumulate(a.mean_alpha.begin(), a.mean_alpha.end(), 0.0);
    const double sum_a0 = std::accumulate(a.mean_a0.begin(), a.mean_a0.end(), 0.0);
    a.re_norm = sum_alpha > 0 && sum_a0 > 0 ? static_cast<float>(sum_a0 / sum_alpha) : 1.0f;
    return a;
}

float RecordAtlas::value(std::size_t record, int part, int channel, int view, int x) const {
    const glm::ivec2 o = tile_origin(record * kAtlasParts + part, tiles_per_row, hrir_length, views);
    const std::size_t at = (static_cast<std::size_t>(o.y + view) * width + o.x + x) * 4 + channel;
    return lo[part][channel] + scale[part][channel] * (texels.at(at) / 255.0f);
}

}  // namespace coif
