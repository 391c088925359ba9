// Sector density fields (004 §3.3) and density features (004 §5.2).
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>

#include "models/hair_style.h"
#include "models/sector_density.h"
#include "models/sector_features.h"

namespace coif {
namespace {

constexpr double kPi = std::numbers::pi;

// ∫_0^W exp(−(s − x)²/λ²) ds: the exact integral of one Gaussian cut by the sector's edges.
double cut_integral(double x, double W, double lambda) {
    return 0.5 * std::sqrt(kPi) * lambda * (std::erf((W - x) / lambda) + std::erf(x / lambda));
}

TEST(SectorDensity, IntegralIsStrandCountTimesGaussianIntegral) {
    const double W = 2.0, D = 1.0, lambda = 0.06;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> S(4 * lambda, W - 4 * lambda), R(4 * lambda, D - 4 * lambda);
    std::vector<glm::dvec2> pts;
    for (int i = 0; i < 25; ++i) pts.emplace_back(S(rng), R(rng));
    const SectorDensity d = density_from_points(80, 40, W, D, pts, lambda);
    const double expected = pts.size() * kPi * lambda * lambda;  // 2D ∫exp(−|x|²/λ²) = πλ²
    std::printf("density integral %.9f, strands x pi lambda^2 = %.9f (rel. error %.2e)\n", d.integral(), expected,
                std::abs(d.integral() / expected - 1));
    // Gaussians at least 4λ from every edge: the cut loses e^-16 ≈ 1e-7; the midpoint rule on a grid of
    // h = 0.42λ is exact to exp(−π²λ²/h²) ≈ 1e-25; float accumulation ~1e-6. Tolerance 1e-5.
    EXPECT_NEAR(d.integral() / expected, 1.0, 1e-5);
}

TEST(SectorDensity, IntegralWithStrandsNearAndBeyondTheEdges) {
    const double W = 1.0, D = 0.5, lambda = 0.05;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> S(-0.1, W + 0.1), R(-0.1, D + 0.1);
    std::vector<glm::dvec2> pts;
    for (int i = 0; i < 40; ++i) pts.emplace_back(S(rng), R(rng));
    double expected = 0;
    for (const auto& p : pts) expected += cut_integral(p.x, W, lambda) * cut_integral(p.y, D, lambda);
    for (int n : {10, 20, 40, 80}) {
        const SectorDensity d = density_from_points(2 * n, n, W, D, pts, lambda);
        const double h = D / n, err = std::abs(d.integral() / expected - 1);
        std::printf("grid %3d x %3d (h/lambda %.2f): integral %.6f vs exact %.6f, rel. error %.2e\n", 2 * n, n, h / lambda,
                    d.integral(), expected, err);
        // The midpoint rule on Gaussians cut at the edges errs by O(h²): ≤ (h/λ)²/24 of the integral
        // (the second-derivative bound of the midpoint rule, |g''| ≤ 2/λ² near the edge), plus 1e-6.
        EXPECT_LT(err, (h / lambda) * (h / lambda) / 24 + 1e-6) << n;
    }
}

TEST(SectorDensity, ClusterSectorsFromUniformSource) {
    // A uniform density source fills every sector with its value; the integral is value × area.
    const GeneralizedCylinder c(Spline3({{0, 0, 0}, {0, -5, 0}}), Spline1({1.0}), Spline1({0.6}), Spline1({0.0}));
    DiskLayout layout;
    DensitySource src;
    src.value = 0.75;
    const std::vector<SectorDensity> grids = cluster_sector_densities(c, layout, src);
    ASSERT_EQ(grids.size(), layout.sector_count());
    for (const SectorDensity& d : grids) {
        EXPECT_EQ(d.n_s, layout.grid_s);
        EXPECT_EQ(d.n_r, layout.grid_r);
        EXPECT_NEAR(d.integral(), 0.75 * d.width * d.depth, 1e-6);
    }
}

TEST(SectorDensity, ClusterSectorsFromStrandCrossings) {
    // One strand crossing plane 3 in the middle of sector (layer 1, sector 2): that sector's integral
    // is πλ². λ = two cells of the larger extent, so the Gaussian is resolved (h/λ ≤ 0.5: midpoint
    // rule exact to e^-39) and lies ≥ 4λ inside the sector (cut e^-16).
    const GeneralizedCylinder c(Spline3({{0, 0, 0}, {0, -5, 0}}), Spline1({1.0}), Spline1({1.0}), Spline1({0.0}));
    DiskLayout layout;
    layout.grid_s = 64;
    layout.grid_r = 64;
    const SectorShape sh = sector_shape(c, layout, 3, 1, 2);
    layout.gaussian_width = 2 * std::max(sh.width, sh.depth) / 64;
    ASSERT_LT(4 * layout.gaussian_width, 0.5 * std::min(sh.width, sh.depth));
    DensitySource src;
    src.kind = DensitySource::Kind::Strands;
    StrandRun run;
    run.first_plane = 3;
    run.vu = {{0.5 * (sh.v0 + sh.v1), 0.5 * (sh.u0 + sh.u1)}};
    src.strands = {run};
    const std::vector<SectorDensity> grids = cluster_sector_densities(c, layout, src);
    const double lambda = layout.gaussian_width;
    EXPECT_NEAR(grids[layout.sector_index(3, 1, 2)].integral(), kPi * lambda * lambda, 1e-5 * kPi * lambda * lambda);
    EXPECT_EQ(grids[layout.sector_index(2, 1, 2)].integral(), 0.0);  // other planes see nothing
    EXPECT_EQ(grids[layout.sector_index(3, 0, 2)].integral(), 0.0);
}

TEST(DensityFeatures, PaperFeaturesAsWrittenRepeatTheMean) {
    const SectorDensity d = density_from_function(8, 4, 1.0, 0.5, [](double s, double r) { return s * s + 3 * r; });
    const auto f = paper_features(d);
    // 004 §5.2 read literally: the means of the projected histograms equal the mean density (1e-6, float).
    EXPECT_NEAR(f[0], d.mean(), 1e-6);
    EXPECT_NEAR(f[1], f[0], 1e-6);
    EXPECT_NEAR(f[2], f[0], 1e-6);
}

TEST(DensityFeatures, RichFeaturesSeeWhereTheHairIs) {
    const SectorDensity uniform = density_from_function(8, 4, 1.0, 0.5, [](double, double) { return 2.0; });
    auto f = rich_features(uniform);
    EXPECT_NEAR(f[kMeanDensity], 2.0, 1e-6);
    EXPECT_NEAR(f[kCentroidS], 0.5, 1e-6);
    EXPECT_NEAR(f[kCentroidR], 0.5, 1e-6);
    EXPECT_NEAR(f[kSpreadS], 1 / std::sqrt(12.0), 1e-6);  // a uniform distribution on [0, 1]
    EXPECT_NEAR(f[kSpreadR], 1 / std::sqrt(12.0), 1e-6);
    for (int b = 0; b < 4; ++b) EXPECT_NEAR(f[kBinS0 + b], 2.0, 1e-6);

    // ρ = r: centroid Σx²/Σx over cell centres (1/8, 3/8, 5/8, 7/8) = 0.65625; bins follow r.
    const SectorDensity ramp = density_from_function(8, 4, 1.0, 0.5, [](double, double r) { return r; });
    f = rich_features(ramp);
    EXPECT_NEAR(f[kCentroidR], 0.65625, 1e-6);
    EXPECT_NEAR(f[kCentroidS], 0.5, 1e-6);
    EXPECT_LT(f[kBinR0], f[kBinR0 + 1]);
    EXPECT_LT(f[kBinR0 + 2], f[kBinR0 + 3]);

    // Hair only in the first quarter of the track: the mean cannot tell it from a thin uniform field,
    // the rich vector can.
    const SectorDensity left = density_from_function(8, 4, 1.0, 0.5, [](double s, double) { return s < 0.25 ? 4.0 : 0.0; });
    const SectorDensity thin = density_from_function(8, 4, 1.0, 0.5, [](double, double) { return 1.0; });
    EXPECT_NEAR(paper_features(left)[0], paper_features(thin)[0], 1e-6);
    f = rich_features(left);
    EXPECT_NEAR(f[kCentroidS], 0.125, 1e-6);
    EXPECT_NEAR(f[kBinS0], 4.0, 1e-6);
    EXPECT_NEAR(f[kBinS0 + 1], 0.0, 1e-6);
    // Instances scale a sector's extents, not its density.
    const SectorDensity big = left.scaled(2.0);
    EXPECT_DOUBLE_EQ(big.width, 2.0);
    EXPECT_NEAR(big.integral(), 4 * left.integral(), 1e-9);
}

TEST(DensityFeatures, SectorRowsAreEachSectorsRawFeaturesAtItsOwnShape) {
    // The rows the cook looks up and `coif db coverage` measures: per sector, raw_sector_features at its depth over λ and
    // its width over depth, one block of kRawFeatureCount after another, exactly.
    const double lambda = 0.25;
    const std::vector<SectorDensity> sectors = {
        density_from_function(8, 4, 1.0, 0.5, [](double s, double r) { return s + r; }),
        density_from_function(8, 4, 2.0, 0.25, [](double, double) { return 3.0; })};
    const std::vector<float> rows = sector_feature_rows(sectors, lambda);
    ASSERT_EQ(rows.size(), 2u * kRawFeatureCount);
    for (std::size_t k = 0; k < sectors.size(); ++k) {
        const RawFeatures f = raw_sector_features(sectors[k], sectors[k].depth / lambda, sectors[k].width / sectors[k].depth);
        for (int c = 0; c < kRawFeatureCount; ++c) EXPECT_EQ(rows[k * kRawFeatureCount + c], f[c]) << k << ", " << c;
    }
    // The two shape columns tell the sectors apart (the density alone does not: 004 §5.2's size in λ).
    EXPECT_NE(rows[kShapeColumn0], rows[kRawFeatureCount + kShapeColumn0]);
    EXPECT_TRUE(sector_feature_rows({}, lambda).empty());
}

}  // namespace
}  // namespace coif
