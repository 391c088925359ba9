#pragma once
// The hair's optical density on a voxel grid, for the shell renderer's shadows between clusters
// (DESIGN.md decision 5; docs/renderer.md says why a grid and what it costs).
//
// Value of a voxel: the optical depth per unit length at κ = 1 of the SATF model. A strand is a
// Gaussian of peak 1 and width λ in the plane across it (∫ρ dA = πλ²) and the planar ray tracer
// accumulates κ ρ / λ per unit of path (offline/planar_tracer.h), so ℓ of strand per volume V gives
// ρ̄ = πλ² ℓ / V and an optical depth per unit length of π λ ℓ / V (× κ). One unit of optical depth
// is about one strand met (a ray through a strand's centre collects κ√π ≈ 1.06 at κ = 0.6), which is
// how dual scattering's fibre count n reads it (shaders/lighting/srbf_shadowed.glsl).
//
// Strands come from the style's densities (models/style_strands.h, the strands the reference
// renderer draws), turned by `orientation`; each segment's length is split into sub-segments no
// longer than half a voxel and splatted trilinearly. The grid spans the strands' bounds plus one
// voxels on every side (so that trilinear splats and fetches lose nothing at the border), `max_dim`
// voxels along the longest axis, cubic voxels.
#include <glm/glm.hpp>
#include <vector>

#include "models/strands.h"

namespace coif {

struct DensityGrid {
    glm::ivec3 dims{0};
    glm::vec3 origin{0.0f};   // world position of the grid's corner (voxel (0,0,0)'s low corner)
    float voxel = 1.0f;       // edge length, world units
    std::vector<float> values;  // x fastest; optical depth per unit length at κ = 1
    glm::vec3 extent() const { return glm::vec3(dims) * voxel; }
    float at(int x, int y, int z) const { return values[(static_cast<std::size_t>(z) * dims.y + y) * dims.x + x]; }
    // Trilinear value at a world point (voxel centres at origin + (i + ½) voxel; 0 outside), as GL samples it.
    float sample(glm::vec3 p) const;
    // ∫ value ds along p + s d, s ∈ [0, length], midpoint rule with steps of `step`.
    float integrate(glm::vec3 p, glm::vec3 d, float length, float step) const;
};

// The RMS angle (radians) between each strand segment and the mean direction of the segments in its cell
// (cubes of edge `cell`, segments by their midpoints, weighted by length): how far fibres stray from the
// local direction of their bundle, which the shells draw as one tangent (ShellSettings::tangent_spread).
// Segments keep their root → tip sense, so hair flowing one way through a cell has a defined mean.
float strand_tangent_spread(const Strands& strands, float cell);

// Throws coif::Error::parameter on an empty strand set, λ <= 0 or max_dim outside 8..512.
DensityGrid voxelize_strands(const Strands& strands, const glm::mat3& orientation, double gaussian_width, int max_dim);

}  // namespace coif
