// Follow strands (models/follow_strands.h): guides filled with followers as AMD TressFX makes them.
#include <gtest/gtest.h>

#include <cmath>

#include "models/core/error.h"
#include "models/follow_strands.h"
#include "models/style_fit.h"

namespace coif {
namespace {

// A row of 20 guides 1 apart along x, hanging along −y in 9 points, the first segment straight down.
Strands row() {
    Strands s;
    for (int i = 0; i < 20; ++i) {
        std::vector<glm::vec3> p;
        for (int k = 0; k < 9; ++k) p.push_back({static_cast<float>(i), -static_cast<float>(k), 0.1f * static_cast<float>(k * (k - 1))});
        s.add_strand(p);
    }
    s.thickness.assign(s.points.size(), 0.5f);
    return s;
}

TEST(FollowStrands, EachGuideKeepsItselfAndGetsFollowersOffsetAcrossItsRootWideningToTheTip) {
    const Strands guides = row();
    FollowOptions o;
    o.strands_per_guide = 8;
    o.tip_separation = 2.0;
    std::vector<std::uint32_t> guide_of;
    double r = 0;
    const Strands f = follow_strands(guides, o, &guide_of, &r);
    EXPECT_NO_THROW(f.validate("follow"));
    ASSERT_EQ(f.strand_count(), 8 * guides.strand_count());
    ASSERT_EQ(guide_of.size(), f.strand_count());
    EXPECT_DOUBLE_EQ(r, 1.0);  // the median root spacing of the row
    EXPECT_EQ(f.thickness.size(), f.points.size());
    double sum_sq = 0;
    int followers = 0;
    for (std::size_t s = 0; s < f.strand_count(); ++s) {
        const std::size_t g = guide_of[s];
        ASSERT_EQ(g, s / 8);
        ASSERT_EQ(f.point_count(s), 9u);
        const glm::vec3 o0 = f.points[f.offsets[s]] - guides.points[guides.offsets[g]];
        if (s % 8 == 0) {  // the guide itself, unchanged
            for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(f.points[f.offsets[s] + k], guides.points[guides.offsets[g] + k]);
            continue;
        }
        // Across the root (the first segment is along −y), within r, and widened by 1 + 2 k / 9 at point k.
        EXPECT_NEAR(o0.y, 0.0f, 1e-6f);
        EXPECT_LE(glm::length(o0), 1.0f + 1e-5f);
        for (std::size_t k = 0; k < 9; ++k) {
            const glm::vec3 ok = f.points[f.offsets[s] + k] - guides.points[guides.offsets[g] + k];
            EXPECT_NEAR(glm::distance(ok, (1.0f + 2.0f * static_cast<float>(k) / 9.0f) * o0), 0.0f, 1e-5f) << s << ", " << k;
        }
        sum_sq += glm::dot(o0, o0);
        ++followers;
    }
    // Uniform in the disc: E|o|² = r²/2. 140 followers: the mean's standard error is 0.024 (|o|² uniform on [0, 1]),
    // so 0.1 is four of them.
    EXPECT_NEAR(sum_sq / followers, 0.5, 0.1);
    // The same seed draws the same followers, another seed others; one strand per guide is the guides.
    EXPECT_EQ(follow_strands(guides, o).points, f.points);
    FollowOptions other = o;
    other.seed = 2;
    EXPECT_NE(follow_strands(guides, other).points, f.points);
    FollowOptions one;
    EXPECT_EQ(follow_strands(guides, one).points, guides.points);
}

TEST(FollowStrands, BadOptionsAreRefusedNamingThem) {
    const Strands guides = row();
    for (const int n : {0, -1, kMaxStrandsPerGuide + 1}) {
        FollowOptions o;
        o.strands_per_guide = n;
        EXPECT_THROW(follow_strands(guides, o), Error) << n;
    }
    FollowOptions o;
    o.radius = -1;
    EXPECT_THROW(follow_strands(guides, o), Error);
    o.radius = std::nan("");
    EXPECT_THROW(follow_strands(guides, o), Error);
    o.radius = 0;
    o.tip_separation = std::numeric_limits<double>::infinity();
    try {
        (void)follow_strands(guides, o);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("tip separation"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace coif
