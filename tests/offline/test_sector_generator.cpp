// Random generalized sectors (offline/sector_generator.h): determinism and ranges.
#include <gtest/gtest.h>

#include "models/sector_features.h"
#include "offline/sector_generator.h"

namespace {

TEST(SectorGenerator, SameSeedAndIndexGiveTheSameSector) {
    const coif::SectorRanges g;
    for (std::uint64_t i : {0ull, 1ull, 999ull}) {
        const auto a = coif::generate_sector(g, 42, i), b = coif::generate_sector(g, 42, i);
        EXPECT_EQ(a.strands, b.strands);
        EXPECT_EQ(a.trace_grid.rho, b.trace_grid.rho);
        EXPECT_EQ(a.feature_grid.rho, b.feature_grid.rho);
    }
    EXPECT_NE(coif::generate_sector(g, 42, 1).trace_grid.rho, coif::generate_sector(g, 42, 2).trace_grid.rho);
    EXPECT_NE(coif::generate_sector(g, 42, 1).trace_grid.rho, coif::generate_sector(g, 43, 1).trace_grid.rho);
}

TEST(SectorGenerator, SamplesStayInTheirRanges) {
    const coif::SectorRanges g;
    for (std::uint64_t i = 0; i < 200; ++i) {
        const auto s = coif::generate_sector(g, 5, i);
        EXPECT_GE(s.params.depth, g.depth_min);
        EXPECT_LE(s.params.depth, g.depth_max);
        EXPECT_GE(s.params.width / s.params.depth, g.aspect_min * (1 - 1e-12));
        EXPECT_LE(s.params.width / s.params.depth, g.aspect_max * (1 + 1e-12));
        for (const auto& x : s.strands) {
            EXPECT_GE(x.x, 0.0);
            EXPECT_LT(x.x, s.params.width);
            EXPECT_GE(x.y, 0.0);
            EXPECT_LE(x.y, s.params.depth);
        }
        EXPECT_EQ(s.feature_grid.n_s, g.feature_grid_s);
        EXPECT_EQ(s.feature_grid.n_r, g.feature_grid_r);
    }
}

TEST(SectorGenerator, DensityIsPeriodicAlongTheTrack) {
    // A single strand on the seam s = 0 puts equal density into the first and the last columns
    // (cell centres ½ cell either side of the seam): tolerance 1e-6 of the peak.
    const std::vector<glm::dvec2> one{{0.0, 1.5}};
    const auto d = coif::periodic_density(10, 6, 5.0, 3.0, one);
    for (int r = 0; r < d.n_r; ++r) EXPECT_NEAR(d.at(0, r), d.at(d.n_s - 1, r), 1e-6);
}

TEST(SectorGenerator, FeatureSetsPickTheirColumns) {
    EXPECT_EQ(coif::feature_columns(coif::FeatureSet::Paper).size(), 3u);
    EXPECT_EQ(coif::feature_columns(coif::FeatureSet::RichShape).size(), static_cast<std::size_t>(coif::kRichFeatureCount + 2));
    EXPECT_EQ(coif::raw_feature_names().size(), static_cast<std::size_t>(coif::kRawFeatureCount));
    for (auto s : coif::kAllFeatureSets) EXPECT_EQ(coif::feature_set_from_name(coif::feature_set_name(s)), s);
}

TEST(SectorGenerator, BandConfinesTheStrands) {
    // With p_band = 1 every strand lies in the r band (exact: the map is affine, tolerance 1e-9 λ for rounding).
    coif::SectorRanges g;
    g.band_probability = 1;
    for (std::uint64_t i = 0; i < 100; ++i) {
        const auto s = coif::generate_sector(g, 11, i);
        ASSERT_TRUE(s.params.band);
        const double lo = s.params.band_outer ? (1 - s.params.band_r) * s.params.depth : 0.0;
        const double hi = lo + s.params.band_r * s.params.depth;
        for (const auto& x : s.strands) {
            EXPECT_GE(x.y, lo - 1e-9);
            EXPECT_LE(x.y, hi + 1e-9);
        }
    }
}

TEST(SectorGenerator, HeadersWithoutTheNewFieldsReadAsTheOldGenerator) {
    // Files written before the band and the non-periodic feature grid regenerate their own sectors.
    nlohmann::json j = coif::to_json(coif::SectorRanges{});
    j.erase("band_probability");
    j.erase("band_fraction");
    j.erase("feature_grid_periodic");
    const coif::SectorRanges old = coif::sector_ranges_from_json(j);
    EXPECT_EQ(old.band_probability, 0.0);
    EXPECT_TRUE(old.feature_grid_periodic);
    const auto s = coif::generate_sector(old, 3, 7);
    EXPECT_FALSE(s.params.band);
    EXPECT_EQ(s.feature_grid.rho, coif::periodic_density(old.feature_grid_s, old.feature_grid_r, s.params.width, s.params.depth, s.strands).rho);
    // And the current defaults round-trip.
    const coif::SectorRanges now = coif::sector_ranges_from_json(coif::to_json(coif::SectorRanges{}));
    EXPECT_EQ(now.band_probability, coif::SectorRanges{}.band_probability);
    EXPECT_FALSE(now.feature_grid_periodic);
}

}  // namespace
