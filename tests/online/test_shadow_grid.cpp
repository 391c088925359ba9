// The optical-density grid of the shell renderer's shadows between clusters (online/shells/shadow_grid.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "models/core/error.h"
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

TEST(ShadowGrid, TangentSpreadIsTheRmsAngleAboutTheLocalDirection) {
    // Parallel straight strands: every segment along its cell's mean, spread 0 (float rounding: 1e-3 rad).
    EXPECT_NEAR(strand_tangent_spread(straight_strands(50, 2.0f), 0.5f), 0.0f, 1e-3f);
    // Zigzags of ±δ about -y, both senses in every cell with segments of equal length: the cell means lie
    // along -y, so every segment is δ off and the RMS is δ (2e-3 rad: a cell may hold one more segment of
    // one sense than the other, tilting its mean a little).
    const float delta = 0.35f;
    Strands z;
    z.offsets.push_back(0);
    for (int i = 0; i < 20; ++i) {
        glm::vec3 p(0.05f * float(i), 0.0f, 0.0f);
        for (int k = 0; k <= 400; ++k) {
            z.points.push_back(p);
            const float s = (k % 2 == 0) ? 1.0f : -1.0f;
            p += 0.01f * glm::vec3(s * std::sin(delta), -std::cos(delta), 0.0f);
        }
        z.offsets.push_back(static_cast<std::uint32_t>(z.points.size()));
    }
    EXPECT_NEAR(strand_tangent_spread(z, 0.25f), delta, 2e-3f);
    EXPECT_THROW(strand_tangent_spread(z, 0.0f), Error);
    EXPECT_THROW(strand_tangent_spread(z, std::nanf("")), Error);
}

TEST(ShadowGrid, KeepsTheStrandsOpticalMass) {
    // Σ values · voxel³ = π λ · total strand length, exactly up to float rounding: every splat weight
    // sums to 1 and the grid has two voxels of margin on every side.
    const Strands s = straight_strands(50, 4.0f);
    const double lambda = 0.05;
    const DensityGrid g = voxelize_strands(s, glm::mat3(1.0f), lambda, 32);
    double mass = 0;
    for (float v : g.values) mass += v;
    mass *= static_cast<double>(g.voxel) * g.voxel * g.voxel;
    const double want = std::numbers::pi * lambda * 50 * 4.0;
    EXPECT_NEAR(mass, want, 1e-4 * want);
    EXPECT_EQ(std::max({g.dims.x, g.dims.y, g.dims.z}), 32);
}

TEST(ShadowGrid, LineIntegralsAcrossABundleAddUpToItsMass) {
    // Rays along x through a bundle of 100 strands along −y, at every z across it: ∫∫ value dx dz over
    // the plane y = −2 is π λ × the strands crossing that plane (what a shadow ray integrates, summed
    // over a ray family), up to the midpoint rules in x and z: 2 %.
    const Strands s = straight_strands(100, 4.0f);
    const double lambda = 0.05;
    const DensityGrid g = voxelize_strands(s, glm::mat3(1.0f), lambda, 40);
    double over_z = 0;
    const int nz = 200;
    for (int k = 0; k < nz; ++k) {
        const float z = g.origin.z + (k + 0.5f) * g.extent().z / nz;
        over_z += g.integrate(glm::vec3(g.origin.x, -2.0f, z), glm::vec3(1, 0, 0), g.extent().x, 0.25f * g.voxel) *
                  g.extent().z / nz;
    }
    const double want = std::numbers::pi * lambda * 100;
    EXPECT_NEAR(over_z, want, 0.02 * want);
}

TEST(ShadowGrid, SampleIsTrilinearAndZeroOutside) {
    const Strands s = straight_strands(10, 1.0f);
    const DensityGrid g = voxelize_strands(s, glm::mat3(1.0f), 0.05, 16);
    ASSERT_GE(std::min({g.dims.x, g.dims.y, g.dims.z}), 4);
    const glm::vec3 c = g.origin + glm::vec3(g.voxel) * (glm::vec3(2, 3, 1) + 0.5f);
    EXPECT_FLOAT_EQ(g.sample(c), g.at(2, 3, 1));
    const glm::vec3 mid = c + glm::vec3(0.5f * g.voxel, 0, 0);
    EXPECT_NEAR(g.sample(mid), 0.5f * (g.at(2, 3, 1) + g.at(3, 3, 1)), 1e-6f);
    EXPECT_EQ(g.sample(g.origin - glm::vec3(5.0f)), 0.0f);
}

TEST(ShadowGrid, RefusesBadInput) {
    EXPECT_THROW(voxelize_strands(Strands{}, glm::mat3(1.0f), 0.05, 32), Error);
    const Strands s = straight_strands(4, 1.0f);
    EXPECT_THROW(voxelize_strands(s, glm::mat3(1.0f), 0.0, 32), Error);
    EXPECT_THROW(voxelize_strands(s, glm::mat3(1.0f), std::nan(""), 32), Error);
    EXPECT_THROW(voxelize_strands(s, glm::mat3(1.0f), 0.05, 7), Error);
    EXPECT_THROW(voxelize_strands(s, glm::mat3(1.0f), 0.05, 100000), Error);
}

}  // namespace
}  // namespace coif
