// SRBF fitting (offline/srbf_fit.h): recovery of known lights, error against N, determinism, energy.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "models/core/error.h"
#include "offline/srbf_fit.h"
#include "shaders/envmap.h"
#include "tests/common/test_data.h"

namespace {
using coif::EnvMap;
using coif::SrbfLight;

// A map point-sampled from lights at `width` (fine enough that its box filter down to the fit grid is
// the box-filtered model the fit assumes).
EnvMap synthesise(const std::vector<SrbfLight>& lights, int width) {
    return coif::render_srbf_lights(lights, width);
}

double angle_degrees(const glm::vec3& a, const glm::vec3& b) {
    return std::acos(std::clamp(double(glm::dot(glm::normalize(a), glm::normalize(b))), -1.0, 1.0)) * 180.0 / M_PI;
}

double energy(const SrbfLight& l) { return coif::luminance(glm::dvec3(l.L)) * coif::glsl::srbf_integral(l.lambda); }

const std::vector<SrbfLight> kKnownLights = {
    {{8.0f, 6.0f, 4.0f}, glm::normalize(glm::vec3(0.6f, 0.7f, -0.2f)), 0.12f},   // a small bright lamp
    {{1.0f, 1.5f, 2.5f}, glm::normalize(glm::vec3(-0.2f, 0.9f, 0.3f)), 0.6f},    // sky
    {{0.6f, 0.5f, 0.3f}, glm::normalize(glm::vec3(0.1f, -0.8f, 0.5f)), 0.8f},    // ground bounce
    {{3.0f, 1.0f, 0.5f}, glm::normalize(glm::vec3(-0.7f, 0.1f, -0.6f)), 0.25f},  // a warm window
};

TEST(SrbfFit, RecoversKnownLights) {
    const EnvMap map = synthesise(kKnownLights, 384);
    coif::SrbfFitSettings s;
    s.lights = int(kKnownLights.size());
    s.fit_width = 64;
    const coif::SrbfFitResult fit = coif::fit_srbf_lights(map, s);
    ASSERT_EQ(fit.lights.size(), kKnownLights.size());
    // The map is exactly representable: the residual is the difference between the 3×3 sub-sampled model
    // and the 6×6 point-sampled box filter of the map, well under 1 %.
    EXPECT_LT(fit.record.relative_l2_error_fit_grid, 0.01);
    EXPECT_LT(std::abs(fit.record.energy_error), 0.01);
    for (const SrbfLight& known : kKnownLights) {
        const SrbfLight* match = nullptr;
        for (const SrbfLight& l : fit.lights)
            if (!match || angle_degrees(l.omega, known.omega) < angle_degrees(match->omega, known.omega)) match = &l;
        // Centres within 1° (a fit-grid pixel is 5.6°, the narrowest lobe 6.9°), energies and bandwidths
        // within 2 %: what is left is the sampling difference above.
        EXPECT_LT(angle_degrees(match->omega, known.omega), 1.0) << known.lambda;
        EXPECT_NEAR(energy(*match) / energy(known), 1.0, 0.02) << known.lambda;
        EXPECT_NEAR(match->lambda / known.lambda, 1.0, 0.02) << known.lambda;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(match->L[c] / known.L[c], 1.0, 0.03) << known.lambda << " channel " << c;
    }
}

std::vector<SrbfLight> random_lights(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> n01;
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<SrbfLight> lights;
    for (int i = 0; i < n; ++i)
        lights.push_back({glm::vec3(u(rng), u(rng), u(rng)) * (0.2f + 5.0f * u(rng) * u(rng)),
                          glm::normalize(glm::vec3(n01(rng), n01(rng), n01(rng))), 0.08f + 0.6f * u(rng)});
    return lights;
}

TEST(SrbfFit, ErrorDoesNotIncreaseWithN) {
    const EnvMap map = synthesise(random_lights(24, 5), 256);
    double previous = 1e9;
    for (int n : {1, 2, 4, 8, 16}) {
        coif::SrbfFitSettings s;
        s.lights = n;
        s.fit_width = 48;
        const coif::SrbfFitResult fit = coif::fit_srbf_lights(map, s);
        // Strictly: more lights can only fit better; 1e-3 absolute absorbs solver tolerance (relative
        // cost change 1e-6 at convergence).
        EXPECT_LE(fit.record.relative_l2_error_fit_grid, previous + 1e-3) << "N = " << n;
        previous = fit.record.relative_l2_error_fit_grid;
    }
    EXPECT_LT(previous, 0.1);  // 16 lights for 24 overlapping ones: most of the map is captured
}

TEST(SrbfFit, IsDeterministicForASeed) {
    const EnvMap map = synthesise(random_lights(10, 9), 128);
    coif::SrbfFitSettings s;
    s.lights = 6;
    s.fit_width = 32;
    const auto a = coif::fit_srbf_lights(map, s);
    const auto b = coif::fit_srbf_lights(map, s);
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (size_t i = 0; i < a.lights.size(); ++i) {
        EXPECT_EQ(a.lights[i].L, b.lights[i].L);
        EXPECT_EQ(a.lights[i].omega, b.lights[i].omega);
        EXPECT_EQ(a.lights[i].lambda, b.lights[i].lambda);
    }
}

TEST(SrbfFit, KeepsBandwidthsInRangeAndLightsNonNegative) {
    const EnvMap map = synthesise(random_lights(10, 11), 128);
    coif::SrbfFitSettings s;
    s.lights = 8;
    s.fit_width = 32;
    s.lambda_min = 0.2;
    s.lambda_max = 1.0;
    for (const SrbfLight& l : coif::fit_srbf_lights(map, s).lights) {
        EXPECT_GE(l.lambda, 0.2f - 1e-6f);
        EXPECT_LE(l.lambda, 1.0f + 1e-6f);
        EXPECT_GE(std::min({l.L.r, l.L.g, l.L.b}), 0.0f);
        EXPECT_NEAR(glm::length(l.omega), 1.0f, 1e-6f);
    }
}

TEST(SrbfFit, RefusesAbsurdSettings) {
    const EnvMap map = synthesise(random_lights(3, 1), 64);
    for (int n : {0, -3, 100000}) {
        coif::SrbfFitSettings s;
        s.lights = n;
        EXPECT_THROW(coif::fit_srbf_lights(map, s), coif::Error) << n;
    }
    coif::SrbfFitSettings s;
    s.lights = 200;  // more than (32×16 pixels)/4 on a 32-wide grid
    s.fit_width = 32;
    EXPECT_THROW(coif::fit_srbf_lights(map, s), coif::Error);
    s.lights = 4;
    s.fit_width = 33;
    EXPECT_THROW(coif::fit_srbf_lights(map, s), coif::Error);
    s.fit_width = 32;
    s.lambda_min = 2.0;
    s.lambda_max = 1.0;
    EXPECT_THROW(coif::fit_srbf_lights(map, s), coif::Error);
}

TEST(SrbfFit, RealMapFitKeepsItsEnergy) {
    COIF_SHARED_DATA(path, "blender_studiolight_courtyard.exr");
    const EnvMap map = coif::load_envmap(path);
    coif::SrbfFitSettings s;
    s.lights = 10;
    s.fit_width = 32;
    const auto fit = coif::fit_srbf_lights(map, s);
    // The box-filtered model keeps ∫L: measured −1.7 % at this size (N = 10, 32×16 grid); 3 % bounds it.
    EXPECT_LT(std::abs(fit.record.energy_error), 0.03);
    EXPECT_LT(fit.record.relative_l2_error_fit_grid, fit.record.relative_l2_error);
    EXPECT_LT(fit.record.relative_l2_error, 0.8);
}

}  // namespace
