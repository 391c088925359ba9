// Environment maps: the pixel <-> direction mapping (shaders/envmap.glsl), solid angles, the SRBF
// integral, downsampling, validation of bad maps, lights files and rotation.
#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "models/core/atomic_file.h"
#include "models/core/checksum.h"
#include "models/core/error.h"
#include "offline/envmap.h"
#include "offline/srbf_fit.h"
#include "offline/srbf_lights.h"
#include "shaders/envmap.h"
#include "tests/common/test_data.h"

namespace {
using coif::EnvMap;
using coif::SrbfLight;
namespace glsl = coif::glsl;

// float evaluation of sin/cos/atan2/acos: round trips hold to a few float ulps of π.
constexpr float kMappingTolerance = 2e-5f;

TEST(EnvMapping, OrientationIsTheDocumentedOne) {
    // shaders/envmap.glsl: row 0 = +y, centre column = +x, quarter column = -z, three quarters = +z, edges = -x.
    const auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < kMappingTolerance; };
    EXPECT_TRUE(near(glsl::envmap_direction({0.5f, 0.5f}), {1, 0, 0}));
    EXPECT_TRUE(near(glsl::envmap_direction({0.25f, 0.5f}), {0, 0, -1}));
    EXPECT_TRUE(near(glsl::envmap_direction({0.75f, 0.5f}), {0, 0, 1}));
    EXPECT_TRUE(near(glsl::envmap_direction({0.0f, 0.5f}), {-1, 0, 0}));
    EXPECT_TRUE(near(glsl::envmap_direction({0.3f, 0.0f}), {0, 1, 0}));
    EXPECT_TRUE(near(glsl::envmap_direction({0.3f, 1.0f}), {0, -1, 0}));
}

TEST(EnvMapping, UvToDirectionToUvRoundTrips) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    for (int i = 0; i < 10000; ++i) {
        // Away from the poles (u undefined there) and the -x seam (u = 0 and 1 are the same column).
        const glm::vec2 uv(0.001f + 0.998f * u01(rng), 0.001f + 0.998f * u01(rng));
        const glm::vec3 w = glsl::envmap_direction(uv);
        EXPECT_NEAR(glm::length(w), 1.0f, 1e-6f);
        const glm::vec2 back = glsl::envmap_uv(w);
        ASSERT_NEAR(back.x, uv.x, kMappingTolerance) << uv.x << "," << uv.y;
        ASSERT_NEAR(back.y, uv.y, kMappingTolerance) << uv.x << "," << uv.y;
    }
}

TEST(EnvMapping, DirectionToUvToDirectionRoundTripsEverywhere) {
    std::mt19937 rng(8);
    std::normal_distribution<float> n01;
    for (int i = 0; i < 10000; ++i) {
        const glm::vec3 w = glm::normalize(glm::vec3(n01(rng), n01(rng), n01(rng)));
        const glm::vec3 back = glsl::envmap_direction(glsl::envmap_uv(w));
        // acos loses precision next to the poles: 1e-3 rad at |y| → 1 in float (sqrt of the ulp).
        ASSERT_LT(glm::length(back - w), 1e-3f);
    }
}

TEST(EnvMapping, PixelCentresAndSolidAnglesCoverTheSphere) {
    for (int width : {8, 64, 1024}) {
        const EnvMap map(width, width / 2);
        double total = 0.0;
        for (int row = 0; row < map.height; ++row) total += map.width * map.pixel_solid_angle(row);
        // float evaluation per row, summed in double: relative 1e-6.
        EXPECT_NEAR(total / (4.0 * M_PI), 1.0, 1e-6) << width;
        // pixel (col,row) → uv of its centre → the same pixel.
        for (int row = 0; row < map.height; row += 3)
            for (int col = 0; col < map.width; col += 5) {
                const glm::vec2 uv = glsl::envmap_uv(map.direction(col, row));
                EXPECT_EQ(int(std::floor(uv.x * map.width)), col);
                EXPECT_EQ(int(std::floor(uv.y * map.height)), row);
            }
    }
}

TEST(Srbf, IntegralMatchesQuadrature) {
    // ∫G over the sphere in closed form (srbf_integral) vs the pixel sum of a 2048×1024 map; the
    // quadrature resolves lobes ≥ 0.02 rad (7 pixels) to < 1e-3.
    const EnvMap grid(2048, 1024);
    const glm::vec3 centre = glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f));
    for (float lambda : {0.02f, 0.1f, 0.5f, 2.0f, 8.0f}) {
        double sum = 0.0;
        for (int row = 0; row < grid.height; ++row) {
            double row_sum = 0.0;
            for (int col = 0; col < grid.width; ++col) row_sum += glsl::srbf_G(grid.direction(col, row), centre, lambda);
            sum += row_sum * grid.pixel_solid_angle(row);
        }
        EXPECT_NEAR(sum / glsl::srbf_integral(lambda), 1.0, 1e-3) << lambda;
    }
    // Table 1: G = 1 at the centre, e^{-4/λ²} at the antipode.
    // (float: ω·ω of a normalised vector is 1 within ~1e-7, amplified by 2/λ² = 22.)
    EXPECT_NEAR(glsl::srbf_G(centre, centre, 0.3f), 1.0f, 1e-5f);
    EXPECT_NEAR(glsl::srbf_G(-centre, centre, 2.0f), std::exp(-1.0f), 1e-6f);
}

TEST(Srbf, LobeCosineIsTheInverseOfTheLobesEnergyFraction) {
    // srbf_lobe_cos(λ, ξ) is the cos γ with a fraction ξ of G's energy at smaller cosines (farther from the centre). The
    // energy at cos γ < c is 2π ∫_{−1}^{c} exp(2(μ − 1)/λ²) dμ = πλ² (e^{2(c−1)/λ²} − e^{−4/λ²}): inverted exactly,
    // to float precision (1e-4 of the fraction), from the narrowest fitted light to a nearly constant one.
    for (float lambda : {0.033f, 0.1f, 0.5f, 2.0f, 4.0f}) {
        const double l2 = double(lambda) * lambda;
        for (float xi : {0.01f, 0.1f, 0.5f, 0.9f, 0.99f}) {
            const double c = glsl::srbf_lobe_cos(lambda, xi);
            ASSERT_GE(c, -1.0);
            ASSERT_LE(c, 1.0);
            const double below = M_PI * l2 * (std::exp(2.0 * (c - 1.0) / l2) - std::exp(-4.0 / l2));
            EXPECT_NEAR(below / glsl::srbf_integral(lambda), xi, 1e-4) << "lambda " << lambda << " xi " << xi;
        }
        // ξ = 1 is the centre; a wide light sends 38 % of its energy from the far hemisphere (cos γ < 0).
        EXPECT_FLOAT_EQ(glsl::srbf_lobe_cos(lambda, 1.0f), 1.0f);
    }
    EXPECT_NEAR(glsl::srbf_lobe_cos(2.0f, 0.3775f), 0.0f, 1e-3f);
    // The narrowest light's strata: near the centre at γ ≈ λ √(−ln(1 − ξ')) for the energy fraction ξ' inside γ.
    EXPECT_NEAR(std::acos(glsl::srbf_lobe_cos(0.033f, 0.5f)), 0.033 * std::sqrt(std::log(2.0)), 1e-3);
}

EnvMap random_map(int width, unsigned seed) {
    EnvMap map(width, width / 2);
    std::mt19937 rng(seed);
    std::exponential_distribution<float> e(1.0f);
    for (auto& p : map.radiance) p = glm::vec3(e(rng), e(rng), e(rng));
    return map;
}

TEST(EnvMapDownsample, PreservesEnergyAndConstants) {
    const EnvMap map = random_map(256, 1);
    const glm::dvec3 E = coif::envmap_energy(map);
    for (int w : {128, 100, 64, 10, 8}) {
        const EnvMap small = coif::downsample_envmap(map, w);
        const glm::dvec3 Es = coif::envmap_energy(small);
        // Exact box filter in (φ, cos θ): energy equal up to float storage of the pixels (1e-6).
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(Es[c] / E[c], 1.0, 1e-5) << w;
    }
    EnvMap flat(256, 128);
    for (auto& p : flat.radiance) p = glm::vec3(2.0f, 1.0f, 0.5f);
    for (const glm::vec3& p : coif::downsample_envmap(flat, 40).radiance)
        EXPECT_LT(glm::length(p - glm::vec3(2.0f, 1.0f, 0.5f)), 1e-5f);
    EXPECT_THROW(coif::downsample_envmap(map, 7), coif::Error);
    EXPECT_THROW(coif::downsample_envmap(map, 512), coif::Error);
}

coif::Image image_of(int w, int h, float value) { return coif::Image(w, h, 3, value); }

TEST(EnvMapValidation, RefusesMapsThatAreNot2To1) {
    try {
        coif::envmap_from_image(image_of(100, 100, 1.0f), "square.exr");
        FAIL() << "a square map was accepted";
    } catch (const coif::Error& e) {
        EXPECT_NE(std::string(e.what()).find("2 x height"), std::string::npos) << e.what();
    }
    EXPECT_THROW(coif::envmap_from_image(image_of(6, 3, 1.0f), "tiny.exr"), coif::Error);
}

TEST(EnvMapValidation, RefusesNonFiniteAndNegativePixelsNamingThePixel) {
    for (float bad : {NAN, INFINITY, -INFINITY, -0.5f}) {
        coif::Image img = image_of(16, 8, 1.0f);
        img.at(5, 3)[1] = bad;
        try {
            coif::envmap_from_image(img, "bad.exr");
            FAIL() << "accepted " << bad;
        } catch (const coif::Error& e) {
            EXPECT_EQ(e.place(), "pixel (col 5, row 3)") << e.what();
        }
    }
    EXPECT_THROW(coif::envmap_from_image(image_of(16, 8, 0.0f), "black.exr"), coif::Error);
}

TEST(EnvMapValidation, ClampsCompressionNoiseAndCountsIt) {
    // -0.01 against a mean of 1 is 1 %: under kNegativeTolerance (5 %), so it is DWAB-style noise.
    coif::Image img = image_of(16, 8, 1.0f);
    img.at(1, 1)[0] = -0.01f;
    img.at(2, 2)[2] = -0.02f;
    std::size_t clamped = 0;
    const EnvMap map = coif::envmap_from_image(img, "noisy.exr", &clamped);
    EXPECT_EQ(clamped, 2u);
    EXPECT_EQ(map.at(1, 1).r, 0.0f);
    EXPECT_EQ(map.at(2, 2).b, 0.0f);
}

TEST(EnvMapLoad, EmptyAndMissingFilesGiveClearErrors) {
    const auto dir = coif::test::scratch_dir("env-load");
    coif::write_file_atomic(dir / "empty.hdr", std::string_view());
    EXPECT_THROW(coif::load_envmap(dir / "empty.hdr"), coif::Error);
    EXPECT_THROW(coif::load_envmap(dir / "missing.hdr"), coif::Error);
    coif::write_file_atomic(dir / "junk.exr", std::string_view("not an image at all"));
    EXPECT_THROW(coif::load_envmap(dir / "junk.exr"), coif::Error);
}

TEST(EnvMapLoad, EightBitImagesComeWithAWarning) {
    const auto dir = coif::test::scratch_dir("env-ldr");
    coif::write_image(dir / "ldr.png", image_of(32, 16, 0.5f));
    coif::EnvMapLoadInfo info;
    const EnvMap map = coif::load_envmap(dir / "ldr.png", &info);
    EXPECT_FALSE(info.floating_point);
    ASSERT_EQ(info.warnings.size(), 1u);
    EXPECT_NE(info.warnings[0].find("8-bit"), std::string::npos) << info.warnings[0];
    EXPECT_EQ(map.width, 32);
}

TEST(EnvMapLoad, RealMapsLoadWithTheirDocumentedStatistics) {
    // ../shared/data/PROVENANCE.md §2: city.exr, 1024×512, EXR channel means 1.050 1.058 1.035 (per pixel).
    COIF_SHARED_DATA(path, "blender_studiolight_city.exr");
    coif::EnvMapLoadInfo info;
    const EnvMap map = coif::load_envmap(path, &info);
    EXPECT_EQ(map.width, 1024);
    EXPECT_EQ(map.height, 512);
    glm::dvec3 mean(0.0);
    for (const glm::vec3& p : map.radiance) mean += glm::dvec3(p);
    mean /= double(map.radiance.size());
    // Clamping the tiny DWAB negatives changes the means by < 1e-5; the table prints 4 digits.
    EXPECT_NEAR(mean.r, 1.050345, 1e-4);
    EXPECT_NEAR(mean.g, 1.057692, 1e-4);
    EXPECT_NEAR(mean.b, 1.035343, 1e-4);
    EXPECT_GT(info.clamped_negatives, 0u);
    // The sun: brightest pixel at (row 120, col 614) per PROVENANCE.md.
    size_t best = 0;
    for (size_t i = 0; i < map.radiance.size(); ++i)
        if (coif::luminance(map.radiance[i]) > coif::luminance(map.radiance[best])) best = i;
    EXPECT_EQ(best / 1024, 120u);
    EXPECT_EQ(best % 1024, 614u);
}

TEST(SrbfLightsFile, RoundTripsAndValidates) {
    coif::SrbfLightSet set;
    set.lights = {{{1.0f, 2.0f, 3.0f}, glm::normalize(glm::vec3(1, 1, 0)), 0.25f}, {{0.5f, 0.5f, 0.5f}, {0, 1, 0}, 2.0f}};
    set.source = coif::SrbfSource{"map.exr", 0x0123456789abcdefull, 64, 32};
    coif::SrbfFitRecord rec;
    rec.lights = 2;
    rec.seed = 3;
    rec.fit_width = 64;
    rec.supersampling = 3;
    rec.energy_error_rgb = {0.1, 0.2, 0.3};
    set.fit = rec;
    const std::string text = coif::srbf_lights_to_json(set);
    const coif::SrbfLightSet back = coif::srbf_lights_from_json(text, "x.json");
    ASSERT_EQ(back.lights.size(), 2u);
    EXPECT_EQ(back.lights[0].L, set.lights[0].L);
    EXPECT_LT(glm::length(back.lights[0].omega - set.lights[0].omega), 1e-6f);
    EXPECT_EQ(back.lights[1].lambda, 2.0f);
    EXPECT_EQ(back.source->checksum, 0x0123456789abcdefull);
    EXPECT_EQ(back.fit->supersampling, 3);
    EXPECT_EQ(coif::srbf_lights_to_json(back), text);

    const auto bad = [&](const std::string& from, const std::string& to, const std::string& place) {
        std::string t = text;
        const auto at = t.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        t.replace(at, from.size(), to);
        try {
            coif::srbf_lights_from_json(t, "x.json");
            FAIL() << "accepted " << to;
        } catch (const coif::Error& e) {
            EXPECT_EQ(e.place(), place) << e.what();
        }
    };
    bad("\"lambda\": 0.25", "\"lambda\": 0.0", "JSON /lights/0/lambda");
    bad("\"lambda\": 2.0", "\"lambda\": 50.0", "JSON /lights/1/lambda");
    bad("\"format\": \"coif-srbf-lights\"", "\"format\": \"other\"", "JSON /format");
    bad("\"lights\": 2,", "\"lights\": 3,", "JSON /fit/lights");
    bad("\"checksum\": \"0123456789abcdef\"", "\"checksum\": \"12\"", "JSON /source/checksum");
    bad("1.0,\n        2.0", "-1.0,\n        2.0", "JSON /lights/0/L");
    bad("\"lights\": [", "\"lights\": [], \"x\": [", "JSON /lights");
    EXPECT_THROW(coif::srbf_lights_from_json("{\"format\": ", "x.json"), coif::Error);
}

TEST(SrbfLightsRotation, RotatingTheLightsRotatesTheEnvironment) {
    std::vector<SrbfLight> lights = {{{1, 2, 3}, glm::normalize(glm::vec3(1, 0.5f, -0.2f)), 0.3f},
                                     {{3, 1, 1}, glm::normalize(glm::vec3(-0.3f, -1, 0.4f)), 0.8f}};
    const float angle = 1.1f;
    const auto rotated = coif::rotate_srbf_lights_y(lights, angle);
    const glm::mat3 R(glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0)));
    std::mt19937 rng(3);
    std::normal_distribution<float> n01;
    for (int i = 0; i < 100; ++i) {
        const glm::vec3 w = glm::normalize(glm::vec3(n01(rng), n01(rng), n01(rng)));
        // L_rot(R ω) = L(ω); float evaluation: 1e-5 relative.
        const glm::vec3 a = coif::evaluate_srbf_lights(rotated, R * w);
        const glm::vec3 b = coif::evaluate_srbf_lights(lights, w);
        EXPECT_LT(glm::length(a - b), 1e-5f * (1.0f + glm::length(b)));
    }
    // Turning by 90° about +y takes +x to -z (right-handed): the map's centre column moves to the quarter column.
    const auto quarter = coif::rotate_srbf_lights_y(std::vector<SrbfLight>{{{1, 1, 1}, {1, 0, 0}, 0.1f}}, float(M_PI / 2));
    EXPECT_LT(glm::length(quarter[0].omega - glm::vec3(0, 0, -1)), 1e-6f);
    const glm::dvec3 E0 = coif::srbf_lights_energy(lights), E1 = coif::srbf_lights_energy(rotated);
    EXPECT_EQ(E0, E1);
}

TEST(SrbfLightsRotation, RotatingTheMapTurnsItAsTheLightsTurn) {
    // A map rendered from lights and then turned equals the map rendered from the turned lights, for a turn
    // by whole columns exactly up to the renderer's float rounding (1e-4 relative), and between columns to
    // the linear interpolation's error (3 % of the peak: 5.6° of a 0.3-wide lobe on a 64-px map). The energy
    // is kept (sums of interpolated periodic rows: 1e-5) and a full turn is the identity.
    const std::vector<SrbfLight> lights = {{{4, 3, 2}, glm::normalize(glm::vec3(1, 0.4f, 0.2f)), 0.3f},
                                           {{0.5f, 0.7f, 1.0f}, {0, 1, 0}, 1.0f}};
    const coif::EnvMap map = coif::render_srbf_lights(lights, 64);
    for (const float angle : {float(M_PI / 2), float(2 * M_PI * 5 / 64), 1.0f}) {
        const coif::EnvMap turned = coif::rotate_envmap_y(map, angle);
        const coif::EnvMap want = coif::render_srbf_lights(coif::rotate_srbf_lights_y(lights, angle), 64);
        float worst = 0, peak = 0;
        for (size_t i = 0; i < want.radiance.size(); ++i) {
            worst = std::max(worst, glm::length(turned.radiance[i] - want.radiance[i]));
            peak = std::max(peak, glm::length(want.radiance[i]));
        }
        const bool whole_columns = std::abs(angle - float(M_PI / 2)) < 1e-6f || std::abs(angle - float(2 * M_PI * 5 / 64)) < 1e-6f;
        EXPECT_LT(worst, (whole_columns ? 1e-4f : 0.03f) * peak) << "angle " << angle;
        const glm::dvec3 e0 = coif::envmap_energy(map), e1 = coif::envmap_energy(turned);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(e1[c], e0[c], 1e-5 * e0[c]);
    }
    const coif::EnvMap full = coif::rotate_envmap_y(map, float(2 * M_PI));
    for (size_t i = 0; i < map.radiance.size(); ++i) ASSERT_LT(glm::length(full.radiance[i] - map.radiance[i]), 1e-4f);
    EXPECT_THROW(coif::rotate_envmap_y(map, std::nanf("")), coif::Error);
}

}  // namespace

namespace {

TEST(DefaultEnvironment, ShippedLightsBelongToTheShippedMap) {
    const auto dir = coif::test::source_dir() / "tools" / "assets";
    const coif::SrbfLightSet set = coif::read_srbf_lights(dir / "default_lights.json");
    ASSERT_TRUE(set.source && set.fit);
    EXPECT_EQ(set.source->checksum, coif::checksum(coif::read_file_bytes(dir / "default_env.hdr")));
    const EnvMap map = coif::load_envmap(dir / "default_env.hdr");
    EXPECT_EQ(map.width, set.source->width);
    // The recorded energy error is the one the lights really have (float re-evaluation: 1e-4).
    const glm::dvec3 E_fit = coif::srbf_lights_energy(set.lights), E_map = coif::envmap_energy(map);
    EXPECT_NEAR((coif::luminance(E_fit) - coif::luminance(E_map)) / coif::luminance(E_map), set.fit->energy_error, 1e-4);
    // ≤ 200 KB so that it can live in the repository and the binary.
    EXPECT_LE(std::filesystem::file_size(dir / "default_env.hdr"), 200u * 1024u);
}

}  // namespace
