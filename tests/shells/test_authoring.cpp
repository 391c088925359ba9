// The viewer's cluster authoring without a window (online/shells/authoring.h): one history for edits and strokes,
// restoring the style and the map exactly; a dragged control point follows the cursor in the plane facing the camera.
#include <gtest/gtest.h>

#include <cstdio>

#include "models/core/error.h"
#include "models/style_edit.h"
#include "online/shells/authoring.h"

namespace coif {
namespace {

HairStyle two() {
    return parse_style(R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 2, "s_t": 2, "s_u": 4, "grid": [2, 2], "mesh": [1, 1], "gaussian_width": 0.05},
      "clusters": [{"name": "left", "trajectory": [[-3, 0, 0], [-3, -5, 0], [-3, -10, 0]], "a": [1.0], "b": [1.0],
                    "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}},
                   {"name": "right", "trajectory": [[3, 0, 0], [3, -5, 0], [3, -10, 0]], "a": [1.0], "b": [1.0],
                    "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}}]})",
                       "<two>");
}

TEST(Authoring, EditsAndStrokesShareOneHistoryThatRestoresExactly) {
    Authoring a(two(), AbsorptionMap(2, 4, glm::vec3(1.0f)));
    const std::string start = style_text(*a.style());
    const std::uint64_t v0 = a.style_version();
    a.select({"right"});
    a.edit([](HairStyle& s, AbsorptionMap* map) { return mirror_clusters(s, std::vector<std::size_t>{1}, 0, 0.0, map); });
    EXPECT_EQ(a.style()->clusters.size(), 3u);
    EXPECT_EQ(a.map()->clusters, 3);
    EXPECT_EQ(a.selection(), std::vector<std::size_t>{2});  // the new cluster
    EXPECT_NE(a.style_version(), v0);
    // A stroke after it: the map changes, the style does not.
    a.begin_stroke();
    a.painting().replace(AbsorptionMap(3, 4, glm::vec3(2.0f)));
    const std::uint64_t v1 = a.style_version();
    ASSERT_TRUE(a.undo());  // the stroke: the style stays, the map is back
    EXPECT_EQ(a.style_version(), v1);
    EXPECT_EQ(a.map()->at(2, 0), glm::vec3(1.0f));
    ASSERT_TRUE(a.undo());  // the mirror
    EXPECT_EQ(style_text(*a.style()), start);
    EXPECT_EQ(a.map()->clusters, 2);
    EXPECT_TRUE(a.selection().empty());  // cluster 2 is gone
    EXPECT_FALSE(a.undo());
    ASSERT_TRUE(a.redo());
    ASSERT_TRUE(a.redo());
    EXPECT_EQ(a.style()->clusters.size(), 3u);
    EXPECT_EQ(a.map()->at(2, 0), glm::vec3(2.0f));
    // A failed edit changes nothing and adds no step.
    EXPECT_THROW(a.edit([](HairStyle& s, AbsorptionMap* map) {
        delete_clusters(s, std::vector<std::size_t>{0, 1, 2}, map);
        return std::vector<std::size_t>{};
    }), Error);
    EXPECT_EQ(a.style()->clusters.size(), 3u);
    EXPECT_FALSE(a.redo());
    // A baked asset is view-only.
    Authoring view_only(std::nullopt, std::nullopt);
    EXPECT_THROW(view_only.edit([](HairStyle&, AbsorptionMap*) { return std::vector<std::size_t>{}; }), Error);
    EXPECT_THROW(view_only.select({"left"}), Error);
}

TEST(Authoring, SymmetryModeMirrorsAnEditOntoThePartnerInTheSameUndoStep) {
    // left and right mirror each other across x = 0 (the middle of the roots).
    Authoring a(two(), std::nullopt);
    const std::string start = style_text(*a.style());
    const glm::dvec3 move(0.5, 0.25, 1.0);
    const auto point = [&](std::size_t c, std::size_t i) { return a.style()->clusters[c].shape->trajectory().control()[i]; };
    // Off: only the edited cluster moves.
    EXPECT_EQ(a.symmetric_partner(0), std::nullopt);
    a.edit_cluster(0, [&](HairStyle& s) { move_control_point(s, 0, 1, move); });
    EXPECT_EQ(point(1, 1), glm::dvec3(3, -5, 0));
    ASSERT_TRUE(a.undo());
    // On: the partner becomes the mirror image of the edited cluster, exactly (the file's rounding: 1e-9 here).
    a.set_symmetry(true);
    ASSERT_EQ(a.symmetric_partner(0), std::optional<std::size_t>(1));
    a.edit_cluster(0, [&](HairStyle& s) { move_control_point(s, 0, 1, move); });
    EXPECT_EQ(a.selection(), std::vector<std::size_t>{0});
    for (std::size_t i = 0; i < 3; ++i) {
        const glm::dvec3 l = point(0, i), r = point(1, i);
        EXPECT_LT(glm::distance(r, glm::dvec3(-l.x, l.y, l.z)), 1e-9) << i;
    }
    EXPECT_LT(glm::distance(point(1, 1), glm::dvec3(2.5, -4.75, 1.0)), 1e-9);
    EXPECT_EQ(a.symmetric_partner(1), std::optional<std::size_t>(0));  // still each other's, the other way too
    // One step: one undo puts both back.
    ASSERT_TRUE(a.undo());
    EXPECT_EQ(style_text(*a.style()), start);
    // A transform of the selection moves each partner that is not selected as the mirror image.
    a.edit_clusters({0}, [&](HairStyle& s) {
        transform_clusters(s, std::vector<std::size_t>{0}, similarity_about(s, std::vector<std::size_t>{0}, {-1, 0.5, 0}, {0, 0, 20}, 1.2));
    });
    for (std::size_t i = 0; i < 3; ++i) {
        const glm::dvec3 l = point(0, i), r = point(1, i);
        EXPECT_LT(glm::distance(r, glm::dvec3(-l.x, l.y, l.z)), 1e-9) << i;
    }
    EXPECT_NE(point(0, 2), glm::dvec3(-3, -10, 0));  // it moved
    ASSERT_TRUE(a.undo());
    EXPECT_EQ(style_text(*a.style()), start);
    // Both selected: each moves by the edit itself, neither is overwritten as the other's mirror.
    a.edit_clusters({0, 1}, [&](HairStyle& s) {
        transform_clusters(s, std::vector<std::size_t>{0, 1}, similarity_about(s, std::vector<std::size_t>{0, 1}, {0, 2, 0}, {0, 0, 0}, 1.0));
    });
    EXPECT_LT(glm::distance(point(0, 0), glm::dvec3(-3, 2, 0)), 1e-9);
    EXPECT_LT(glm::distance(point(1, 0), glm::dvec3(3, 2, 0)), 1e-9);
    ASSERT_TRUE(a.undo());
    // A cluster with no mirror image: the edit stays on its side.
    a.set_symmetry(false);
    a.edit_cluster(1, [&](HairStyle& s) { move_control_point(s, 1, 2, glm::dvec3(4, 0, 0)); });  // right no longer mirrors left
    a.set_symmetry(true);
    EXPECT_EQ(a.symmetric_partner(0), std::nullopt);
    const glm::dvec3 right_tip = point(1, 2);
    a.edit_cluster(0, [&](HairStyle& s) { move_control_point(s, 0, 0, move); });
    EXPECT_EQ(point(1, 2), right_tip);
}

TEST(Authoring, SymmetryModeDuplicatesAndDeletesThePartnerToo) {
    // left and right mirror each other across x = 0. With symmetry on, a copy of left gets its mirror image beside
    // right (the style stays symmetric), and deleting left deletes right too; each one undo step. Off: left alone.
    Authoring a(two(), AbsorptionMap(2, 4, glm::vec3(1.0f)));
    const std::string start = style_text(*a.style());
    const auto point = [&](std::size_t c, std::size_t i) {
        const Cluster& cl = a.style()->clusters[c];
        return cl.placement.apply(a.style()->clusters[cl.prototype].shape->trajectory().control()[i]);
    };
    a.duplicate({0}, true, {-1.0, 0.0, 0.5});
    ASSERT_EQ(a.style()->clusters.size(), 3u);
    EXPECT_EQ(a.selection(), std::vector<std::size_t>{2});
    ASSERT_TRUE(a.undo());
    a.set_symmetry(true);
    a.duplicate({0}, true, {-1.0, 0.0, 0.5});
    ASSERT_EQ(a.style()->clusters.size(), 4u);
    EXPECT_EQ(a.selection(), (std::vector<std::size_t>{2, 3}));
    EXPECT_EQ(a.map()->clusters, 4);  // the painted rows follow
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_LT(glm::distance(point(2, i), point(0, i) + glm::dvec3(-1.0, 0.0, 0.5)), 1e-9) << i;  // the copy, moved
        const glm::dvec3 l = point(2, i), r = point(3, i);
        EXPECT_LT(glm::distance(r, glm::dvec3(-l.x, l.y, l.z)), 1e-9) << i;  // its mirror image
    }
    // The copy deleted: its mirror image goes with it, back to the two clusters as they were.
    a.remove({2});
    EXPECT_EQ(style_text(*a.style()), start);
    EXPECT_TRUE(a.selection().empty());
    EXPECT_EQ(a.map()->clusters, 2);
    ASSERT_TRUE(a.undo());
    EXPECT_EQ(a.style()->clusters.size(), 4u);
    ASSERT_TRUE(a.undo());
    EXPECT_EQ(style_text(*a.style()), start);
    EXPECT_THROW(a.remove({0}), Error);  // left and its partner: nothing would remain
    EXPECT_EQ(style_text(*a.style()), start);
    a.set_symmetry(false);
    a.remove({0});
    ASSERT_EQ(a.style()->clusters.size(), 1u);
    EXPECT_EQ(a.style()->clusters[0].name, "right");
}

TEST(Authoring, AClusterIsAddedWhereTheCursorMeetsTheScalp) {
    // Roots on the sphere of radius 5 about the origin, symmetric across x = 0; the camera at (0, 0, 50) looks at it.
    std::string clusters;
    for (const glm::dvec3 r : {glm::dvec3(-3, 4, 0), glm::dvec3(3, 4, 0), glm::dvec3(-3, 0, 4), glm::dvec3(3, 0, 4),
                               glm::dvec3(-4, 0, -3), glm::dvec3(4, 0, -3), glm::dvec3(0, 5, 0)}) {
        char c[320];
        std::snprintf(c, sizeof c,
                      R"(%s{"name": "r%zu", "trajectory": [[%g, %g, %g], [%g, %g, %g]], "a": [1], "b": [1], "theta_deg": [0],
                          "density": {"kind": "uniform", "value": 0.5}})",
                      clusters.empty() ? "" : ", ", clusters.size(), r.x, r.y, r.z, r.x, r.y - 8, r.z);
        clusters += c;
    }
    Authoring a(parse_style(R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 2, "s_t": 2, "s_u": 4, "grid": [2, 2], "mesh": [1, 1], "gaussian_width": 0.05},
      "clusters": [)" + clusters + "]}",
                            "<scalp>"),
                AbsorptionMap(7, 2, glm::vec3(1.0f)));
    const std::string start = style_text(*a.style());
    Camera cam;
    const auto root = [&](std::size_t c) { return a.style()->clusters[c].shape->trajectory().control()[0]; };
    // The middle pixel's ray is the −z axis: it meets the sphere at (0, 0, 5), on the mirror plane, so symmetry mode
    // adds no mirror image there.
    a.set_symmetry(true);
    a.add(cam, glm::mat3(1.0f), 0.5 * cam.width, 0.5 * cam.height);
    ASSERT_EQ(a.style()->clusters.size(), 8u);
    EXPECT_LT(glm::distance(root(7), glm::dvec3(0, 0, 5)), 1e-4);  // float rays, the file's rounding
    EXPECT_EQ(a.selection(), std::vector<std::size_t>{7});
    EXPECT_EQ(a.map()->clusters, 8);
    // Right of the middle: a root on the sphere under that pixel, and its mirror image in the same step.
    a.add(cam, glm::mat3(1.0f), 0.5 * cam.width + 30, 0.5 * cam.height - 20);
    ASSERT_EQ(a.style()->clusters.size(), 10u);
    const glm::dvec3 r = root(8);
    EXPECT_NEAR(glm::length(r), 5.0, 1e-4);
    EXPECT_GT(r.x, 0.5);
    EXPECT_GT(r.y, 0.3);  // image y runs down
    glm::vec3 o, d;
    cam.ray(static_cast<float>(0.5 * cam.width + 30), static_cast<float>(0.5 * cam.height - 20), o, d);
    EXPECT_LT(glm::length(glm::cross(glm::dvec3(glm::normalize(d)), r - glm::dvec3(o))), 1e-3);  // on the pixel's ray
    EXPECT_LT(glm::distance(root(9), glm::dvec3(-r.x, r.y, r.z)), 1e-4);
    EXPECT_EQ(a.selection(), (std::vector<std::size_t>{8, 9}));
    // A ray that passes by: the sphere's point nearest it.
    a.set_symmetry(false);
    a.add(cam, glm::mat3(1.0f), 0.0, 0.5 * cam.height);
    EXPECT_NEAR(glm::length(root(10)), 5.0, 1e-4);
    EXPECT_LT(root(10).x, -4.0);
    cam.ray(0.0f, static_cast<float>(0.5 * cam.height), o, d);
    EXPECT_NEAR(glm::dot(glm::normalize(root(10)), glm::dvec3(glm::normalize(d))), 0.0, 1e-4);  // across the ray
    // Undone one step at a time, back to the style it was.
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(a.undo());
    EXPECT_EQ(style_text(*a.style()), start);
    EXPECT_EQ(a.map()->clusters, 7);
}

TEST(Authoring, ADraggedPointFollowsTheCursorInThePlaneFacingTheCameraOrAlongItsAxis) {
    Authoring a(two(), std::nullopt);
    Camera cam;  // at (0, 0, 50) looking at the origin, 720 × 480, 40°
    a.select({"right"});
    EXPECT_THROW(a.drag_point(cam, glm::mat3(1.0f), 7, {0, 0}, {1, 1}, -1), Error);  // 3 control points
    // Point 1, (3, −5, 0), lies in the plane z = 0, 50 from the eye: a pixel there is 2 · 50 · tan 20° / 480.
    const double pixel = 2.0 * 50.0 * std::tan(0.5 * cam.fov_y) / cam.height;
    a.drag_point(cam, glm::mat3(1.0f), 1, {400, 300}, {420, 290}, -1);
    const glm::dvec3 moved = a.style()->clusters[1].shape->trajectory().control()[1];
    EXPECT_NEAR(moved.x, 3.0 + 20 * pixel, 1e-3);
    EXPECT_NEAR(moved.y, -5.0 + 10 * pixel, 1e-3);  // image y runs down
    EXPECT_NEAR(moved.z, 0.0, 1e-4);
    // Locked to y, the horizontal part is dropped.
    a.drag_point(cam, glm::mat3(1.0f), 1, {400, 300}, {420, 290}, 1);
    const glm::dvec3 locked = a.style()->clusters[1].shape->trajectory().control()[1];
    EXPECT_NEAR(locked.x, moved.x, 1e-4);
    EXPECT_NEAR(locked.y, moved.y + 10 * pixel, 1e-3);
    // Two drags, two steps.
    ASSERT_TRUE(a.undo());
    ASSERT_TRUE(a.undo());
    EXPECT_EQ(a.style()->clusters[1].shape->trajectory().control()[1], glm::dvec3(3, -5, 0));
    a.select({"left", "right"});
    EXPECT_THROW(a.drag_point(cam, glm::mat3(1.0f), 1, {0, 0}, {1, 1}, -1), Error);  // one cluster at a time
}

}  // namespace
}  // namespace coif
