// Clusters outside the view are skipped (ShellSettings::cull, online/shells/prepared_shells.h box_in_view): the
// test of a box against a frustum, and a view of one cluster of two drawing one, with the same pixels as
// drawing both.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "models/style_edit.h"
#include "online/gl_context.h"
#include "online/scene/cook.h"
#include "online/shell_renderer.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

// A cube of half-size h about c.
ClusterBox cube(glm::vec3 c, float h) {
    ClusterBox b;
    for (int k = 0; k < 8; ++k) b[static_cast<std::size_t>(k)] = c + h * glm::vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
    return b;
}

TEST(Culling, ABoxIsInTheViewUnlessWhollyBeyondAPlane) {
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 10), glm::vec3(0), glm::vec3(0, 1, 0));
    const glm::mat4 projection = glm::perspective(glm::radians(40.0f), 1.5f, 0.1f, 100.0f);
    const glm::mat4 vp = projection * view;
    EXPECT_TRUE(box_in_view(vp, cube(glm::vec3(0, 0, 0), 1)));       // in front
    EXPECT_FALSE(box_in_view(vp, cube(glm::vec3(0, 0, 20), 1)));     // behind the eye
    EXPECT_FALSE(box_in_view(vp, cube(glm::vec3(30, 0, 0), 1)));     // far to the right
    EXPECT_TRUE(box_in_view(vp, cube(glm::vec3(5, 0, 0), 2)));       // straddling the right plane
    EXPECT_FALSE(box_in_view(vp, cube(glm::vec3(0, 0, -200), 1)));   // beyond the far plane
    // A [0, w] depth range (glClipControl, reversed Z): z' = (z + w)/2 keeps the side planes and culls nothing
    // more.
    const glm::mat4 half_depth = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(1, 1, 0.5f));
    EXPECT_TRUE(box_in_view(half_depth * vp, cube(glm::vec3(0, 0, 0), 1)));
    EXPECT_FALSE(box_in_view(half_depth * vp, cube(glm::vec3(30, 0, 0), 1)));
}

TEST(Culling, AViewOfOneClusterDrawsOneWithTheSamePixels) {
    auto context = gl::Context::headless();
    gl::ShellRenderer r(cook_shells(test::prototype_and_instance(), test::test_index(), glm::mat3(1.0f)));
    r.set_lights(test::two_lights());
    // Close to the first cluster (x = 0), looking at it along −z: the instance at x = 5 is outside a narrow view.
    Camera camera;
    camera.eye = glm::vec3(0.0f, -5.0f, 8.0f);
    camera.target = glm::vec3(0.0f, -5.0f, 0.0f);
    camera.fov_y = glm::radians(20.0f);
    camera.width = 64;
    camera.height = 96;
    gl::ShellSettings s;
    s.samples = 1;
    const Image culled = r.render(camera, s);
    EXPECT_EQ(r.timings().clusters_drawn, 1u);
    s.cull = false;
    const Image all = r.render(camera, s);
    EXPECT_EQ(r.timings().clusters_drawn, 2u);
    double sum = 0;
    for (float v : all.pixels) sum += v;
    ASSERT_GT(sum, 0.0) << "the hair must show";
    // No tolerance: the skipped cluster makes no fragment.
    EXPECT_EQ(culled.pixels, all.pixels);
    // From far away both show, and both are drawn.
    s.cull = true;
    (void)r.render(Camera::orbit(r.bounds_min(), r.bounds_max(), 0.3f, 0.2f, 64, 48), s);
    EXPECT_EQ(r.timings().clusters_drawn, 2u);
}

TEST(Culling, AHairGivenAgainIsCulledByItsOwnBoxes) {
    // set_hair keeps the renderer (its programs and passes): the boxes it culls by must be the new hair's, though the
    // counts of clusters and prototypes are the same (an edit that moves a cluster).
    auto context = gl::Context::headless();
    HairStyle style = test::two_cluster_style();
    gl::ShellRenderer r(cook_shells(style, test::test_index(), glm::mat3(1.0f)));
    r.set_lights(test::two_lights());
    gl::ShellSettings s;
    s.samples = 1;
    (void)r.render(Camera::orbit(r.bounds_min(), r.bounds_max(), 0.3f, 0.2f, 64, 48), s);  // the boxes made
    move_control_point(style, 1, 0, {27, 0, 0});  // "right" from x = 3 to x = 30
    move_control_point(style, 1, 1, {27, 0, 0});
    move_control_point(style, 1, 2, {27, 0, 0});
    r.set_hair(cook_shells(style, test::test_index(), glm::mat3(1.0f)));
    Camera camera;  // narrowly at the moved cluster, far from where it was
    camera.eye = glm::vec3(30.0f, -5.0f, 8.0f);
    camera.target = glm::vec3(30.0f, -5.0f, 0.0f);
    camera.fov_y = glm::radians(20.0f);
    camera.width = 64;
    camera.height = 96;
    s.background = glm::vec3(0.0f);
    const Image image = r.render(camera, s);
    EXPECT_EQ(r.timings().clusters_drawn, 1u);
    double sum = 0;  // the colour over black (not the alpha channel, 1 everywhere)
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) sum += image.at(x, y)[c];
    EXPECT_GT(sum, 0.0) << "the moved cluster must show";
}

}  // namespace
}  // namespace coif
