#pragma once
// The hair's optical density on a voxel grid, for the shell renderer's shadows between clusters
// (DESIGN.md decision 5; docs/renderer.md says why a grid and what it costs).
//
// A voxel holds the strands' length per unit volume, by direction: the second moment M = Σ ℓ t tᵀ / V of the
// unit tangents t of the ℓ of strand in a voxel of volume V (6 numbers; its trace is the length density).
// A ray along ω crosses fibres of radius r at the rate 2r · Σ ℓ |sin ψ| / V per unit length (ψ the angle
// between ω and the fibre), the expected number of fibres met, exactly as `coif reference`'s cylinders of
// radius r meet it; the grid gives Σ ℓ |sin ψ| / V as √(tr M · (tr M − ωᵀ M ω)), which is exact for the
// fibres of a voxel that are parallel and, by Jensen, at most 4 % high for isotropic ones (√(2/3) against π/4).
// docs/quality.md ("The shadows count the reference's fibres") says why this replaced the SATF model's
// optical depth κ π λ ℓ / V, 2.2× the fibres' cross-section.
//
// Strands come from the style's densities (models/style_strands.h, the strands the reference
// renderer draws), turned by `orientation`; each segment's length is split into sub-segments no
// longer than half a voxel and splatted trilinearly, summed in fixed point (GridSums). The grid spans the strands'
// bounds plus two voxels on every side (so that trilinear splats and fetches lose nothing at the border), at most
// `max_dim` voxels along the longest axis (at least 0.92 of it), cubic voxels on a lattice (GridSums::can_reframe).
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <utility>
#include <vector>

#include "models/character.h"
#include "models/core/bulk.h"
#include "models/strands.h"

namespace coif {

struct DensityGrid {
    glm::ivec3 dims{0};
    glm::vec3 origin{0.0f};   // world position of the grid's corner (voxel (0,0,0)'s low corner)
    float voxel = 1.0f;       // edge length, world units
    glm::vec3 strands_min{0.0f}, strands_max{0.0f};  // the voxelized (turned) strands' bounding box
    // x fastest; M's diagonal (xx, yy, zz) and xy in `diagonal_xy`, (xz, yz) in `off_diagonal`: per unit volume
    Bulk<glm::vec4> diagonal_xy;
    Bulk<glm::vec2> off_diagonal;
    glm::vec3 extent() const { return glm::vec3(dims) * voxel; }
    std::size_t index(int x, int y, int z) const { return (static_cast<std::size_t>(z) * dims.y + y) * dims.x + x; }
    // The length density tr M of a voxel.
    float length_density(int x, int y, int z) const;
    // Trilinear M at a world point (voxel centres at origin + (i + ½) voxel; 0 outside), as GL samples it, and
    // the projected length density √(tr M (tr M − ωᵀMω)) it gives along the unit direction ω.
    float projected(glm::vec3 p, glm::vec3 omega) const;
    // ∫ projected(·, d) ds along p + s d, s ∈ [0, length], midpoint rule with steps of `step`: the fibres of
    // radius r met are 2r times this.
    float integrate(glm::vec3 p, glm::vec3 d, float length, float step) const;
};

// √(tr M (tr M − ωᵀMω)) for M given as (xx, yy, zz, xy) and (xz, yz), the formula shaders/gl/density_march.glsl
// repeats for the GPU's marches (it is two lines; tests compare the shadow pass and the key lights' volumes with
// integrate()).
float projected_length_density(glm::vec4 diagonal_xy, glm::vec2 off_diagonal, glm::vec3 omega);

inline constexpr int kShadowGridSize = 64;  // shadow grid voxels along the hair's longest axis (docs/renderer.md: error and cost)
// The key lights' fine grid (ShellSettings::key_lights): a voxel of 1/128 of the hair, finer than the clusters' narrow
// half-axis, so that a fragment's shadow resolves its own cluster's side (docs/quality.md, "The shadow marched from
// each fragment on a finer grid": 64 voxels left the lights along the hair at 0.25-0.47, 256 brighter everywhere).
inline constexpr int kKeyLightGridSize = 128;

// Throws coif::Error::parameter on an empty strand set or max_dim outside 8..512.
DensityGrid voxelize_strands(const Strands& strands, const glm::mat3& orientation, int max_dim);

// The bounding box of the strands turned by `orientation` (what voxelize_strands frames).
std::pair<glm::vec3, glm::vec3> turned_bounds(const Strands& strands, const glm::mat3& orientation);

// What voxelize_strands sums, in fixed point (an int64 per value: each splat rounded to 2⁻²⁰ voxel of strand length and
// shared by trilinear weights in steps of 1/256 voxel, online/shells/shadow_grid.cpp): integer sums do not depend on the
// order in which strands are added or taken out. A
// caller that keeps them (online/scene/cook.h's CookCache, for a style being edited) takes an edited cluster's old
// strands out and puts its new ones in, and has the grid of voxelizing all of them, bit for bit, as long as their
// bounds (the grid's frame) are the same.
class GridSums {
public:
    // An empty grid framing the turned strands' bounds [lo, hi] as voxelize_strands does; throws as it does.
    GridSums(glm::vec3 lo, glm::vec3 hi, int max_dim);
    // Whether bounds [lo, hi] are framed with the same voxel size: then reframe keeps the sums. The voxel is on a
    // lattice (a power of 2^(1/8), voxel corners at whole multiples of it), so bounds that move a little keep it.
    bool can_reframe(glm::vec3 lo, glm::vec3 hi) const;
    // The same sums framed for bounds [lo, hi] (can_reframe, or coif::Error::parameter), as a grid made for them frames
    // them: the voxels of both frames keep their sums, the rest are dropped or empty. An edit's cook frames the union of
    // the old and new bounds, takes the old strands out and puts the new ones in, then frames the new bounds.
    void reframe(glm::vec3 lo, glm::vec3 hi);
    // The strands turned by `orientation`, splatted in (sign 1) or taken out (sign −1).
    void add(const Strands& strands, const glm::mat3& orientation, int sign = 1);
    DensityGrid grid() const;
    const DensityGrid& frame() const { return frame_; }  // the dimensions, origin, voxel and bounds; no values

private:
    void frame(glm::vec3 lo, glm::vec3 hi);  // the window of the lattice holding [lo, hi], at frame_.voxel
    DensityGrid frame_;
    int max_dim_ = 0;
    glm::ivec3 first_{0};  // the lattice coordinates of voxel (0, 0, 0)
    std::vector<std::array<std::int64_t, 6>> sums_;
};

// `grid` grown by whole voxels to hold the box [lo, hi] as well, at most by half its longest extent on each side (so at
// most twice its longest side along any axis: 128³ voxels for the 64 of coif's grids, 48 MiB): the same voxels hold the
// same values, the new ones are empty. A body beside the hair (online/shell_renderer.h set_body) gets its own voxels this
// way; a character far larger than its hair is cut.
DensityGrid extend_grid(const DensityGrid& grid, glm::vec3 lo, glm::vec3 hi);

// A character's body as an opaque occluder on `grid`'s voxels (x fastest, 0 or 1): the voxels its surface crosses
// (every triangle sampled at a third of a voxel) and those it encloses (no path of free voxels joins them to the
// grid's border; an open mesh encloses nothing). The body is turned by `orientation`, as the hair's strands are. Only
// the part of the body within the grid (extend_grid) is held: the rest casts no shadow on the hair.
std::vector<std::uint8_t> voxelize_body(const BodyMesh& body, const glm::mat3& orientation, const DensityGrid& grid);
// A ray that crosses body voxels meets kBodyOpacity times its length through them in voxels as optical depth, at most
// kBodyMaxDepth (shaders/gl/shell_shadow.comp, which repeats both): a wall one voxel thick, sampled trilinearly, gives
// at least 20, e^−20 ≈ 2e-9 of the light. The cap keeps a blocked ray from counting as thousands of fibres in the
// multiple scattering's fibres met n (one blocked ray of 7 adds 20/7).
inline constexpr float kBodyOpacity = 40.0f;
inline constexpr float kBodyMaxDepth = 20.0f;

}  // namespace coif
