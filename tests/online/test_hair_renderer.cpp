// coif::HairRenderer (online/hair_renderer.h): cooked hair drawn into a host-owned framebuffer with the host's
// matrices and depth, blended over its frame, with its GL state put back. The full example host (a head hiding the
// hair) is tests/consumer/example_host.cpp, run as online.ExampleHost.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>
#include <vector>

#include "models/core/error.h"
#include "models/core/log.h"
#include "online/gl.h"
#include "online/gl_context.h"
#include "online/hair_renderer.h"
#include "online/scene/cook.h"
#include "online/scene/hair_motion.h"
#include "online/shell_renderer.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

using test::one_cluster_style;
using test::test_index;
using test::two_lights;

constexpr int W = 96, H = 64;
constexpr glm::vec4 kClear{0.1f, 0.2f, 0.3f, 1.0f};

const CookedShells& cooked() {
    static const CookedShells c = cook_shells(one_cluster_style(), test_index(), glm::mat3(1.0f));
    return c;
}

// A host's frame: an RGBA32F colour texture and a DEPTH_COMPONENT32F texture, both W × H.
struct HostFrame {
    gl::Texture color = gl::make_texture_2d(GL_RGBA32F, W, H), depth = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, W, H);
    GLuint fb = 0;
    HostFrame() {
        glCreateFramebuffers(1, &fb);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, color.id(), 0);
        glNamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, depth.id(), 0);
    }
    ~HostFrame() { glDeleteFramebuffers(1, &fb); }
    // Clears the colour, and the depth to `far`, then sets the depth of the left half (x < W/2) to `wall`.
    void clear(float far, float wall) const {
        glClearTexImage(color.id(), 0, GL_RGBA, GL_FLOAT, &kClear.x);
        glClearTexImage(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far);
        glClearTexSubImage(depth.id(), 0, 0, 0, 0, W / 2, H, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &wall);
    }
    std::vector<glm::vec4> read() const {
        std::vector<glm::vec4> p(static_cast<std::size_t>(W) * H);
        glGetTextureImage(color.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(p.size() * sizeof(glm::vec4)), p.data());
        return p;  // row 0 at the bottom (GL's)
    }
};

Camera camera_of(const HairRenderer& r) { return Camera::orbit(r.bounds_min(), r.bounds_max(), 0.3f, 0.2f, W, H); }

FrameInputs inputs(const Camera& cam, const HostFrame& host, const std::vector<SrbfLight>& lights) {
    FrameInputs f;
    f.view = cam.view();
    f.projection = cam.projection();
    f.framebuffer = host.fb;
    f.viewport = glm::ivec4(0, 0, W, H);
    f.lights = lights;
    return f;
}

bool hair(const glm::vec4& p) { return p != kClear; }

// What every test starts from: a context, the renderer of the one-cluster hair, a camera on it, two lights and a
// host frame cleared to its colour and to the far depth.
struct Scene {
    std::unique_ptr<gl::Context> context = gl::Context::headless();
    HairRenderer hr{CookedShells(cooked())};
    Camera cam = camera_of(hr);
    std::vector<SrbfLight> lights = two_lights();
    HostFrame host;
    Scene() { host.clear(1.0f, 1.0f); }
};

TEST(HairRenderer, BlendsOverTheHostFrameAsTheStandaloneImageOverItsBackground) {
    // For the default compositing (exact) and the bounded one (weighted): both resolve premultiplied over the frame.
    for (const gl::Compositing mode : {gl::Compositing::exact, gl::Compositing::weighted}) {
        Scene scene;
        HairRenderer& hr = scene.hr;
        const Camera& cam = scene.cam;
        const std::vector<SrbfLight>& lights = scene.lights;
        HostFrame& host = scene.host;
        gl::ShellSettings s = hr.defaults();
        s.compositing = mode;
        FrameInputs f = inputs(cam, host, lights);
        f.settings = &s;
        hr.draw(f);
        const std::vector<glm::vec4> got = host.read();
        // The same hair drawn alone over a background of the host's clear colour (render(): an RGBA16F target).
        gl::ShellRenderer alone{CookedShells(cooked())};
        alone.set_lights(lights);
        s.samples = 1;
        s.background = glm::vec3(kClear);
        const Image ref = alone.render(cam, s);
        double worst = 0, peak = 0;
        std::size_t covered = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const glm::vec4& g = got[static_cast<std::size_t>(H - 1 - y) * W + x];
                covered += hair(g);
                for (int c = 0; c < 3; ++c) {
                    const double r = ref.pixels[(static_cast<std::size_t>(y) * W + x) * 4 + c];
                    worst = std::max(worst, std::abs(r - g[c]));
                    peak = std::max(peak, r);
                }
            }
        std::printf("%s: over the host's frame vs alone over the same colour: max |diff| %.3g of a peak %.3g; %zu hair pixels\n",
                    gl::compositing_name(mode), worst, peak, covered);
        EXPECT_GT(covered, static_cast<std::size_t>(W * H / 20)) << gl::compositing_name(mode);
        // Only the reference's RGBA16F target rounds (relative 2⁻¹¹); the host's target is RGBA32F.
        EXPECT_LE(worst, 2e-3 * peak) << gl::compositing_name(mode);
    }
}

TEST(HairRenderer, SceneDepthHidesTheHairBehindItInEitherConvention) {
    Scene scene;
    HairRenderer& hr = scene.hr;
    const Camera& cam = scene.cam;
    const std::vector<SrbfLight>& lights = scene.lights;
    HostFrame& host = scene.host;
    // A wall over the left half, between the eye and the hair: its window depth, standard convention.
    const glm::vec3 forward = glm::normalize(cam.target - cam.eye);
    const glm::vec4 clip = cam.projection() * cam.view() * glm::vec4(cam.eye + 0.3f * glm::distance(cam.eye, cam.target) * forward, 1.0f);
    const float wall = 0.5f * (clip.z / clip.w) + 0.5f;
    hr.draw(inputs(cam, host, lights));
    const std::vector<glm::vec4> open = host.read();

    host.clear(1.0f, wall);
    FrameInputs f = inputs(cam, host, lights);
    f.depth_texture = host.depth.id();
    f.depth_test = DepthTest::less_equal;
    hr.draw(f);
    const std::vector<glm::vec4> standard = host.read();

    // Reversed Z: the same projection with window depth 1 − d, the depth cleared to 0 and the wall at 1 − wall.
    const glm::mat4 flip(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 0, 0, 1));
    host.clear(0.0f, 1.0f - wall);
    f.projection = flip * cam.projection();
    f.depth_test = DepthTest::greater_equal;
    hr.draw(f);
    const std::vector<glm::vec4> reversed = host.read();

    std::size_t left_hair = 0, right_hair = 0, left_shown = 0, right_same = 0, reversed_same = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * W + x;
            if (!hair(open[p])) continue;
            if (x < W / 2) ++left_hair, left_shown += hair(standard[p]) || hair(reversed[p]);
            else ++right_hair, right_same += standard[p] == open[p];
            reversed_same += standard[p] == reversed[p];
        }
    std::printf("hair pixels left %zu (shown through the wall %zu), right %zu (unchanged %zu); reversed Z equals standard at %zu\n",
                left_hair, left_shown, right_hair, right_same, reversed_same);
    ASSERT_GT(left_hair, 20u);
    ASSERT_GT(right_hair, 20u);
    EXPECT_EQ(left_shown, 0u);            // the wall hides every hair fragment behind it
    EXPECT_EQ(right_same, right_hair);    // where the depth is far, the hair is as without depth
    // Depth values differ in rounding between the conventions only at fragments exactly at the wall: none here.
    EXPECT_EQ(reversed_same, left_hair + right_hair);
}

TEST(HairRenderer, DrawsEveryInstanceAndRefusesTransformsThatAreNotRigid) {
    Scene scene;
    HairRenderer& hr = scene.hr;
    const glm::vec3 size = hr.bounds_max() - hr.bounds_min();
    Camera cam = scene.cam;
    cam.fov_y *= 2.0f;  // wider, so that a second copy beside the first fits in the view
    const std::vector<SrbfLight>& lights = scene.lights;
    HostFrame& host = scene.host;
    const auto count = [&](std::vector<glm::mat4> instances) {
        host.clear(1.0f, 1.0f);
        FrameInputs f = inputs(cam, host, lights);
        f.instances = instances;
        hr.draw(f);
        std::size_t n = 0;
        for (const glm::vec4& p : host.read()) n += hair(p);
        return n;
    };
    const glm::vec3 right = glm::normalize(glm::cross(cam.target - cam.eye, glm::vec3(0, 1, 0)));
    const glm::mat4 beside = glm::translate(glm::mat4(1.0f), 1.2f * glm::length(size) * right);
    const std::size_t one = count({}), other = count({beside}), two = count({glm::mat4(1.0f), beside});
    // A copy turned about y and half the size: its own lights turned with it (the hair's space), fewer pixels.
    const std::size_t small = count({glm::scale(glm::rotate(glm::mat4(1.0f), 1.0f, glm::vec3(0, 1, 0)), glm::vec3(0.5f))});
    std::printf("hair pixels: one instance %zu, the copy beside it alone %zu, both %zu; one turned at half size %zu\n", one,
                other, two, small);
    EXPECT_GT(one, 50u);
    EXPECT_GT(other, 50u);
    EXPECT_EQ(two, one + other);  // apart on screen: both drawn in one frame, each as it is alone
    EXPECT_LT(small, one / 2);
    EXPECT_GT(small, one / 10);
    FrameInputs f = inputs(cam, host, lights);
    const glm::mat4 shear(glm::vec4(1, 0, 0, 0), glm::vec4(0.5f, 1, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, 0, 0, 1));
    f.instances = std::span<const glm::mat4>(&shear, 1);
    EXPECT_THROW(hr.draw(f), Error);
    f.instances = {};
    f.viewport = glm::ivec4(0);
    EXPECT_THROW(hr.draw(f), Error);
}

// Key lights (ShellSettings::key_lights) light every instance in its own space: their shadow volumes are made per
// instance from the lights turned into it, and kept with them. Two copies side by side, the second turned about y, each
// with a key light: where they do not overlap, the pair draws what each copy draws alone (to 1e-5), the key light
// changes the image, and a second frame draws the same again (the volumes kept per instance, not remade for the other).
TEST(HairRenderer, KeyLightsLightEveryInstanceInItsOwnSpace) {
    Scene scene;
    HairRenderer& hr = scene.hr;
    const glm::vec3 size = hr.bounds_max() - hr.bounds_min();
    Camera cam = scene.cam;
    cam.fov_y *= 2.0f;
    const glm::vec3 right = glm::normalize(glm::cross(cam.target - cam.eye, glm::vec3(0, 1, 0)));
    const glm::vec3 centre = 0.5f * (hr.bounds_min() + hr.bounds_max());
    const glm::mat4 beside = glm::translate(glm::mat4(1.0f), 1.2f * glm::length(size) * right + centre) *
                             glm::rotate(glm::mat4(1.0f), 1.0f, glm::vec3(0, 1, 0)) * glm::translate(glm::mat4(1.0f), -centre);
    gl::ShellSettings keyed, plain;
    keyed.key_lights = 1;
    plain.key_lights = 0;
    const auto draw = [&](std::vector<glm::mat4> instances, const gl::ShellSettings& st) {
        scene.host.clear(1.0f, 1.0f);
        FrameInputs f = inputs(cam, scene.host, scene.lights);
        f.instances = instances;
        f.settings = &st;
        hr.draw(f);
        return scene.host.read();
    };
    const std::vector<glm::vec4> a = draw({glm::mat4(1.0f)}, keyed), b = draw({beside}, keyed);
    const std::vector<glm::vec4> both = draw({glm::mat4(1.0f), beside}, keyed), again = draw({glm::mat4(1.0f), beside}, keyed);
    const std::vector<glm::vec4> unkeyed = draw({glm::mat4(1.0f), beside}, plain);
    int only_a = 0, only_b = 0;
    double changed = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (hair(a[i]) && !hair(b[i])) {
            EXPECT_LT(glm::distance(both[i], a[i]), 1e-5f) << "pixel " << i;
            ++only_a;
        } else if (hair(b[i]) && !hair(a[i])) {
            EXPECT_LT(glm::distance(both[i], b[i]), 1e-5f) << "pixel " << i;
            ++only_b;
        }
        EXPECT_EQ(again[i], both[i]) << "pixel " << i;
        changed += glm::distance(glm::vec3(both[i]), glm::vec3(unkeyed[i]));
    }
    std::printf("pixels of one copy alone: %d and %d; the key light moved the pair's colours by %.3g in all\n", only_a, only_b,
                changed);
    EXPECT_GT(only_a, 50);
    EXPECT_GT(only_b, 50);
    EXPECT_GT(changed, 0.01);
}

// The k-buffer compositing draws every instance's depths before it shades any (ShellDraw::Phase): two copies of the
// hair, one behind and through the other, composite as the exact lists composite them. Shading one copy before the
// other's depths were in the slots would leave its colours in slots that the other's nearer fragments then shift: drawn
// so, instance by instance, this measured 41.9 dB. Bound: PSNR over the hair pixels > 60 dB (measured 82.5: 16 slots
// hold all but the deepest pixels' faintest fragments, online.ShellCompositing.KBuffer…).
TEST(HairRenderer, TheKBufferCompositesOverlappingInstancesAsTheExactListsDo) {
    Scene scene;
    HairRenderer& hr = scene.hr;
    const glm::vec3 size = hr.bounds_max() - hr.bounds_min();
    const glm::vec3 forward = glm::normalize(scene.cam.target - scene.cam.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    // The second copy 0.05 of the hair's size (a quarter of the cluster's width) to the right and 0.02 behind: the two
    // overlap on screen (693 hair pixels of 525 and 542), and their fragments interleave in depth.
    const glm::mat4 behind = glm::translate(glm::mat4(1.0f), 0.05f * glm::length(size) * right + 0.02f * glm::length(size) * forward);
    const std::vector<glm::mat4> both = {behind, glm::mat4(1.0f)};  // the farther first: the nearer one's depths come after
    const auto draw = [&](gl::Compositing mode) {
        gl::ShellSettings s = hr.defaults();
        s.compositing = mode;
        s.kbuffer_slots = gl::kMaxKBufferSlots;
        scene.host.clear(1.0f, 1.0f);
        FrameInputs f = inputs(scene.cam, scene.host, scene.lights);
        f.instances = both;
        f.settings = &s;
        hr.draw(f);
        return scene.host.read();
    };
    const std::vector<glm::vec4> exact = draw(gl::Compositing::exact), kbuffer = draw(gl::Compositing::kbuffer);
    double se = 0, peak = 0;
    std::size_t n = 0;
    for (std::size_t p = 0; p < exact.size(); ++p) {
        if (!hair(exact[p])) continue;
        ++n;
        for (int c = 0; c < 3; ++c) {
            se += (kbuffer[p][c] - exact[p][c]) * (kbuffer[p][c] - exact[p][c]);
            peak = std::max(peak, static_cast<double>(exact[p][c]));
        }
    }
    ASSERT_GT(n, 100u);
    const double psnr = 10.0 * std::log10(peak * peak / std::max(se / (3.0 * n), 1e-30));
    std::printf("two overlapping instances, k-buffer (16 slots) against the exact lists: PSNR over %zu hair pixels %.1f dB\n", n, psnr);
    EXPECT_GT(psnr, 60.0);
}

TEST(HairRenderer, PutsBackTheHostsGlStateEvenWhenItThrows) {
    Scene scene;
    HairRenderer& hr = scene.hr;
    const Camera& cam = scene.cam;
    const std::vector<SrbfLight>& lights = scene.lights;
    HostFrame& host = scene.host;
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    // A host's state, set to values none of the passes use.
    const auto set_host_state = [&] {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, host.fb);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glViewport(3, 4, 50, 40);
        glBindVertexArray(vao);
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE, GL_ZERO, GL_DST_ALPHA);
        glBlendEquationSeparate(GL_FUNC_SUBTRACT, GL_MAX);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT_AND_BACK);
        glFrontFace(GL_CW);
        glEnable(GL_SCISSOR_TEST);
        glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
        glDisable(GL_FRAMEBUFFER_SRGB);
    };
    const auto state = [] {
        std::vector<GLint> v(24, 0);
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &v[0]);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &v[1]);
        glGetIntegerv(GL_VIEWPORT, &v[2]);
        glGetIntegerv(GL_CURRENT_PROGRAM, &v[6]);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &v[7]);
        v[8] = glIsEnabled(GL_BLEND);
        glGetIntegerv(GL_BLEND_SRC_RGB, &v[9]);
        glGetIntegerv(GL_BLEND_DST_ALPHA, &v[10]);
        glGetIntegerv(GL_BLEND_EQUATION_RGB, &v[11]);
        glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &v[12]);
        v[13] = glIsEnabled(GL_DEPTH_TEST);
        GLboolean b[4] = {};
        glGetBooleanv(GL_DEPTH_WRITEMASK, b);
        v[14] = b[0];
        v[15] = glIsEnabled(GL_CULL_FACE);
        glGetIntegerv(GL_CULL_FACE_MODE, &v[16]);
        glGetIntegerv(GL_FRONT_FACE, &v[17]);
        v[18] = glIsEnabled(GL_SCISSOR_TEST);
        glGetBooleanv(GL_COLOR_WRITEMASK, b);
        v[19] = b[0] + 2 * b[1] + 4 * b[2] + 8 * b[3];
        v[20] = glIsEnabled(GL_FRAMEBUFFER_SRGB);
        v[21] = glIsEnabled(GL_RASTERIZER_DISCARD);
        return v;
    };
    set_host_state();
    const std::vector<GLint> before = state();
    FrameInputs f = inputs(cam, host, lights);
    hr.draw(f);
    EXPECT_EQ(state(), before);
    // The host's scissor, colour mask and culling did not hide the hair from its own passes.
    std::size_t n = 0;
    for (const glm::vec4& p : host.read()) n += hair(p);
    EXPECT_GT(n, static_cast<std::size_t>(W * H / 20));
    // A draw that fails inside (a sheared instance) puts the state back too.
    const glm::mat4 shear(glm::vec4(1, 0, 0, 0), glm::vec4(0.5f, 1, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, 0, 0, 1));
    f.instances = std::span<const glm::mat4>(&shear, 1);
    EXPECT_THROW(hr.draw(f), Error);
    EXPECT_EQ(state(), before);
    glDeleteVertexArrays(1, &vao);
}

TEST(HairRenderer, MessagesGoToTheHostsLogSink) {
    std::vector<std::string> messages;
    const LogSink previous = set_log_sink([&](LogLevel, std::string_view m) { messages.emplace_back(m); });
    {
        Scene scene;
        HairRenderer& hr = scene.hr;
        FrameInputs f = inputs(scene.cam, scene.host, scene.lights);
        gl::ShellSettings s = hr.defaults();
        s.hair.fibre.sigma_a = glm::vec3(0.3f, 0.5f, 0.9f);  // other tables: the renderer says it rebuilds them
        f.settings = &s;
        hr.draw(f);
    }
    set_log_sink(previous);
    ASSERT_FALSE(messages.empty());
    EXPECT_NE(messages.back().find("dual-scattering tables"), std::string::npos) << messages.back();
}

TEST(HairRenderer, FollowsTheBonesItIsGivenAsTheAuthoringMotionDoes) {
    // The two-cluster hair skinned to bones "a" (left) and "b" (right), through its asset's bytes, on a body of two plates
    // over the roots (one per bone). Posed through FrameInputs::bones, the runtime draws what the authoring path (HairMotion
    // on a ShellRenderer, which coif render --animate uses) draws for the same pose into the same host frame: the same
    // cluster transforms, the same strands voxelized again with the same posed body, so the same pixels.
    std::unique_ptr<gl::Context> context = gl::Context::headless();
    const HairStyle style = test::two_cluster_style(true);
    const CookedShells c = cook_shells(style, test_index(), glm::mat3(1.0f));
    const CookedShells read = parse_hair_asset(hair_asset_bytes(c), "two.coif");
    HairRenderer hr{CookedShells(read)};
    ASSERT_EQ(hr.bones(), (std::vector<std::string>{"a", "b"}));
    const BodyMesh head = test::skinned_head();
    hr.set_body(&head);

    const Camera cam = camera_of(hr);
    const std::vector<SrbfLight> lights = two_lights();
    HostFrame host;
    const auto frame = [&](std::span<const glm::mat4> bones) {
        host.clear(1.0f, 1.0f);
        FrameInputs f = inputs(cam, host, lights);
        f.bones = bones;
        hr.draw(f);
        return host.read();
    };
    const std::vector<glm::vec4> rest = frame({});
    const std::vector<glm::mat4> identity(2, glm::mat4(1.0f));
    EXPECT_EQ(frame(identity), rest);  // the rest pose given as matrices: the cooked grid voxelized again, bit for bit

    gl::HairMotion motion(style, head, glm::mat3(1.0f), glm::mat3(1.0f));
    BonePose pose = motion.rest();
    pose.transforms[1] = {glm::angleAxis(0.5f, glm::vec3(0, 0, 1)), glm::vec3(0.0f, 1.0f, 0.0f)};  // b turns and rises
    const std::vector<glm::mat4> bones = pose.matrices();
    const std::vector<glm::vec4> posed = frame(bones);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < posed.size(); ++i) changed += posed[i] != rest[i];
    EXPECT_GT(changed, posed.size() / 50);

    gl::ShellRenderer authoring{CookedShells(read)};
    authoring.set_body(&head);
    motion.pose(authoring, pose);
    host.clear(1.0f, 1.0f);
    FrameInputs f = inputs(cam, host, lights);
    gl::FrameTarget target;
    target.viewport = f.viewport;
    target.over = true;
    gl::ShellSettings s = hr.defaults();
    s.samples = 1;
    s.timed = false;
    glBindFramebuffer(GL_FRAMEBUFFER, host.fb);
    authoring.draw_frame(f.view, f.projection, lights, s, target);
    EXPECT_EQ(host.read(), posed);
    std::printf("pose: %zu of %zu pixels changed; skinning and grid: placement %.2f ms, shadow grid %.2f ms\n", changed,
                posed.size(), hr.shells().move_timings().placement_ms, hr.shells().move_timings().shadow_grid_ms);

    // Bones it cannot follow: a count other than the asset's, a matrix that is not finite, bones for unskinned hair.
    f = inputs(cam, host, lights);
    f.bones = std::span<const glm::mat4>(bones).first(1);
    EXPECT_THROW(hr.draw(f), Error);
    std::vector<glm::mat4> nan = bones;
    nan[1][3][0] = std::nanf("");
    f.bones = nan;
    EXPECT_THROW(hr.draw(f), Error);
    HairRenderer unskinned{CookedShells(cooked())};
    EXPECT_TRUE(unskinned.bones().empty());
    f.bones = bones;
    EXPECT_THROW(unskinned.draw(f), Error);
}

}  // namespace
}  // namespace coif
