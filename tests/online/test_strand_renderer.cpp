// The lit strand renderer (online/strand_renderer.h) on llvmpipe: its pixels against the CPU evaluator of
// the lighting module, the fibre's pixel coverage 2r/p, and `coif render --strands` refusing bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "models/core/error.h"
#include "models/strands.h"
#include "online/gl_context.h"
#include "online/strand_renderer.h"
#include "shaders/lighting.h"
#include "tests/common/run.h"

namespace coif {
namespace {

// One straight strand, oblique to the image axes and to the view, 21 points.
Strands straight_strand(glm::vec3 a, glm::vec3 b) {
    std::vector<glm::vec3> points;
    for (int i = 0; i <= 20; ++i) points.push_back(a + (b - a) * (float(i) / 20.0f));
    Strands s;
    s.add_strand(points);
    return s;
}

// The point of the line a→b whose attributes GL interpolates for the fragment of pixel (x, y): the pixel
// centre projected orthogonally onto the line's image (GL 4.5 §14.5.1), lifted back onto the 3D line
// along the camera ray through that image point.
glm::vec3 fragment_point(const Camera& camera, glm::vec3 a, glm::vec3 b, int x, int y) {
    const glm::vec2 A = camera.pixel(a), B = camera.pixel(b), C(float(x) + 0.5f, float(y) + 0.5f);
    const glm::vec2 Q = A + (B - A) * (glm::dot(C - A, B - A) / glm::dot(B - A, B - A));
    glm::vec3 o, d;
    camera.ray(Q.x, Q.y, o, d);
    // Closest point of the line a + s (b − a) to the ray o + t d.
    const glm::vec3 e = b - a, r = a - o;
    const float ee = glm::dot(e, e), ed = glm::dot(e, d), dd = glm::dot(d, d), er = glm::dot(e, r), dr = glm::dot(d, r);
    const float s = (ed * dr - dd * er) / (ee * dd - ed * ed);
    return a + s * e;
}

// The strand spans ~85 % of the image width; the light sits on the R lobe's cone of the view at the
// strand's middle (θi = −θo, φi = φo), so the highlight falls on the strand and the rest is TT and TRT.
struct Scene {
    glm::vec3 a{-1.0f, -0.25f, -0.1f}, b{1.0f, 0.35f, 0.25f};
    Strands strands = straight_strand(a, b);
    Camera camera = Camera::orbit({-0.7f, -0.3f, -0.1f}, {0.7f, 0.3f, 0.1f}, 0.35f, 0.15f, 128, 96);
    SrbfLight light = [this] {
        const glm::vec3 u = glm::normalize(b - a), V = glm::normalize(camera.eye - 0.5f * (a + b));
        // L_j: a light of λ = 0.1 covers ∫G dω ≈ πλ² ≈ 0.03 sr, so 40 makes L_o of order 0.01–0.1.
        return SrbfLight{glm::vec3(40.0f, 32.0f, 24.0f), glm::normalize(V - 2.0f * glm::dot(V, u) * u), 0.1f};
    }();
};

// L_o at the fragment of pixel (x, y), from the CPU evaluator, in the reference renderer's frame
// (v = u × y: a different normal from the GPU's view-aligned one, which a round fibre must not notice).
glm::vec3 cpu_radiance(const Scene& sc, const shading::LightingEvaluator& ev, bool multiple, int x, int y) {
    const glm::vec3 p = fragment_point(sc.camera, sc.a, sc.b, x, y);
    const glm::vec3 u = glm::normalize(sc.b - sc.a);
    const shading::FibreFrame frame = shading::FibreFrame::from_tangent(u, glm::cross(u, glm::vec3(0, 1, 0)));
    return ev.shade(frame, glm::normalize(sc.camera.eye - p), std::span(&sc.light, 1), {}, multiple).total();
}

TEST(StrandRenderer, PixelsMatchTheCpuEvaluatorUnderOneNarrowLight) {
    auto context = gl::Context::headless();
    const Scene sc;
    gl::StrandRenderer renderer(sc.strands);
    const SrbfLight lights[] = {sc.light};
    renderer.set_lights(lights);
    for (const bool per_fragment : {true, false})
    for (const bool multiple : {false, true}) {
        gl::StrandSettings settings;
        settings.per_fragment = per_fragment;
        settings.hair.multiple = multiple;
        settings.samples = 1;                 // one fragment per pixel: a hair pixel holds exactly that fragment
        settings.background = glm::vec3(0.0f);
        settings.fiber_radius = 0.1f;         // 2r/p ≈ 2.5 at this framing: alpha clamps to 1, pixel = L_o
        const Image img = renderer.render(sc.camera, settings);
        const shading::LightingEvaluator ev(settings.hair.fibre, settings.hair.config);
        std::vector<std::pair<glm::vec3, glm::vec3>> got_want;
        double peak = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const float* p = img.at(x, y);
                if (p[0] + p[1] + p[2] <= 0.0f) continue;
                got_want.emplace_back(glm::vec3(p[0], p[1], p[2]), cpu_radiance(sc, ev, multiple, x, y));
                peak = std::max(peak, double(got_want.back().second.x));
            }
        double worst = 0;
        for (const auto& [got, want] : got_want)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(double(got[c]) - want[c]) / std::max(0.01 * peak, double(want[c])));
        std::printf("per fragment %d, multiple %d: %zu strand pixels, peak L_o %.3g, worst relative difference GPU vs CPU %.3g\n",
                    per_fragment, multiple, got_want.size(), peak, worst);
        EXPECT_GT(got_want.size(), 100u);  // the strand crosses most of the 128-px-wide image
        EXPECT_GT(peak, 0.04);             // and the highlight is on it (0.060: 000's literal M_t gave twice that)
        // Same GLSL on both sides; the GPU runs llvmpipe's float transcendentals, bilinear fetches at 8-bit
        // sub-texel precision and stores RGBA16F (11 significant bits), and the fragment's point is found
        // here in float: 2 % (relative, or of 1 % of the peak where L_o is darker).
        // Per strand point, interpolated along ~5-px segments: the view direction turns ~0.4° per segment
        // across a lobe of β_R = 7.5°; measured 1.6 % worst, allowed 3 %.
        EXPECT_LT(worst, per_fragment ? 0.02 : 0.03) << "multiple scattering " << multiple;
    }
}

TEST(StrandRenderer, CoverageIsTheProjectedFibreDiameter) {
    auto context = gl::Context::headless();
    const Scene sc;
    gl::StrandRenderer renderer(sc.strands);
    const SrbfLight lights[] = {sc.light};
    renderer.set_lights(lights);
    gl::StrandSettings settings;
    settings.samples = 4;  // MSAA: the 1-px line's area spreads over the pixels it partly covers
    settings.background = glm::vec3(0.0f);
    settings.fiber_radius = 0.004f;  // 2r/p ≈ 0.4
    const Image img = renderer.render(sc.camera, settings);
    const shading::LightingEvaluator ev(settings.hair.fibre, settings.hair.config);
    // The line is x-major: per column, Σ_y pixel / L_o = the fibre's coverage across one pixel column
    // (× 1/cos of the line's slope, the column's cut through a line of unit width), expected 2r/p.
    const glm::vec2 A = sc.camera.pixel(sc.a), B = sc.camera.pixel(sc.b);
    const float slope_factor = glm::length(B - A) / std::abs(B.x - A.x);
    double sum_ratio = 0, sum_expected = 0;
    int columns = 0;
    for (int x = 8; x < img.width - 8; ++x) {
        const float t = (float(x) + 0.5f - A.x) / (B.x - A.x);
        if (t < 0.05f || t > 0.95f) continue;
        const int y = static_cast<int>((A + t * (B - A)).y);
        const glm::vec3 p = fragment_point(sc.camera, sc.a, sc.b, x, y);
        const glm::vec3 L = cpu_radiance(sc, ev, true, x, y);
        // Ratios of dark pixels are RGBA16F rounding: at L_o ≥ 0.01 and coverage ≥ 0.1 a pixel holds ≥ 1e-3,
        // which half floats keep to 5e-4 relative.
        if (L.y < 0.01f) continue;
        double column = 0;
        for (int yy = 0; yy < img.height; ++yy) column += img.at(x, yy)[1];
        const float z = -(sc.camera.view() * glm::vec4(p, 1.0f)).z;
        const float pixel = 2.0f * z * std::tan(0.5f * sc.camera.fov_y) / float(sc.camera.height);
        sum_ratio += column / L.y;
        sum_expected += 2.0f * settings.fiber_radius / pixel * slope_factor;
        ++columns;
    }
    ASSERT_GT(columns, 40);
    const double mean_ratio = sum_ratio / columns, mean_expected = sum_expected / columns;
    std::printf("%d columns: mean coverage %.4f, expected 2r/p %.4f\n", columns, mean_ratio, mean_expected);
    EXPECT_LT(mean_expected, 0.9);  // the test needs alpha < 1
    // 4 MSAA samples quantise a pixel's coverage to 1/4; over 40+ columns the mean is within 5 %.
    EXPECT_NEAR(mean_ratio, mean_expected, 0.05 * mean_expected);
}

TEST(StrandRenderer, CoifRenderStrandsRefusesBadInputAndWritesNothing) {
    const auto dir = test::scratch_dir("strand-cli");
    const std::string out = (dir / "out.png").string();
    write_hair(dir / "one.hair", straight_strand({0, 0, 0}, {0, -10, 1}));
    std::ofstream(dir / "bad.json") << "{\"eta\": \"high\"}";
    std::ofstream(dir / "bad.hair") << "HAIRtruncated";
    const std::string good = " --strands '" + (dir / "one.hair").string() + "'";
    for (const std::string& args : {good + " --params '" + (dir / "bad.json").string() + "'",
                                   good + " --env '" + (dir / "missing.json").string() + "'",
                                   " --strands '" + (dir / "bad.hair").string() + "'",
                                   " --strands '" + (dir / "missing.hair").string() + "'"}) {
        const auto r = test::run_coif("render" + args + " -o '" + out + "'");
        EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("coif: error"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << args;
    }
    const auto r = test::run_coif("render" + good + " --radius -1 -o '" + out + "'");
    EXPECT_EQ(r.exit_code, 2) << r.err;  // a bad option value is a usage error
    EXPECT_FALSE(std::filesystem::exists(out));
    const auto ok = test::run_coif("render" + good + " --width 64 --height 48 -o '" + out + "'");
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
    EXPECT_TRUE(std::filesystem::exists(out));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace coif
