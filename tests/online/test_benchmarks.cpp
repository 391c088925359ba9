// The GPU measurements of online/benchmarks.h on llvmpipe: they run, return figures that make sense, and the
// lighting compute shader agrees with the same GLSL compiled as C++.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "online/benchmarks.h"
#include "online/gl_context.h"
#include "shaders/lighting.h"

namespace coif {
namespace {

TEST(Benchmarks, FillRateCountsEveryFragmentOfEveryLayer) {
    auto context = gl::Context::headless();
    gl::FillRateOptions o;
    o.width = 64;
    o.height = 32;
    o.layers = 3;
    o.frames = 2;
    const gl::FillRate r = gl::measure_fill_rate(o);
    EXPECT_GT(r.wall_ms_per_frame, 0.0);
    EXPECT_GT(r.gpu_ms_per_frame, 0.0);
    // The rates are the fragments drawn over the times measured.
    const double mfragments_per_frame = 64.0 * 32.0 * 3.0 * 1e-6;
    EXPECT_NEAR(r.mfragments_per_s_wall, mfragments_per_frame / (r.wall_ms_per_frame * 1e-3), 1e-9 * r.mfragments_per_s_wall);
    EXPECT_NEAR(r.mfragments_per_s_gpu, mfragments_per_frame / (r.gpu_ms_per_frame * 1e-3), 1e-9 * r.mfragments_per_s_gpu);
}

TEST(Benchmarks, GpuLightingMatchesTheCpuEvaluator) {
    auto context = gl::Context::headless();
    const shading::HairParams hair = shading::default_hair_params();
    const shading::LightingConfig config = shading::default_config(4);
    const shading::LightingEvaluator eval(hair, config);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    std::vector<glm::vec4> points(100), lights(5);  // 100: not a multiple of the 64-wide work groups
    for (auto& p : points) p = glm::vec4(std::asin(2.0f * U(rng) - 1.0f), 6.2831853f * U(rng) - 3.1415927f, 0, 0);
    for (auto& l : lights)
        l = glm::vec4(std::asin(2.0f * U(rng) - 1.0f), 6.2831853f * U(rng) - 3.1415927f, 0.05f * std::pow(40.0f, U(rng)),
                      0.02f * U(rng));
    const gl::GpuLightingRun gpu = gl::run_gpu_lighting(points, lights, hair, config, true, 1);
    ASSERT_EQ(gpu.single.size(), points.size());
    ASSERT_EQ(gpu.multiple.size(), points.size());
    EXPECT_GT(gpu.dispatch_seconds, 0.0);
    std::vector<glm::vec3> single(points.size()), multiple(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        for (const auto& l : lights) {
            single[i] += eval.single(points[i].x, points[i].y, l.x, l.y, l.z);
            multiple[i] += eval.multiple(points[i].x, points[i].y, l.x, l.y, l.z, l.w);
        }
    const double d = gl::max_relative_difference(gpu, single, multiple);
    std::printf("max |GPU - CPU| = %.3g of the largest value\n", d);
    // The same GLSL on both sides; they differ by float rounding and by the tables' bilinear filtering, whose
    // weights llvmpipe quantises to 8 bits (up to 1/512 of a table step): 1e-3 of the largest value bounds both.
    EXPECT_LT(d, 1e-3);
    EXPECT_GT(gl::max_relative_difference(gpu, multiple, single), 1e-3);  // and the measure sees a real difference
}

}  // namespace
}  // namespace coif
