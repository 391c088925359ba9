// A character's body in the shell renderer (ShellRenderer::set_body, online/body_pass.h): it hides the hair behind it
// and nothing else, and it shadows the hair where it stands between the hair and the light, and only there.
#include <gtest/gtest.h>

#include <memory>

#include "models/character.h"
#include "online/gl_context.h"
#include "online/scene/cook.h"
#include "online/shell_renderer.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

// A rectangle with corners a, a + u, a + u + v, a + v (two triangles), not skinned.
BodyMesh quad(glm::vec3 a, glm::vec3 u, glm::vec3 v) {
    BodyMesh m;
    m.positions = {a, a + u, a + u + v, a + v};
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    m.normals.assign(4, n);
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

struct Scene {
    std::unique_ptr<gl::Context> context = gl::Context::headless();
    gl::ShellRenderer renderer{cook_shells(test::two_cluster_style(), test::test_index(), glm::mat3(1.0f))};
};

TEST(Body, HidesTheHairBehindItAndNothingElse) {
    Scene sc;
    sc.renderer.set_lights(test::two_lights());
    Camera camera = Camera::orbit(sc.renderer.bounds_min(), sc.renderer.bounds_max(), 0.0f, 0.0f, 160, 120);  // from +z
    gl::ShellSettings s;
    s.samples = 1;
    s.shadows = false;  // the occlusion alone (the shadows have their own test)
    const Image without = sc.renderer.render(camera, s);
    // A wall in front of the lower half of the right cluster, facing the camera.
    const BodyMesh wall = quad({1.0f, -11.0f, 2.0f}, {4.0f, 0.0f, 0.0f}, {0.0f, 6.0f, 0.0f});
    sc.renderer.set_body(&wall);
    const Image with = sc.renderer.render(camera, s);
    ASSERT_EQ(with.width, without.width);
    // The wall's pixels, by projecting its corners (a margin of 2 pixels on each side of its edges is left out).
    glm::vec2 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& p : wall.positions) {
        const glm::vec2 px = camera.pixel(p);
        lo = glm::min(lo, px), hi = glm::max(hi, px);
    }
    int inside = 0, outside = 0, hair_hidden = 0;
    glm::vec3 wall_colour(-1.0f);
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const glm::vec2 p(x + 0.5f, y + 0.5f);
            const float* a = &without.pixels[(static_cast<std::size_t>(y) * camera.width + x) * 4];
            const float* b = &with.pixels[(static_cast<std::size_t>(y) * camera.width + x) * 4];
            const glm::vec3 ca(a[0], a[1], a[2]), cb(b[0], b[1], b[2]);
            if (glm::all(glm::greaterThan(p, lo + 2.0f)) && glm::all(glm::lessThan(p, hi - 2.0f))) {
                // The flat wall under directional lights has one colour, whatever hair lies behind it.
                if (wall_colour.x < 0.0f) wall_colour = cb;
                ASSERT_LT(glm::length(cb - wall_colour), 2e-3f) << "pixel " << x << ", " << y;  // RGBA16F rounding
                hair_hidden += glm::length(ca - glm::vec3(gl::ShellSettings{}.background)) > 1e-2f;
                ++inside;
            } else if (!(glm::all(glm::greaterThan(p, lo - 2.0f)) && glm::all(glm::lessThan(p, hi + 2.0f)))) {
                // Elsewhere the image is the one without the body (blended over the background instead of replacing it).
                ASSERT_LT(glm::length(cb - ca), 2e-3f) << "pixel " << x << ", " << y;
                ++outside;
            }
        }
    EXPECT_GT(inside, 200);
    EXPECT_GT(outside, 5000);
    EXPECT_GT(hair_hidden, 50);  // there was hair behind the wall
    EXPECT_GT(wall_colour.x, 0.0f);
}

// A narrow light from above at 45° towards +z.
SrbfLight sun() {
    SrbfLight l;
    l.L = glm::vec3(1.0f);
    l.omega = glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));
    l.lambda = 0.1f;
    return l;
}

TEST(Body, ShadowsTheHairOnlyWhereItBlocksTheLight) {
    Scene sc;
    sc.renderer.set_lights(std::vector<SrbfLight>{sun()});
    Camera camera = Camera::orbit(sc.renderer.bounds_min(), sc.renderer.bounds_max(), 0.0f, 0.0f, 64, 48);
    gl::ShellSettings s;
    s.samples = 1;
    sc.renderer.render(camera, s);
    const std::vector<glm::vec2> open = sc.renderer.read_shadows();
    // A roof over the right cluster at y = −2, reaching beyond the hair's box towards the light (the shadow grid grows
    // to hold it): the sun's rays from the right cluster's axis at height y meet it at z = −2 − y.
    const BodyMesh roof = quad({1.0f, -2.0f, -2.0f}, {4.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 12.0f});
    sc.renderer.set_body(&roof);
    sc.renderer.render(camera, s);
    const std::vector<glm::vec2> shaded = sc.renderer.read_shadows();
    ASSERT_EQ(open.size(), shaded.size());
    int under = 0, left = 0, above = 0;
    for (std::size_t i = 0; i < open.size(); ++i) {
        const glm::vec3 p = sc.renderer.lighting_sample(i)[0];
        if (p.x < 0.0f) {  // the left cluster: nothing between it and the light
            EXPECT_NEAR(shaded[i].x, open[i].x, 1e-5f) << "sample " << i;  // the grown grid: a longer march through empty voxels
            ++left;
        } else if (p.y < -4.0f && p.y > -8.0f) {
            // Well under the roof (beyond the own cluster's 1.4 cm along the ray), where the grid holds it (up to half the
            // hair's longest side, 5.7 cm, beyond its box): in its shadow.
            EXPECT_GT(open[i].x, 0.3f) << "sample " << i;
            EXPECT_LT(shaded[i].x, 1e-3f) << "sample " << i << " open " << open[i].x << " y " << p.y;
            ++under;
        } else if (p.y > -1.0f) {  // above it: the roof lies behind, away from the light
            EXPECT_NEAR(shaded[i].x, open[i].x, 1e-3f) << "sample " << i;
            ++above;
        }
    }
    EXPECT_GT(left, 4);
    EXPECT_GT(under, 2);
    EXPECT_GT(above, 0);
    // Removed, the body shadows nothing.
    sc.renderer.set_body(nullptr);
    sc.renderer.render(camera, s);
    const std::vector<glm::vec2> again = sc.renderer.read_shadows();
    for (std::size_t i = 0; i < open.size(); ++i) EXPECT_EQ(again[i], open[i]) << "sample " << i;
}

// A key light (ShellSettings::key_lights) is shadowed by the body as the shadow pass's lights are: its volume
// (shell_key_light.comp) adds the body's depth, read on the shadow grid beyond the volume's own box too. The same roof
// and sun as above: at the right cluster's lighting samples well under the roof the fibres met toward the sun grow by the
// body's most depth per ray, 20 (kBodyMaxDepth; read at the nearest voxel, so at least 15); at the left cluster's
// samples nothing changes (to half-float rounding).
TEST(Body, ShadowsTheKeyLightsToo) {
    Scene sc;
    sc.renderer.set_lights(std::vector<SrbfLight>{sun()});
    Camera camera = Camera::orbit(sc.renderer.bounds_min(), sc.renderer.bounds_max(), 0.0f, 0.0f, 64, 48);
    gl::ShellSettings s;
    s.samples = 1;
    s.key_lights = 1;
    sc.renderer.render(camera, s);
    const gl::ShellRenderer::KeyVolume open = sc.renderer.read_key_volume(0);
    ASSERT_FALSE(open.fibres.empty());
    const BodyMesh roof = quad({1.0f, -2.0f, -2.0f}, {4.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 12.0f});
    sc.renderer.set_body(&roof);
    sc.renderer.render(camera, s);
    const gl::ShellRenderer::KeyVolume shaded = sc.renderer.read_key_volume(0);
    ASSERT_EQ(shaded.dims, open.dims);  // the volume frames the strands' grid, which the body does not change
    const auto at = [&](const gl::ShellRenderer::KeyVolume& v, glm::vec3 p) {
        const glm::ivec3 i = glm::clamp(glm::ivec3(glm::floor(glm::vec3(v.frame * glm::vec4(p, 1.0f)) * glm::vec3(v.dims))),
                                        glm::ivec3(0), v.dims - 1);
        return v.fibres[(static_cast<std::size_t>(i.z) * v.dims.y + i.y) * v.dims.x + i.x];
    };
    int under = 0, left = 0;
    for (std::size_t i = 0; i < sc.renderer.prepared().samples.size(); ++i) {
        const glm::vec3 p = sc.renderer.lighting_sample(i)[0];
        if (p.x < 0.0f) {
            EXPECT_NEAR(at(shaded, p), at(open, p), 1e-3f * at(open, p) + 1e-4f) << "sample " << i;
            ++left;
        } else if (p.y < -4.0f && p.y > -8.0f) {
            EXPECT_GT(at(shaded, p) - at(open, p), 15.0f) << "sample " << i;
            ++under;
        }
    }
    EXPECT_GT(left, 4);
    EXPECT_GT(under, 2);
}

}  // namespace
}  // namespace coif
