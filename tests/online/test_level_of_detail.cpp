// The shells' level of detail (ShellSettings::lod_pixels, online/shells/shell_lod.h) as drawn: a camera moving away in
// small steps and back coarsens the clusters' meshes and refines them again, each cluster switching once each way, and
// the image changes from one step to the next about as much as the full meshes' image does (no popping).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>

#include "online/gl.h"
#include "online/gl_context.h"
#include "online/scene/cook.h"
#include "models/style_edit.h"
#include "online/shell_renderer.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

double mean_abs_difference(const Image& a, const Image& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
    return sum / double(a.pixels.size());
}

double mean(const Image& a) {
    double sum = 0;
    for (const float v : a.pixels) sum += v;
    return sum / double(a.pixels.size());
}

TEST(LevelOfDetail, ACameraMovingAwayAndBackSwitchesEachClusterOnceEachWayWithoutPopping) {
    auto context = gl::Context::headless();
    gl::ShellRenderer r(cook_shells(test::prototype_and_instance(), test::test_index(), glm::mat3(1.0f)));
    r.set_lights(test::two_lights());
    const Camera framed = Camera::orbit(r.bounds_min(), r.bounds_max(), 0.3f, 0.2f, 96, 64);
    gl::ShellSettings full, lod;
    full.samples = lod.samples = 1;
    full.lod_pixels = 0.0f;
    lod.lod_pixels = 10.0f;
    // Out to 4.8 times the framing distance in steps of 4 %, and back.
    std::vector<float> path;
    for (int k = 0; k <= 40; ++k) path.push_back(std::pow(1.04f, float(k)));
    for (int k = 39; k >= 0; --k) path.push_back(std::pow(1.04f, float(k)));
    std::vector<Image> drawn, exact;
    gl::RenderTarget target(framed.width, framed.height);
    std::vector<std::array<std::size_t, kLodLevels>> levels;
    for (const float f : path) {
        Camera c = framed;
        c.eye = c.target + f * (framed.eye - framed.target);
        c.far_plane = f * framed.far_plane;  // the framing's far plane moves out with the eye
        exact.push_back(r.render(c, full));
        // As a viewer or a game draws its frames (render() picks every image's levels afresh).
        target.bind();
        r.draw(c, lod);
        drawn.push_back(target.read_back());
        levels.push_back(r.timings().clusters_at_level);
    }
    // Full detail at the framing distance, both clusters at the coarsest level at the far end.
    EXPECT_EQ(levels.front()[0], 2u);
    EXPECT_EQ(levels[40][kLodLevels - 1], 2u);
    EXPECT_EQ(levels.back()[0], 2u);
    // Monotonic both ways: no cluster goes back to a finer level while the camera moves away, nor coarser while it comes
    // nearer (the count at level 0, and at levels ≤ 1, never rises out, never falls back).
    int switches = 0;
    for (std::size_t k = 1; k < path.size(); ++k) {
        const bool out = k <= 40;
        for (std::size_t l = 0; l + 1 < kLodLevels; ++l) {
            std::size_t finer_now = 0, finer_before = 0;
            for (std::size_t m = 0; m <= l; ++m) finer_now += levels[k][m], finer_before += levels[k - 1][m];
            if (out) EXPECT_LE(finer_now, finer_before) << "step " << k;
            else EXPECT_GE(finer_now, finer_before) << "step " << k;
        }
        switches += levels[k] != levels[k - 1];
    }
    // Two clusters, two levels to go down and up: at most 8 steps at which a level changes.
    EXPECT_LE(switches, 8);
    EXPECT_GE(switches, 2);
    // An image (render()) does not depend on what was drawn before it: at the step where coming back still draws the
    // coarser meshes (hysteresis), render() picks as from nothing, as a new renderer's first image does.
    {
        Camera c = framed;
        c.eye = c.target + 1.4f * (framed.eye - framed.target);
        c.far_plane = 1.4f * framed.far_plane;
        const Image after = r.render(c, lod);
        gl::ShellRenderer fresh(cook_shells(test::prototype_and_instance(), test::test_index(), glm::mat3(1.0f)));
        fresh.set_lights(test::two_lights());
        EXPECT_EQ(fresh.render(c, lod).pixels, after.pixels);
    }
    // Hysteresis: coming back, the clusters return to full detail nearer than where they left it going out.
    std::size_t left = 0, returned = 0;
    for (std::size_t k = 1; k <= 40; ++k)
        if (!left && levels[k][0] < 2) left = k;
    for (std::size_t k = 41; k < path.size(); ++k)
        if (!returned && levels[k][0] == 2) returned = k;
    ASSERT_GT(left, 0u);
    ASSERT_GT(returned, 0u);
    EXPECT_LT(path[returned], path[left - 1]);
    // No popping: a step's change of the picture stays within what the full meshes' picture changes by at that step plus
    // 0.3 % of the picture's mean, and every picture stays within 0.4 % (mean absolute difference over the mean) of full
    // detail. Measured: at most 0.03 % and 0.04 % (these clusters are straight: the coarser rows lose nothing along t,
    // the rings go from 16 sides to 8), so the bounds hold a tenfold margin against the rasteriser's ties.
    for (std::size_t k = 1; k < path.size(); ++k) {
        const double scale = mean(exact[k]);
        ASSERT_GT(scale, 0.0) << "the hair must show";
        EXPECT_LE(mean_abs_difference(drawn[k], drawn[k - 1]), mean_abs_difference(exact[k], exact[k - 1]) + 0.003 * scale)
            << "step " << k;
        EXPECT_LE(mean_abs_difference(drawn[k], exact[k]), 0.004 * scale) << "step " << k;
    }
}

TEST(LevelOfDetail, TheLightingPassLightsOnlyTheSamplesTheCoarserMeshesRead) {
    // A cluster drawn at level 2 joins every 4th row along t, and its vertices read the lighting sums at those rows
    // alone, so the lighting pass skips the others (ShellSettings::lod_lighting): the image is bit-identical to lighting
    // every sample. Each pass lights every sample (lighting_step 1), so that the levels' strides decide alone.
    auto context = gl::Context::headless();
    gl::ShellRenderer r(cook_shells(test::prototype_and_instance(), test::test_index(), glm::mat3(1.0f)));
    r.set_lights(test::two_lights());
    const Camera framed = Camera::orbit(r.bounds_min(), r.bounds_max(), 0.3f, 0.2f, 96, 64);
    Camera far = framed;
    far.eye = far.target + 4.0f * (framed.eye - framed.target);
    far.far_plane = 4.0f * framed.far_plane;
    gl::ShellSettings s;
    s.samples = 1;
    s.lod_pixels = 10.0f;
    s.lighting_step = 1;
    s.key_lights = 1;  // its weights are read per vertex too (shell.vert), not from the skipped samples between them
    gl::ShellSettings every = s;
    every.lod_lighting = false;
    const int rows = r.lighting_rows();
    const std::size_t clusters = 2;
    // The rows a level-2 mesh keeps: 0, 4, 8, … and the last.
    const std::size_t kept = static_cast<std::size_t>((rows - 1) / 4 + 1 + ((rows - 1) % 4 != 0 ? 1 : 0));

    const Image skipped = r.render(far, s);
    ASSERT_EQ(r.timings().clusters_at_level[kLodLevels - 1], clusters) << "both clusters at the coarsest level";
    EXPECT_EQ(r.read_lights_lit().size(), clusters * kept);
    const Image all = r.render(far, every);
    EXPECT_EQ(r.read_lights_lit().size(), clusters * static_cast<std::size_t>(rows));
    EXPECT_EQ(skipped.pixels, all.pixels) << "the samples skipped are read by no vertex";
    ASSERT_GT(mean(all), 0.0) << "the hair must show";

    // Near, at full detail, every sample is lit.
    r.render(framed, s);
    ASSERT_EQ(r.timings().clusters_at_level[0], clusters);
    EXPECT_EQ(r.read_lights_lit().size(), clusters * static_cast<std::size_t>(rows));

    // The samples lit are part of what the sums are reused for: the same eye with full meshes after the skipping frame
    // lights the skipped samples too, and draws what a new renderer draws.
    r.render(far, s);
    gl::ShellSettings full_meshes = s;
    full_meshes.lod_pixels = 0.0f;
    const Image after = r.render(far, full_meshes);
    gl::ShellRenderer fresh(cook_shells(test::prototype_and_instance(), test::test_index(), glm::mat3(1.0f)));
    fresh.set_lights(test::two_lights());
    EXPECT_EQ(fresh.render(far, full_meshes).pixels, after.pixels);
}

TEST(LevelOfDetail, FoldedLayersDrawHalfTheTrianglesAndKeepTheLook) {
    // ShellSettings::fold_level: a cluster at that level or coarser draws its 4 layers as 2 pairs, each from the outer
    // layer's mesh, the fragment shading both layers (shell_shade.glsl SHELL_FOLD, the inner one where the view ray meets
    // it). With the weighted compositing (the order-independent one that low uses), the image keeps the unfolded one's
    // light and coverage.
    auto context = gl::Context::headless();
    gl::ShellRenderer r(cook_shells(test::prototype_and_instance(), test::test_index(), glm::mat3(1.0f)));
    r.set_lights(test::two_lights());
    const Camera camera = Camera::orbit(r.bounds_min(), r.bounds_max(), 0.3f, 0.2f, 96, 64);
    gl::ShellSettings s;
    s.samples = 1;
    s.compositing = gl::Compositing::weighted;
    s.lod_pixels = 0.0f;  // every cluster at level 0, so that fold_level 0 folds them all
    gl::ShellSettings folded = s;
    folded.fold_level = 0;

    const Image whole = r.render(camera, s);
    const std::size_t whole_triangles = r.timings().triangles_drawn;
    const Image pairs = r.render(camera, folded);
    ASSERT_GT(whole_triangles, 0u);
    EXPECT_EQ(r.timings().triangles_drawn * 2, whole_triangles) << "layers 1 and 3 of 4, every layer's mesh alike";
    // The look: mean radiance within 2 % and the mean absolute difference within 5 % of the mean (measured 0.03 % and
    // 0.04 %: a round cluster, where the inner layer's point on the ray is exact; the bounds leave room for drivers).
    const double m = mean(whole);
    ASSERT_GT(m, 0.0) << "the hair must show";
    std::printf("folded against every layer: mean ratio %.4f, mean absolute difference %.4f of the mean\n", mean(pairs) / m,
                mean_abs_difference(pairs, whole) / m);
    EXPECT_NEAR(mean(pairs) / m, 1.0, 0.02);
    EXPECT_LT(mean_abs_difference(pairs, whole), 0.05 * m);
    // With fibres thick enough that a key light from the camera keeps a quarter of its light (each layer's slab lies
    // under the layers outside it), each layer of a pair takes its own slab (shell.vert v_key_weight_inner): the folded
    // image keeps the unfolded one's light within [0.85, 1.1]. Measured 0.88 (0.91 before the records' thinning): the inner layer's slab is taken on the
    // outer vertex's line from the axis, where the view ray meets that layer elsewhere. With the outer layer's slab for
    // both (before), 1.17.
    {
        SrbfLight key;  // narrow, from the camera: it reaches each layer through the layers outside it
        key.L = glm::vec3(1.0f);
        key.omega = glm::normalize(camera.eye - 0.5f * (r.bounds_min() + r.bounds_max()));
        key.lambda = 0.05f;
        const SrbfLight lights[] = {key};
        r.set_lights(lights);
        gl::ShellSettings thick = s, thick_folded = folded;
        thick.background = thick_folded.background = glm::vec3(0.0f);
        // Read at the slabs' own points: here the light shines from the camera, and the reads moved toward both would
        // take each point past the layer outside it.
        thick.key_toward_camera = thick_folded.key_toward_camera = 0.0f;
        thick.key_toward_light = thick_folded.key_toward_light = 0.0f;
        const auto rgb = [](const Image& a) {
            double sum = 0;
            for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += i % 4 == 3 ? 0.0 : a.pixels[i];
            return sum;
        };
        thick.fiber_radius = thick_folded.fiber_radius = 1e-7f;
        const double thin = rgb(r.render(camera, thick));
        thick.fiber_radius = thick_folded.fiber_radius = 0.2f;
        const Image w = r.render(camera, thick), p = r.render(camera, thick_folded);
        std::printf("with thick fibres: folded against every layer %.4f (every layer keeps %.4f of the thin fibres' light)\n",
                    rgb(p) / rgb(w), rgb(w) / thin);
        EXPECT_LT(rgb(w), 0.5 * thin) << "the thick fibres shadow the layers";
        EXPECT_GT(rgb(p) / rgb(w), 0.85);
        EXPECT_LT(rgb(p) / rgb(w), 1.1);
        r.set_lights(test::two_lights());
    }
    // Without fold_level the same renderer draws every layer again.
    EXPECT_EQ(r.render(camera, s).pixels, whole.pixels);
    EXPECT_EQ(r.timings().triangles_drawn, whole_triangles);
    // The exact lists draw every layer whatever fold_level says.
    gl::ShellSettings exact = folded;
    exact.compositing = gl::Compositing::exact;
    const Image listed = r.render(camera, exact);
    EXPECT_EQ(r.timings().triangles_drawn, whole_triangles);
    exact.fold_level = 3;
    EXPECT_EQ(r.render(camera, exact).pixels, listed.pixels);

    // An odd layer count: the innermost layer is drawn alone (nothing folded into it). With one layer, folding changes
    // nothing but the program: the same image to float rounding.
    HairStyle one = test::prototype_and_instance();
    set_layers(one, 0, 1);
    gl::ShellRenderer single(cook_shells(one, test::test_index(), glm::mat3(1.0f)));
    single.set_lights(test::two_lights());
    const Image a = single.render(camera, s);
    const std::size_t one_layer = single.timings().triangles_drawn;
    const Image b = single.render(camera, folded);
    EXPECT_EQ(single.timings().triangles_drawn, one_layer);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double worst = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) worst = std::max(worst, std::abs(double(a.pixels[i]) - double(b.pixels[i])));
    EXPECT_LT(worst, 1e-5);
    ASSERT_GT(mean(a), 0.0);
}

}  // namespace
}  // namespace coif
