#pragma once
// The record atlas: the HRIR database's records (db/hrir_db.h) packed as one RGBA8 image for the shell
// renderer's bilinear fetch, with the per-record means the scene preparation needs. GL-free; the layout
// (tiles, borders, channel order) is shaders/gl/record_atlas.glsl, shared with the shader that reads it.
//
// Quantisation: 8-bit unorm texels with one affine range per channel of each part (value = lo + scale ·
// texel / 255). Bilinear filtering and the neighbour blend commute with the affine map, so the shader decodes
// once per sector. Half the memory of RGBA16F and llvmpipe's faster 8-bit filtering; its effect on the image
// (51 dB against RGBA16F) is in docs/renderer.md.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "db/hrir_db.h"

namespace coif {

inline constexpr int kAtlasParts = 3;  // shaders/gl/record_atlas.glsl ATLAS_PARTS

struct RecordAtlas {
    int width = 1, height = 1;       // texels
    int tiles_per_row = 1;
    int views = 0, hrir_length = 0;  // the database's angle grids (tile interior: hrir_length × views)
    std::vector<std::uint8_t> texels;  // RGBA8, width × height, row 0 first
    std::array<glm::vec4, kAtlasParts> lo{}, scale{};  // value = lo + scale · texel / 255, per part and channel
    std::vector<float> mean_alpha, mean_a0;  // per record: mean α and mean re a0 over views and x
    float re_norm = 1;                       // Σ mean a0 / Σ mean α over the records (docs/renderer.md)

    // The decoded value of channel `channel` of part `part` at (x, view) of `record` (tests).
    float value(std::size_t record, int part, int channel, int view, int x) const;
};

RecordAtlas pack_record_atlas(const HrirDatabase& db);

}  // namespace coif
