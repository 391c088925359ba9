// Picking the shells under a pixel (online/shells/shell_pick.h) and painting absorption with it
// (online/shells/painting.h): a ray through the hair meets its outer layer at the right t, one that misses meets
// nothing, a dab changes only the columns under it, and strokes undo and redo exactly (in the authoring's history,
// online/shells/authoring.h, which is the painting's).
#include <gtest/gtest.h>

#include "online/scene/cook.h"
#include "online/shells/authoring.h"
#include "online/shells/painting.h"
#include "online/shells/shell_pick.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

const CookedShells& cooked() {
    static const CookedShells c = cook_shells(test::one_cluster_style(), test::test_index(), glm::mat3(1.0f));
    return c;
}

TEST(ShellPick, ARayThroughTheHairMeetsItsOuterLayerAtItsT) {
    const PreparedShells& p = cooked().shells;
    const glm::vec3 lo = p.bounds_min, hi = p.bounds_max, centre = 0.5f * (lo + hi);
    // Straight at the middle of the cluster from far in front (+z): the outer layer, t near the middle.
    const auto hit = pick_shells(p, centre + glm::vec3(0.0f, 0.0f, 100.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->cluster, 0);
    EXPECT_NEAR(hit->t, 0.5f, 0.1f);
    EXPECT_GT(hit->distance, 100.0f - (hi.z - centre.z) - 1e-3f);
    EXPECT_LE(hit->distance, 100.0f);
    // Beside the box: nothing. Backwards: nothing (the hair is behind the origin).
    EXPECT_FALSE(pick_shells(p, hi + glm::vec3(10.0f, 0.0f, 100.0f), glm::vec3(0.0f, 0.0f, -1.0f)).has_value());
    EXPECT_FALSE(pick_shells(p, centre + glm::vec3(0.0f, 0.0f, 100.0f), glm::vec3(0.0f, 0.0f, 1.0f)).has_value());
}

TEST(Painting, ADabChangesTheColumnsUnderItAndStrokesUndoExactly) {
    const PreparedShells& p = cooked().shells;
    const Camera camera = Camera::orbit(p.bounds_min, p.bounds_max, 0.0f, 0.0f, 96, 64);
    const glm::vec3 base(0.4f, 0.6f, 1.0f);
    Authoring history(std::nullopt, std::nullopt);  // the strokes' history; painting needs no style
    Painting& painting = history.painting();
    EXPECT_EQ(painting.map(), nullptr);
    Brush brush;
    brush.radius = 3;
    brush.strength = 1;
    brush.sigma_a = glm::vec3(8.0f);
    history.begin_stroke();
    ASSERT_TRUE(painting.dab(camera, p, 48, 32, brush, base));  // the image's centre: the hair
    ASSERT_NE(painting.map(), nullptr);
    const AbsorptionMap& m = *painting.map();
    EXPECT_EQ(m.clusters, 1);
    EXPECT_EQ(m.samples, Painting::kSamples);
    int changed = 0;
    for (int i = 0; i < m.samples; ++i) changed += m.at(0, i) != base;
    EXPECT_GT(changed, 0);
    EXPECT_LT(changed, m.samples / 2) << "a 3-pixel dab paints a few columns, not the cluster";
    EXPECT_EQ(m.at(0, 0), base) << "the root is far from the dab";
    const AbsorptionMap painted = m;
    // A dab beside the hair meets nothing and changes nothing.
    history.begin_stroke();
    EXPECT_FALSE(painting.dab(camera, p, 1, 1, brush, base));
    EXPECT_EQ(painting.map()->sigma_a, painted.sigma_a);
    // Undo twice: unpainted again; redo: the painted map, exactly.
    EXPECT_TRUE(history.undo());
    EXPECT_TRUE(history.undo());
    EXPECT_EQ(painting.map(), nullptr);
    EXPECT_FALSE(history.undo());
    EXPECT_TRUE(history.redo());
    ASSERT_NE(painting.map(), nullptr);
    EXPECT_EQ(painting.map()->sigma_a, painted.sigma_a);
    // Clearing is a stroke too.
    history.clear_paint();
    EXPECT_EQ(painting.map(), nullptr);
    EXPECT_TRUE(history.undo());
    EXPECT_EQ(painting.map()->sigma_a, painted.sigma_a);
}

}  // namespace
}  // namespace coif
