// Moving hair (ShellRenderer::set_cluster_transforms, set_shadow_grid; online/scene/hair_motion.h): the rest pose draws
// the cooked image, a rigid motion of the hair with its lights is the camera moved the other way, and a skinned pose moves
// each cluster with its bone and the body with it.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "models/character.h"
#include "models/skinning.h"
#include "models/style_strands.h"
#include "online/gl_context.h"
#include "online/scene/cook.h"
#include "online/scene/hair_motion.h"
#include "online/shell_renderer.h"
#include "online/shells/shadow_grid.h"
#include "tests/common/images.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

using test::max_difference;
using test::skinned_head;

struct Scene {
    std::unique_ptr<gl::Context> context = gl::Context::headless();
    HairStyle style = test::two_cluster_style(true);
    gl::ShellRenderer renderer{cook_shells(style, test::test_index(), glm::mat3(1.0f))};
    Camera camera = Camera::orbit(renderer.bounds_min(), renderer.bounds_max(), 0.4f, 0.2f, 120, 96);
    Scene() { renderer.set_lights(test::two_lights()); }
};

TEST(Motion, TheRestPoseDrawsTheCookedImage) {
    Scene sc;
    const BodyMesh head = skinned_head();
    sc.renderer.set_body(&head);
    gl::ShellSettings s;
    s.samples = 1;
    const Image cooked = sc.renderer.render(sc.camera, s);
    gl::HairMotion motion(sc.style, head, glm::mat3(1.0f), glm::mat3(1.0f));
    motion.pose(sc.renderer, motion.rest());
    // The same placements, the same strands voxelized the same way, the same body: the same pixels.
    EXPECT_EQ(max_difference(sc.renderer.render(sc.camera, s), cooked), 0.0f);
}

TEST(Motion, AMovedBodyChangesTheShadowGridWhereItMovedAndOnlyThere) {
    // GL-free: the body's voxels at rest and with bone b (the right plate, x = 1 … 5) lifted by 2 cm.
    const BodyMesh head = skinned_head();
    Strands hair;
    hair.add_strand({{-6.0f, 4.0f, -3.0f}, {6.0f, -4.0f, 3.0f}});
    const DensityGrid grid = voxelize_strands(hair, glm::mat3(1.0f), 32);
    BonePose pose = rest_pose(head);
    pose.transforms[1].translation = glm::vec3(0.0f, 2.0f, 0.0f);
    BodyMesh moved = head;
    skin_body(head, pose, moved.positions, moved.normals);
    const std::vector<std::uint8_t> a = voxelize_body(head, glm::mat3(1.0f), grid), b = voxelize_body(moved, glm::mat3(1.0f), grid);
    int changed = 0;
    for (int z = 0; z < grid.dims.z; ++z)
        for (int y = 0; y < grid.dims.y; ++y)
            for (int x = 0; x < grid.dims.x; ++x) {
                const std::size_t i = grid.index(x, y, z);
                if (a[i] == b[i]) continue;
                ++changed;
                // Only where the right plate was or is: its voxels reach x = 1 − 1 voxel.
                EXPECT_GE(grid.origin.x + (x + 1) * grid.voxel, 1.0f - grid.voxel) << x << ", " << y << ", " << z;
            }
    EXPECT_GT(changed, 20);
}

TEST(Motion, ARigidMotionOfTheHairAndItsLightsIsTheCameraMovedInversely) {
    // Hair and lights moved by M, seen by the camera moved by M, are the hair seen by the camera: exactly, but for the
    // shadow grid, which set_cluster_transforms voxelizes anew on axes that did not turn with the hair.
    Scene sc;
    const glm::mat4 M = glm::translate(glm::mat4(1.0f), glm::vec3(2.0f, -1.0f, 3.0f)) *
                        glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f)));
    const glm::mat3 R(M);
    for (const bool shadows : {false, true}) {
        gl::ShellSettings s;
        s.samples = 1;
        s.shadows = shadows;
        sc.renderer.set_cluster_transforms(std::vector<glm::mat4>(2, glm::mat4(1.0f)));
        sc.renderer.set_lights(test::two_lights());
        const Image still = sc.renderer.render(sc.camera, s);

        sc.renderer.set_cluster_transforms(std::vector<glm::mat4>(2, M));  // which voxelizes the moved strands
        std::vector<SrbfLight> lights = test::two_lights();
        for (SrbfLight& l : lights) l.omega = R * l.omega;
        sc.renderer.set_lights(lights);
        Camera camera = sc.camera;
        camera.eye = glm::vec3(M * glm::vec4(sc.camera.eye, 1.0f));
        camera.target = glm::vec3(M * glm::vec4(sc.camera.target, 1.0f));
        camera.up = R * sc.camera.up;
        const Image moved_image = sc.renderer.render(camera, s);
        double sum_a = 0, sum_b = 0;
        for (std::size_t i = 0; i < still.pixels.size(); ++i) sum_a += still.pixels[i], sum_b += moved_image.pixels[i];
        if (!shadows) {
            // Float rounding of the turned geometry, and RGBA16F: an edge pixel may flip.
            int differing = 0;
            for (std::size_t i = 0; i < still.pixels.size(); ++i) differing += std::abs(still.pixels[i] - moved_image.pixels[i]) > 4e-3f;
            EXPECT_LT(differing, 20) << "of " << still.pixels.size();
        }
        // The mean radiance within 0.1 % (measured: 6e-8 without shadows; 1.4e-4 with them, the grid's new voxels moving
        // the shadows' sampling).
        EXPECT_NEAR(sum_b / sum_a, 1.0, 1e-3) << (shadows ? "with shadows" : "without shadows");
    }
}

TEST(Motion, ASkinnedPoseMovesEachClusterWithItsBoneAndTheBodyWithIt) {
    Scene sc;
    const BodyMesh head = skinned_head();
    gl::HairMotion motion(sc.style, head, glm::mat3(1.0f), glm::mat3(1.0f));
    BonePose pose = motion.rest();
    pose.transforms[1] = {glm::angleAxis(0.5f, glm::vec3(0, 0, 1)), glm::vec3(0.0f, 1.0f, 0.0f)};  // b turns and rises
    motion.pose(sc.renderer, pose);
    const glm::mat4 B = pose.matrix(1);
    EXPECT_EQ(motion.cluster_transforms()[0], glm::mat4(1.0f));  // on a, at rest
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(motion.cluster_transforms()[1][c][r], B[c][r], 1e-5f);
    // The right cluster's lighting samples moved with b, the left's did not.
    const std::size_t rows = sc.renderer.prepared().samples.size() / 2;
    const PreparedShells& p = sc.renderer.prepared();
    for (std::size_t i = 0; i < rows; ++i) {
        EXPECT_EQ(glm::vec3(p.samples[i].position).x, -3.0f) << i;
        const glm::vec3 right = glm::vec3(p.samples[rows + i].position);
        const glm::vec3 was(3.0f, -10.0f * static_cast<float>(i) / static_cast<float>(rows - 1), 0.0f);
        EXPECT_NEAR(glm::distance(right, glm::vec3(B * glm::vec4(was, 1.0f))), 0.0f, 1e-3f) << i;
    }
    // The body's right plate moved by b, its left plate stayed.
    const BodyMesh& posed = motion.posed_body();
    for (std::size_t i = 0; i < head.positions.size(); ++i) {
        const glm::vec3 x = head.positions[i], y = posed.positions[i];
        if (x.x < 0) EXPECT_EQ(y, x);
        else EXPECT_NEAR(glm::distance(y, glm::vec3(B * glm::vec4(x, 1.0f))), 0.0f, 1e-5f);
    }
    // And the frame draws: the image differs from the rest pose's.
    gl::ShellSettings s;
    s.samples = 1;
    const Image posed_image = sc.renderer.render(sc.camera, s);
    motion.pose(sc.renderer, motion.rest());
    EXPECT_GT(max_difference(posed_image, sc.renderer.render(sc.camera, s)), 0.05f);
}

}  // namespace
}  // namespace coif
