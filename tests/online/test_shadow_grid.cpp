// The optical-density grid of the shell renderer's shadows between clusters (online/shells/shadow_grid.h).
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "models/core/error.h"
#include "online/shells/prepared_shells.h"
#include "online/shells/shadow_grid.h"

namespace coif {
namespace {

Strands straight_strands(int count, float length) {
    Strands s;
    s.offsets.push_back(0);
    for (int i = 0; i < count; ++i) {
        const float x = 0.01f * static_cast<float>(i % 10), z = 0.01f * static_cast<float>(i / 10);
        for (int k = 0; k <= 8; ++k) s.points.emplace_back(x, -length * static_cast<float>(k) / 8.0f, z);
        s.offsets.push_back(static_cast<std::uint32_t>(s.points.size()));
    }
    return s;
}

TEST(FibreTilts, AreTheMomentsOfTheStrandsTiltsAboutTheOwnClustersAxis) {
    // Two clusters, each an axis along −y sampled at 9 rows (placed 1 apart in x): the shells' lighting samples,
    // with the frame normal +x (so a tilt's components are along +x and T × +x = +z).
    const auto axes = [] {
        PreparedShells shells;
        shells.cluster_proto = {0, 0};
        shells.lighting_rows = 9;
        for (int c = 0; c < 2; ++c)
            for (int r = 0; r < 9; ++r)
                shells.samples.push_back({glm::vec4(float(c), -0.5f * float(r), 0.0f, 0.1f), glm::vec4(0, -1, 0, 0), glm::vec4(1, 0, 0, 0)});
        return shells;
    };
    // Straight strands along the axes: no tilt (float rounding: 1e-3 rad).
    PreparedShells shells = axes();
    const Strands straight = straight_strands(20, 4.0f);
    std::vector<std::uint32_t> cluster(straight.strand_count(), 0u);
    EXPECT_NEAR(measure_fibre_tilts(shells, straight, cluster, glm::mat3(1.0f)), 0.0f, 1e-3f);
    EXPECT_LT(glm::length(glm::vec3(shells.samples[4].tilt_a)), 1e-3f);
    // Zigzags of ±δ about −y in the x-y plane: every segment is δ off its axis, so the RMS is δ (float rounding of
    // acos: 1e-4 rad), whichever cluster they belong to. Their tilts are ±δ along x: mean 0 and a = √2 δ x̂ (the
    // four tilts ±a, ±b then have the second moment δ² x̂x̂ᵀ), b = 0. A quarter turn of the strands about y puts the
    // tilts along z.
    const float delta = 0.35f;
    Strands z;
    z.offsets.push_back(0);
    for (int i = 0; i < 4; ++i) {
        glm::vec3 p(float(i % 2), 0.0f, 0.0f);
        for (int k = 0; k <= 100; ++k) {
            z.points.push_back(p);
            const float s = (k % 2 == 0) ? 1.0f : -1.0f;
            p += 0.04f * glm::vec3(s * std::sin(delta), -std::cos(delta), 0.0f);
        }
        z.offsets.push_back(static_cast<std::uint32_t>(z.points.size()));
    }
    const std::vector<std::uint32_t> own{0u, 1u, 0u, 1u};
    EXPECT_NEAR(measure_fibre_tilts(shells, z, own, glm::mat3(1.0f)), delta, 1e-4f);
    for (const std::size_t i : {std::size_t(2), std::size_t(13)}) {  // a sample of each cluster
        const LightingSample& q = shells.samples[i];
        EXPECT_LT(glm::length(glm::vec3(q.tilt_mean)), 0.05f) << i;  // a row of 13 segments: one more of one sense, δ/13
        EXPECT_NEAR(std::abs(q.tilt_a.x), std::sqrt(2.0f) * delta, 0.01f) << i;
        EXPECT_NEAR(q.tilt_a.z, 0.0f, 1e-4f) << i;
        EXPECT_LT(glm::length(glm::vec3(q.tilt_b)), 1e-3f) << i;
    }
    const glm::mat3 quarter = glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0)));
    EXPECT_NEAR(measure_fibre_tilts(shells, z, own, quarter), delta, 1e-4f);
    EXPECT_NEAR(std::abs(shells.samples[2].tilt_a.z), std::sqrt(2.0f) * delta, 0.01f);
    EXPECT_NEAR(shells.samples[2].tilt_a.x, 0.0f, 1e-4f);
    // A strand's cluster must exist, and every strand needs one.
    EXPECT_THROW(measure_fibre_tilts(shells, z, std::vector<std::uint32_t>{0u, 1u, 2u, 0u}, glm::mat3(1.0f)), Error);
    EXPECT_THROW(measure_fibre_tilts(shells, z, std::vector<std::uint32_t>{0u, 1u}, glm::mat3(1.0f)), Error);
}

TEST(ShadowGrid, SumsDoNotDependOnTheOrderOfTheStrandsAndTakeStrandsOutExactly) {
    // The fixed-point sums (GridSums) make a grid that is the same, bit for bit, whatever the order of the strands and
    // after strands are taken out and others put in: what a cook keeping its grid between edits relies on
    // (online/scene/cook.h CookCache). Float sums fail all three comparisons.
    Strands a = straight_strands(30, 4.0f), b = straight_strands(20, 3.0f);
    for (glm::vec3& p : b.points) p += glm::vec3(0.05f, -0.3f, 0.005f);
    // a's strands with their inner points pulled towards its middle: inside its hull, so the bounds stay.
    Strands moved = a;
    for (std::size_t i = 0; i < moved.points.size(); ++i)
        if (i % 9 != 0 && i % 9 != 8) moved.points[i] += 0.3f * (glm::vec3(0.045f, -2.0f, 0.01f) - moved.points[i]);
    const glm::mat3 turn(glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0.2f, 1.0f, 0.1f)));
    const auto joined = [](const Strands& x, const Strands& y) {
        Strands s = x;
        s.add_strands(y);
        return s;
    };
    const auto same = [](const DensityGrid& x, const DensityGrid& y) {
        const auto equal = [](const auto& p, const auto& q) { return std::ranges::equal(p.span(), q.span()); };
        return x.dims == y.dims && x.origin == y.origin && x.voxel == y.voxel && equal(x.diagonal_xy, y.diagonal_xy) &&
               equal(x.off_diagonal, y.off_diagonal);
    };
    const DensityGrid ab = voxelize_strands(joined(a, b), turn, 32);
    EXPECT_TRUE(same(ab, voxelize_strands(joined(b, a), turn, 32)));
    // b and a in, a out, moved in: the grid of b and moved, when the bounds are the same.
    const auto [lo, hi] = turned_bounds(joined(joined(a, b), moved), turn);
    const DensityGrid bm = voxelize_strands(joined(b, moved), turn, 32);
    ASSERT_EQ(bm.strands_min, lo) << "the test's strands must keep the bounds";
    ASSERT_EQ(bm.strands_max, hi);
    GridSums sums(lo, hi, 32);
    sums.add(b, turn);
    sums.add(a, turn);
    sums.add(a, turn, -1);
    sums.add(moved, turn);
    EXPECT_TRUE(same(sums.grid(), bm));
    // b's strands moved beyond the bounds, by less than changes the voxel: framed to hold both, b out, b moved in, framed
    // to the new bounds: the grid of a and the moved b, made from nothing.
    Strands b_moved = b;
    for (glm::vec3& p : b_moved.points) p += glm::vec3(0.3f, 0.0f, -0.2f);
    const auto [new_lo, new_hi] = turned_bounds(joined(moved, b_moved), turn);
    ASSERT_TRUE(sums.can_reframe(new_lo, new_hi));
    sums.reframe(glm::min(lo, new_lo), glm::max(hi, new_hi));
    sums.add(b, turn, -1);
    sums.add(b_moved, turn);
    sums.reframe(new_lo, new_hi);
    EXPECT_TRUE(same(sums.grid(), voxelize_strands(joined(moved, b_moved), turn, 32)));
    EXPECT_FALSE(sums.can_reframe(new_lo, new_hi + glm::vec3(0.0f, 3.0f, 0.0f)));  // a longer side: another voxel
    // And tr M · voxel³ is still the strands' length, to float rounding.
    double grid_length = 0, length = 0;
    for (const glm::vec4& m : bm.diagonal_xy) grid_length += double(m.x) + m.y + m.z;
    for (const Strands* s : {&b, &moved})
        for (std::size_t i = 0; i + 1 < s->points.size(); ++i)
            if ((i + 1) % 9 != 0) length += glm::distance(s->points[i], s->points[i + 1]);
    EXPECT_NEAR(grid_length * bm.voxel * bm.voxel * bm.voxel, length, 1e-4 * length);
}

TEST(ShadowGrid, KeepsTheStrandsLength) {
    // Σ tr M · voxel³ = the total strand length, up to float rounding: every splat weight sums to 1 and the
    // grid has two voxels of margin on every side.
    const Strands s = straight_strands(50, 4.0f);
    const DensityGrid g = voxelize_strands(s, glm::mat3(1.0f), 32);
    double length = 0;
    for (int z = 0; z < g.dims.z; ++z)
        for (int y = 0; y < g.dims.y; ++y)
            for (int x = 0; x < g.dims.x; ++x) length += g.length_density(x, y, z);
    length *= static_cast<double>(g.voxel) * g.voxel * g.voxel;
    EXPECT_NEAR(length, 50 * 4.0, 1e-4 * 50 * 4.0);
    // At most the 32 asked for, and at least 26 / 2^(1/8) + 5 (the voxel is rounded up to the lattice's step).
    EXPECT_LE(std::max({g.dims.x, g.dims.y, g.dims.z}), 32);
    EXPECT_GE(std::max({g.dims.x, g.dims.y, g.dims.z}), 29);
}

TEST(ShadowGrid, LineIntegralsAcrossABundleCountItsStrands) {
    // Rays along x through a bundle of 100 strands along −y, at every z across it: ∫∫ projected dx dz over
    // the plane y = −2 is the number of strands crossing that plane (so 2r times a ray's integral is the
    // fibres of radius r it meets), up to the midpoint rules in x and z: 2 %.
    const Strands s = straight_strands(100, 4.0f);
    const DensityGrid g = voxelize_strands(s, glm::mat3(1.0f), 40);
    const auto across = [&](glm::vec3 d) {
        double sum = 0;
        const int nz = 200;
        for (int k = 0; k < nz; ++k) {
            const float z = g.origin.z + (k + 0.5f) * g.extent().z / nz;
            const glm::vec3 start(g.origin.x - d.x * 0.0f, -2.0f - d.y * 0.5f * g.extent().x / d.x, z);
            sum += g.integrate(start, d, g.extent().x / d.x, 0.25f * g.voxel) * g.extent().z / nz;
        }
        return sum;
    };
    EXPECT_NEAR(across(glm::vec3(1, 0, 0)), 100.0, 0.02 * 100.0);
    // A ray tilted by ψ from the fibres is longer across the bundle by 1/sin ψ and meets each fibre's
    // projected width 2r sin ψ: the count per plane is the same (3 %: the tilted ray samples more voxels
    // along y, where the bundle's ends are not in this plane).
    const float psi = 0.6f;
    EXPECT_NEAR(across(glm::vec3(std::sin(psi), -std::cos(psi), 0.0f)), 100.0, 0.03 * 100.0);
}

TEST(ShadowGrid, ProjectedDensityFollowsTheFibresDirection) {
    // Parallel fibres along −y of length density ρ: ρ |sin ψ| for a ray at ψ from them, exactly (the formula
    // is exact for parallel fibres), 0 along them.
    const glm::vec4 m(0.0f, 3.0f, 0.0f, 0.0f);
    const glm::vec2 o(0.0f);
    EXPECT_FLOAT_EQ(projected_length_density(m, o, glm::vec3(1, 0, 0)), 3.0f);
    EXPECT_NEAR(projected_length_density(m, o, glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    const float psi = 0.4f;
    EXPECT_NEAR(projected_length_density(m, o, glm::vec3(0, std::cos(psi), std::sin(psi))), 3.0f * std::sin(psi), 1e-5f);
    // Fibres along the diagonal (1, 1, 0)/√2 use the off-diagonal term: along them 0, across them ρ.
    const glm::vec4 md(1.5f, 1.5f, 0.0f, 1.5f);
    EXPECT_NEAR(projected_length_density(md, o, glm::normalize(glm::vec3(1, 1, 0))), 0.0f, 1e-3f);
    EXPECT_NEAR(projected_length_density(md, o, glm::vec3(0, 0, 1)), 3.0f, 1e-5f);
    // Isotropic fibres (M = ρ/3 I): the mean |sin ψ| is π/4; the formula gives √(2/3), 4 % high (the bound
    // the header states).
    const glm::vec4 mi(1.0f, 1.0f, 1.0f, 0.0f);
    const float iso = projected_length_density(mi, o, glm::vec3(0, 0, 1));
    EXPECT_NEAR(iso, 3.0f * std::sqrt(2.0f / 3.0f), 1e-5f);
    EXPECT_LT(iso / (3.0f * std::numbers::pi_v<float> / 4.0f), 1.04f);
}

TEST(ShadowGrid, SampleIsTrilinearAndZeroOutside) {
    const Strands s = straight_strands(10, 1.0f);
    const DensityGrid g = voxelize_strands(s, glm::mat3(1.0f), 16);
    ASSERT_GE(std::min({g.dims.x, g.dims.y, g.dims.z}), 4);
    // Strands along y: the projected density across them (along x) is the length density, trilinear.
    const glm::vec3 x(1, 0, 0);
    const glm::vec3 c = g.origin + glm::vec3(g.voxel) * (glm::vec3(2, 3, 1) + 0.5f);
    EXPECT_NEAR(g.projected(c, x), g.length_density(2, 3, 1), 1e-5f * g.length_density(2, 3, 1) + 1e-6f);
    const glm::vec3 mid = c + glm::vec3(0.5f * g.voxel, 0, 0);
    const float want = 0.5f * (g.length_density(2, 3, 1) + g.length_density(3, 3, 1));
    EXPECT_NEAR(g.projected(mid, x), want, 1e-5f * want + 1e-6f);
    EXPECT_EQ(g.projected(g.origin - glm::vec3(5.0f), x), 0.0f);
}

TEST(ShadowGrid, RefusesBadInput) {
    EXPECT_THROW(voxelize_strands(Strands{}, glm::mat3(1.0f), 32), Error);
    const Strands s = straight_strands(4, 1.0f);
    EXPECT_THROW(voxelize_strands(s, glm::mat3(1.0f), 7), Error);
    EXPECT_THROW(voxelize_strands(s, glm::mat3(1.0f), 100000), Error);
}

}  // namespace
}  // namespace coif
