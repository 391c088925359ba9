// The record atlas's layout, written once for its packer (online/shells/record_atlas.cpp, compiled as C++
// through shaders/glsl_prelude.h) and its fetch (shaders/gl/shell_shade.glsl).
//
// Every HRIR database record (db/hrir_db.h) is ATLAS_PARTS tiles of views × X texels (x along the HRIR,
// one row per view θv), each with a border of ATLAS_BORDER texels copied periodically from the opposite
// edge, so that one bilinear fetch interpolates x and θv across their wrap. Tiles are laid out row-major,
// `tiles_per_row` to a row; record r owns tiles ATLAS_PARTS·r … ATLAS_PARTS·r + ATLAS_PARTS − 1.
// The 12 channels of a record's 3 RGBA tiles hold, in order (atlas_value_index):
//   0 α, then re's Fourier coefficients in θl a0, a1, b1, a2, b2, a3, b3, a4, b4 (DESIGN.md decision 1),
//   then two unused channels (zero).
// Texels are 8-bit unorm with one affine range per part and channel (value = lo + scale · texel).
#ifndef COIF_SHADERS_GL_RECORD_ATLAS_GLSL
#define COIF_SHADERS_GL_RECORD_ATLAS_GLSL

#ifndef COIF_FN
#define COIF_FN
#endif

const int ATLAS_PARTS = 3;         // RGBA tiles per record: α + 9 coefficients of re = 10 of 12 channels
const int ATLAS_BORDER = 1;        // periodic border texels on each side of a tile
const int ATLAS_RE_COEFFICIENTS = 9;  // re's coefficients kept: orders 0..4 (a0, a1, b1, …, a4, b4)

// The texel position of the first interior texel (x = 0, view 0) of tile `tile`.
COIF_FN vec2 atlas_tile_origin(uint tile, int tiles_per_row, int hrir_length, int views) {
    uint tx = tile % uint(tiles_per_row);
    uint ty = tile / uint(tiles_per_row);
    return vec2(float(tx) * float(hrir_length + 2 * ATLAS_BORDER), float(ty) * float(views + 2 * ATLAS_BORDER)) +
           float(ATLAS_BORDER);
}

// What channel `channel` (0..3) of part `part` holds: 0 = α, 1..9 = re coefficient index + 1, > 9 unused.
COIF_FN int atlas_value_index(int part, int channel) { return part * 4 + channel; }

// A record of a denser sector thinned to its own sector's density (online/scene/cook.cpp sector_thinning): the look-up
// returns the nearest record, and for sparse sectors that is one of a denser sector (docs/quality.md, "The records'
// density against their sectors'"). Its fibres' coverage α becomes 1 − (1 − α)^c, c ≤ 1 the sector's density over the
// record's (c of the record's layers of fibres kept, each layer covering as the record's do), and re, which is the
// record's scattered light per unit of α, is scaled with α.
COIF_FN float thinned_alpha(float alpha, float c) { return 1.0 - pow(max(1.0 - alpha, 1e-6), c); }

#endif
