#pragma once
// The record atlas: HRIR database records (db/hrir_db.h) packed as one RGBA8 image for the shell
// renderer's bilinear fetch, with the per-record means the scene preparation needs. GL-free; the layout
// (tiles, borders, channel order) is shaders/gl/record_atlas.glsl, shared with the shader that reads it.
//
// Quantisation: 8-bit unorm texels with one affine range per channel of each part (value = lo + scale ·
// texel / 255). Bilinear filtering and the neighbour blend commute with the affine map, so the shader decodes
// once per sector. Half the memory of RGBA16F and llvmpipe's faster 8-bit filtering; its effect on the image
// (51 dB against RGBA16F) is in docs/renderer.md.
#include <array>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "models/core/bulk.h"

namespace coif {

inline constexpr int kAtlasParts = 3;            // shaders/gl/record_atlas.glsl ATLAS_PARTS
inline constexpr int kAtlasReCoefficients = 9;   // ATLAS_RE_COEFFICIENTS: re's a0, a1, b1, …, a4, b4

struct RecordAtlas {
    int width = 1, height = 1;       // texels
    int tiles_per_row = 1;
    int views = 0, hrir_length = 0;  // the database's angle grids (tile interior: hrir_length × views)
    Bulk<std::uint8_t> texels;  // RGBA8, width × height, row 0 first
    std::array<glm::vec4, kAtlasParts> lo{}, scale{};  // value = lo + scale · texel / 255, per part and channel
    std::vector<float> mean_alpha, mean_a0;  // per record: mean α and mean re a0 over views and x
    // Σ mean a0 / Σ mean α over the whole database's records (docs/renderer.md), not only the atlas's: an atlas of
    // the records one style uses renders as the database's would.
    float re_norm = 1;

    // The decoded value of channel `channel` of part `part` at (x, view) of `record` (tests).
    float value(std::size_t record, int part, int channel, int view, int x) const;
};

// What a record's 12 atlas channels hold at one texel: (α, a0, a1, b1, …, a4, b4, 0, 0) as the layout orders them.
using AtlasTexels = std::array<float, 4 * kAtlasParts>;
// The value a channel of a part holds (shaders/gl/record_atlas.glsl atlas_value_index): 0 α, 1..9 re's
// coefficient index + 1, above that unused.
int atlas_value_index(int part, int channel);
// A record's coverage α thinned by c ≤ 1, 1 − (1 − α)^c (shaders/gl/record_atlas.glsl thinned_alpha, which the shells
// apply per texel with ShellSector::shadow.z).
float thinned_alpha(float alpha, float c);

// Packs `records` records of views × hrir_length texels, `values(record, view, x)` giving each texel's channels,
// quantised with the given ranges (`lo`, `scale`: those of every record the atlas may be asked to match, e.g. a
// whole database's, so that a subset packs to the same texels). Fills texels and the layout; the per-record means
// and re_norm are the caller's. GL- and database-free: online/scene/cook.h packs a database's records with it.
RecordAtlas pack_atlas(std::size_t records, int views, int hrir_length, const std::array<glm::vec4, kAtlasParts>& lo,
                       const std::array<glm::vec4, kAtlasParts>& scale,
                       const std::function<AtlasTexels(std::size_t record, int view, int x)>& values);
// pack_atlas in two steps, for a caller that keeps records' tiles between packings (online/scene/cook.h's CookCache):
// record_tiles quantises one record's texels into its kAtlasParts tiles with their borders (part by part, each
// (hrir_length + 2 border) × (views + 2 border) RGBA8 texels, row by row), and place_record_tiles lays out an atlas
// of `records` records and copies record i's tiles (`tiles(i)`, as record_tiles made them) into its place. The same
// texels as pack_atlas. Throws coif::Error::parameter for tiles of another size.
std::vector<std::uint8_t> record_tiles(int views, int hrir_length, const std::array<glm::vec4, kAtlasParts>& lo,
                                       const std::array<glm::vec4, kAtlasParts>& scale,
                                       const std::function<AtlasTexels(int view, int x)>& values);
RecordAtlas place_record_tiles(std::size_t records, int views, int hrir_length, const std::array<glm::vec4, kAtlasParts>& lo,
                               const std::array<glm::vec4, kAtlasParts>& scale,
                               const std::function<const std::vector<std::uint8_t>&(std::size_t record)>& tiles);

}  // namespace coif
