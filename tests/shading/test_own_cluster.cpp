// The own cluster's shadow on a shell fragment (shaders/lighting/own_cluster.glsl), compiled as C++.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "shaders/glsl_prelude.h"
#include "shaders/lighting.h"

namespace coif::glsl {
#include "shaders/lighting/own_cluster.glsl"
}  // namespace coif::glsl

namespace coif {
namespace {

using glsl::vec2;
using glsl::vec3;
using glsl::vec4;

TEST(OwnCluster, PathIsTheChordTowardTheLight) {
    // Facing the light: 1 − ρ to the surface; away from it: 1 + ρ; on the axis: 1 whatever the side.
    EXPECT_FLOAT_EQ(glsl::own_cluster_path(0.6f, 1.0f, 0.0f), 0.4f);
    EXPECT_FLOAT_EQ(glsl::own_cluster_path(0.6f, -1.0f, 0.0f), 1.6f);
    EXPECT_FLOAT_EQ(glsl::own_cluster_path(0.0f, 0.3f, std::sqrt(1.0f - 0.09f)), 1.0f);
    // At the surface (ρ = 1) a fibre whose light grazes its cluster (Δ = 90°) sees it unshadowed.
    EXPECT_NEAR(glsl::own_cluster_path(1.0f, 0.0f, 1.0f), 0.0f, 1e-6f);
    // The chord from (ρ, 0) toward an in-plane direction at Δ from the radial, by geometry.
    const float rho = 0.5f, d = 2.2f;
    const float x = rho, y = 0.0f, dx = std::cos(d), dy = std::sin(d);
    const float b = x * dx + y * dy, c = x * x + y * y - 1.0f;
    EXPECT_NEAR(glsl::own_cluster_path(rho, std::cos(d), std::sin(d)), -b + std::sqrt(b * b - c), 1e-6f);
    EXPECT_FLOAT_EQ(glsl::own_cluster_transmittance(0.0f, rho, dx, dy), 1.0f);
    EXPECT_NEAR(glsl::own_cluster_transmittance(2.0f, 0.6f, -1.0f, 0.0f), std::exp(-3.2f), 1e-6f);
}

TEST(OwnCluster, StretchIsOneOverTheSineOfTheAngleToTheAxisAtMostFour) {
    const vec3 T(0.0f, 1.0f, 0.0f);
    EXPECT_FLOAT_EQ(glsl::own_cluster_stretch(vec3(1.0f, 0.0f, 0.0f), T), 1.0f);
    EXPECT_NEAR(glsl::own_cluster_stretch(vec3(std::sin(0.5f), std::cos(0.5f), 0.0f), T), 1.0f / std::sin(0.5f), 1e-5f);
    EXPECT_FLOAT_EQ(glsl::own_cluster_stretch(T, T), 4.0f);
}

TEST(OwnCluster, RaysLeaveAFlatClusterThroughItsEllipse) {
    // A cluster 3 wide along e1 and 0.5 along T × e1 (e2): a ray across the axis leaves it at the ellipse's radius in
    // its direction, x²/A² + y²/B² = 1, times the stretch of its angle to the axis.
    const vec3 T(0.0f, 1.0f, 0.0f), e1(1.0f, 0.0f, 0.0f);
    const vec3 e2 = glm::cross(T, e1);
    const float A = 3.0f, B = 0.5f;
    EXPECT_NEAR(glsl::own_cluster_exit(e1, T, e1, A, B), A, 1e-5f);
    EXPECT_NEAR(glsl::own_cluster_exit(-e2, T, e1, A, B), B, 1e-5f);
    for (const float a : {0.3f, 1.0f, 2.0f}) {
        const vec3 u = std::cos(a) * e1 + std::sin(a) * e2;
        const float r = glsl::own_cluster_exit(u, T, e1, A, B);
        const glm::vec2 at = r * glm::vec2(std::cos(a), std::sin(a));
        EXPECT_NEAR(at.x * at.x / (A * A) + at.y * at.y / (B * B), 1.0f, 1e-5f) << a;  // on the ellipse
        // Tilted toward the axis by 30°: the same point of the ellipse, reached 1 / sin 60° farther along the ray.
        const vec3 tilted = std::sin(glm::radians(60.0f)) * u + std::cos(glm::radians(60.0f)) * T;
        EXPECT_NEAR(glsl::own_cluster_exit(tilted, T, e1, A, B), r / std::sin(glm::radians(60.0f)), 1e-4f) << a;
    }
    // A round cluster is left at its radius times own_cluster_stretch, as before the ellipse (the widest half-axis
    // along the axis itself, where the stretch caps at 4).
    EXPECT_NEAR(glsl::own_cluster_exit(glm::normalize(vec3(1.0f, 1.0f, 1.0f)), T, e1, 2.0f, 2.0f),
                2.0f * glsl::own_cluster_stretch(glm::normalize(vec3(1.0f, 1.0f, 1.0f)), T), 1e-5f);
    EXPECT_FLOAT_EQ(glsl::own_cluster_exit(T, T, e1, A, B), 4.0f * A);
    // Counting the neighbours in the ellipse, a ray starts at most the narrow half-axis out (times its stretch): along
    // the wide axis at B, not A; along the narrow one where it leaves; a round cluster where it leaves, either way.
    EXPECT_FLOAT_EQ(glsl::own_cluster_shadow_start(e1, T, e1, A, B, false), glsl::own_cluster_exit(e1, T, e1, A, B));
    EXPECT_NEAR(glsl::own_cluster_shadow_start(e1, T, e1, A, B, true), B, 1e-5f);
    EXPECT_NEAR(glsl::own_cluster_shadow_start(-e2, T, e1, A, B, true), B, 1e-5f);
    const vec3 tilted = glm::normalize(e1 + T);
    EXPECT_NEAR(glsl::own_cluster_shadow_start(tilted, T, e1, A, B, true), B * std::sqrt(2.0f), 1e-5f);
    for (const float a : {0.3f, 1.0f, 2.0f}) {
        const vec3 u = std::cos(a) * e1 + std::sin(a) * e2;
        EXPECT_LE(glsl::own_cluster_shadow_start(u, T, e1, A, B, true), glsl::own_cluster_exit(u, T, e1, A, B) + 1e-6f) << a;
        EXPECT_NEAR(glsl::own_cluster_shadow_start(u, T, e1, 2.0f, 2.0f, true), glsl::own_cluster_exit(u, T, e1, 2.0f, 2.0f),
                    1e-5f) << a;
    }
}

// re(Δ) of the shells' layout at Δ.
float series(vec3 c01, vec4 c23, vec2 c4, double delta) {
    double v = c01.x + c01.y * std::cos(delta) + c01.z * std::sin(delta);
    v += c23.x * std::cos(2 * delta) + c23.y * std::sin(2 * delta) + c23.z * std::cos(3 * delta) + c23.w * std::sin(3 * delta);
    v += c4.x * std::cos(4 * delta) + c4.y * std::sin(4 * delta);
    return static_cast<float>(v);
}

// The table's builder against O's harmonics in closed form: at ρ = 0 the chord is 1 whatever the side (O = e^−τ);
// at ρ = 1 and a large τ, O is 1 on the side facing the light and 0 behind (a half circle: o_0 = 1/2,
// o_m = 2 sin(mπ/2) / (mπ)). Tolerances: the trapezoid rule's error, 1e-9 and (for the steep fall behind a kink) 1e-3.
TEST(OwnCluster, TableBuilderGivesTheClosedFormsOfTheChord) {
    for (const double tau : {0.0, 0.7, 3.0}) {
        const auto o = shading::own_cluster_direct(tau, 0.0);
        EXPECT_NEAR(o[0], std::exp(-tau), 1e-9) << tau;
        for (int m = 1; m < 9; ++m) EXPECT_NEAR(o[m], 0.0, 1e-9) << tau << " " << m;
    }
    const auto o = shading::own_cluster_direct(1e4, 1.0);
    EXPECT_NEAR(o[0], 0.5, 1e-3);
    for (int m = 1; m < 9; ++m) EXPECT_NEAR(o[m], 2.0 * std::sin(m * std::numbers::pi / 2) / (m * std::numbers::pi), 1e-3) << m;
}

// h's harmonics 0..4 of re·O, integrated directly with 4096 points.
std::array<double, 9> product_harmonics(vec3 c01, vec4 c23, vec2 c4, float tau, float rho) {
    const int n = 4096;
    std::array<double, 9> want{};
    for (int q = 0; q < n; ++q) {
        const double d = 2 * std::numbers::pi * q / n;
        const double h = series(c01, c23, c4, d) * std::exp(-tau * glsl::own_cluster_path(rho, float(std::cos(d)), float(std::sin(d))));
        want[0] += h / n;
        for (int k = 1; k <= 4; ++k) {
            want[2 * k - 1] += 2 * h * std::cos(k * d) / n;
            want[2 * k] += 2 * h * std::sin(k * d) / n;
        }
    }
    return want;
}

TEST(OwnCluster, HarmonicsOfTheProductMatchDirectIntegration) {
    const shading::LutBinding tables(shading::global_lighting_tables().set());
    const vec3 c01(0.8f, 0.3f, -0.2f);
    const vec4 c23(0.1f, 0.05f, -0.04f, 0.02f);
    const vec2 c4(0.01f, -0.015f);
    vec3 h01;
    vec4 h23;
    vec2 h4;
    // τ = 0: O = 1 (o_0 = 1 exactly, the others 0 to the builder's rounding), and re comes back to float rounding.
    glsl::own_cluster_harmonics(0.0f, 0.7f, c01, c23, c4, h01, h23, h4);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(h01[i], c01[i], 1e-6f) << i;
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(h23[i], c23[i], 1e-6f) << i;
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(h4[i], c4[i], 1e-6f) << i;
    // τ > 0, between the table's grid points (ρ on a 1/32 grid, τ on a grid of τ/(τ + 2)) and on them, up to τ = 16
    // (an outer layer's 4 radii of stretch at τ_R = 4): the product is exact, so the error is the bilinear read's.
    // Stated bound 1e-3 of re's mean (0.8), measured 4.9e-4 (τ = 16, ρ = 0.97, where O changes fastest with ρ);
    // the 16-point rule this replaced was off by 4.1e-2 at ρ = 1.
    double worst = 0.0;
    for (const float tau : {0.3f, 0.5f, 1.5f, 2.71f, 4.0f, 9.0f, 16.0f})
        for (const float rho : {0.1f, 0.4f, 0.77f, 0.8f, 0.9f, 0.97f, 1.0f}) {
            glsl::own_cluster_harmonics(tau, rho, c01, c23, c4, h01, h23, h4);
            const auto want = product_harmonics(c01, c23, c4, tau, rho);
            const float got[9] = {h01.x, h01.y, h01.z, h23.x, h23.y, h23.z, h23.w, h4.x, h4.y};
            for (int i = 0; i < 9; ++i) {
                worst = std::max(worst, std::abs(got[i] - want[i]) / 0.8);
                EXPECT_NEAR(got[i], want[i], 1e-3 * 0.8) << "tau " << tau << " rho " << rho << " coefficient " << i;
            }
        }
    std::printf("worst error of the product's harmonics, of re's mean: %.2e\n", worst);
    // The side facing the light keeps more of it: with re = 1 and the light at Δ = 0, h(0) > h(π).
    glsl::own_cluster_harmonics(1.5f, 0.8f, vec3(1.0f, 0.0f, 0.0f), vec4(0.0f), vec2(0.0f), h01, h23, h4);
    EXPECT_GT(series(h01, h23, h4, 0.0), 2.0f * series(h01, h23, h4, std::numbers::pi));
}

// With the forward-scattered light (SHELL_OWN 2) each channel's factor is (1 − d_f) O(τ) + d_f O(τ · loss): its series
// times re's must be that function's harmonics, integrated directly. The limits: loss 1 (fibres that pass all light
// forward scatter none of it away) or d_f 0 give O's own product; loss 0 gives (1 − d_f) O + d_f, no shadow for
// that share. Tolerance: the table's bilinear read, as in HarmonicsOfTheProductMatchDirectIntegration (1e-3 of re's mean).
TEST(OwnCluster, ForwardScatteredLightIsTheMixOfTwoDepths) {
    const shading::LutBinding tables(shading::global_lighting_tables().set());
    const vec3 c01(0.8f, 0.3f, -0.2f);
    const vec4 c23(0.1f, 0.05f, -0.04f, 0.02f);
    const vec2 c4(0.01f, -0.015f);
    double worst = 0.0;
    for (const float tau : {0.5f, 2.71f, 9.0f})
        for (const float rho : {0.4f, 0.9f, 1.0f})
            for (const float loss : {0.0f, 0.64f, 0.85f, 1.0f})
                for (const float d_f : {0.0f, 0.7f}) {
                    float p0;
                    vec4 p1234;
                    vec4 p5678;
                    glsl::own_cluster_series(tau, rho, p0, p1234, p5678);
                    float q0;
                    vec4 q1234;
                    vec4 q5678;
                    glsl::own_cluster_forward_series(tau, rho, loss, d_f, p0, p1234, p5678, q0, q1234, q5678);
                    vec3 h01;
                    vec4 h23;
                    vec2 h4;
                    glsl::own_cluster_product(q0, q1234, q5678, c01, c23, c4, h01, h23, h4);
                    const auto direct = product_harmonics(c01, c23, c4, tau, rho);
                    const auto forward = product_harmonics(c01, c23, c4, tau * loss, rho);
                    const float got[9] = {h01.x, h01.y, h01.z, h23.x, h23.y, h23.z, h23.w, h4.x, h4.y};
                    for (int i = 0; i < 9; ++i) {
                        const double want = (1.0 - d_f) * direct[i] + d_f * forward[i];
                        worst = std::max(worst, std::abs(got[i] - want) / 0.8);
                        EXPECT_NEAR(got[i], want, 1e-3 * 0.8)
                            << "tau " << tau << " rho " << rho << " loss " << loss << " d_f " << d_f << " coefficient " << i;
                    }
                }
    std::printf("worst error of the forward mix's harmonics, of re's mean: %.2e\n", worst);
    // More light reaches the fibre with its forward-scattered share than without, and at most as much as unshadowed.
    vec3 h01;
    vec4 h23;
    vec2 h4;
    glsl::own_cluster_harmonics(3.0f, 0.5f, vec3(1.0f, 0.0f, 0.0f), vec4(0.0f), vec2(0.0f), h01, h23, h4);
    const float unscattered = h01.x;
    float p0;
    vec4 p1234;
    vec4 p5678;
    glsl::own_cluster_series(3.0f, 0.5f, p0, p1234, p5678);
    glsl::own_cluster_forward_series(3.0f, 0.5f, 0.64f, 0.7f, p0, p1234, p5678, p0, p1234, p5678);
    glsl::own_cluster_product(p0, p1234, p5678, vec3(1.0f, 0.0f, 0.0f), vec4(0.0f), vec2(0.0f), h01, h23, h4);
    EXPECT_GT(h01.x, 1.5f * unscattered);
    EXPECT_LT(h01.x, 1.0f);
}

}  // namespace
}  // namespace coif
