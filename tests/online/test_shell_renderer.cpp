// The SATF shell renderer (online/shell_renderer.h) on llvmpipe: the lighting pass against the CPU
// evaluator of the lighting module, determinism, a parameter change shows in the next frame, lit hair.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "db/hrir_db.h"
#include "db/satf.h"
#include "models/core/error.h"
#include "online/gl_context.h"
#include "online/shell_renderer.h"
#include "shaders/lighting.h"

namespace coif {
namespace {

// A small database built once for the whole file (40 sectors: ~3 s on 2 cores). The renderer's
// behaviour, not the look-up's quality, is under test here.
const HrirDatabase& test_db() {
    static const HrirDatabase db = [] {
        const auto path = std::filesystem::temp_directory_path() / ("coif-shell-test-" + std::to_string(::getpid()) + ".db");
        BuildOptions b;
        b.params.sectors = 40;
        b.threads = 2;
        build_database(b, path);
        HrirDatabase d = HrirDatabase::open(path);
        return d;
    }();
    return db;
}
const SatfIndex& test_index() {
    static const SatfIndex index(test_db(), SatfOptions{});
    return index;
}

// One straight cluster hanging along −y, 10 cm long, radius 1 cm, uniform density.
HairStyle one_cluster_style() {
    const char* text = R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 4, "s_t": 4, "s_u": 8, "grid": [8, 4], "mesh": [2, 2], "gaussian_width": 0.05},
      "clusters": [{"name": "c0", "trajectory": [[0, 0, 0], [0, -5, 0], [0, -10, 0]], "a": [1.0], "b": [1.0],
                    "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}}]})";
    return parse_style(text, "<test style>");
}

Camera front_camera(const gl::ShellRenderer& r, int w = 96, int h = 64) {
    return Camera::orbit(r.bounds_min(), r.bounds_max(), 0.3f, 0.2f, w, h);
}

TEST(ShellRenderer, LightingPassMatchesCpuEvaluatorUnderOneNarrowLight) {
    auto context = gl::Context::headless();
    const HairStyle style = one_cluster_style();
    gl::ShellRenderer renderer(style, test_index(), glm::mat3(1.0f));
    SrbfLight light;
    light.L = glm::vec3(1.0f, 0.8f, 0.6f);
    light.omega = glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f));
    light.lambda = 0.1f;
    const SrbfLight lights[] = {light};
    renderer.set_lights(lights);
    const Camera camera = front_camera(renderer);
    gl::RenderTarget target(camera.width, camera.height, GL_RGBA16F, 1);
    target.bind();
    for (const bool multiple : {false, true}) {
    gl::ShellSettings settings;
    settings.multiple = multiple;
    renderer.draw(camera, settings);
    const std::vector<float> lit = renderer.read_lighting();
    const shading::LightingEvaluator ev(settings.hair, settings.config);
    const shading::SrbfLight cpu_light{light.omega, light.lambda, light.L};
    double worst = 0;
    for (int r = 0; r < renderer.lighting_rows(); ++r) {
        const std::vector<glm::vec3> s = renderer.lighting_sample(static_cast<std::size_t>(r));
        const shading::FibreFrame frame = shading::FibreFrame::from_tangent(s[1], s[2]);
        const glm::vec3 view = glm::normalize(camera.eye - s[0]);
        const glm::vec3 want = ev.shade(frame, view, std::span(&cpu_light, 1), {}, multiple).total();
        const glm::vec3 got(lit[r * 27 + 0], lit[r * 27 + 1], lit[r * 27 + 2]);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(got[c]) - want[c]) / std::max(1e-3, double(want[c])));
        if (r == 0) std::printf("row 0: GPU %g %g %g, CPU %g %g %g\n", got.x, got.y, got.z, want.x, want.y, want.z);
    }
    std::printf("multiple %d: worst relative difference GPU lighting pass vs CPU evaluator: %.3g\n", multiple, worst);
    // Same GLSL on both sides; the GPU runs float transcendental functions of llvmpipe and bilinear
    // texture fetches at GL's 8-bit sub-texel precision, so allow 1 %.
    EXPECT_LT(worst, 0.01) << "multiple scattering " << multiple;
    }
}

}  // namespace
}  // namespace coif
