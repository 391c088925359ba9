// The brute-force reference renderer (offline/reference.h, offline/reference_fiber.h) and `coif reference`.
#include <cmath>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <cstdio>
#include <random>

#include "models/core/error.h"
#include "models/core/image.h"
#include "models/core/image_metrics.h"
#include "offline/reference.h"
#include "offline/reference_fiber.h"
#include "shaders/marschner_reference.h"
#include "tests/common/run.h"
#include "tests/common/test_data.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr float kPi = 3.14159265358979323846f;

// One straight fibre along +x through the origin: its frame is u = +x, v = u × y = +z, w = u × v = −y.
Strands single_fibre() {
    Strands s;
    s.add_strand({glm::vec3(-1, 0, 0), glm::vec3(1, 0, 0)});
    return s;
}

FiberFrame fibre_frame_x() { return FiberFrame::from_tangent(glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)); }

glm::vec3 direction(float theta, float phi, const FiberFrame& f) {
    return std::sin(theta) * f.u + std::cos(theta) * (std::cos(phi) * f.v + std::sin(phi) * f.w);
}

// A dense bundle of 40 nearly parallel fibres in a 0.3 × 0.3 cross-section: light scatters many times
// between them.
Strands bundle() {
    Strands s;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-0.15f, 0.15f);
    for (int i = 0; i < 40; ++i) {
        const float y = u(rng), z = u(rng);
        s.add_strand({glm::vec3(-1, y, z), glm::vec3(0, y + 0.2f * u(rng), z + 0.2f * u(rng)), glm::vec3(1, y, z)});
    }
    return s;
}

Camera camera_on(const glm::vec3& eye, int size, float fov_deg) {
    Camera c;
    c.eye = eye;
    c.target = glm::vec3(0);
    c.width = c.height = size;
    c.fov_y = fov_deg * kPi / 180.0f;
    return c;
}

shading::HairParams clear_hair() {
    shading::HairParams p = shading::default_hair_params();
    p.sigma_a = glm::vec3(0.0f);
    return p;
}

// The coverage-weighted mean radiance of the 40-fibre bundle seen at 32×32 px (straight alpha) under a
// constant unit environment: the furnace tests' figure.
glm::dvec3 bundle_furnace_mean(const FiberBsdf& fibre, int max_depth) {
    const ReferenceEnvironment env = ReferenceEnvironment::constant(glm::vec3(1.0f));
    ReferenceSettings s;
    s.samples_per_pixel = 16;
    s.max_depth = max_depth;
    s.fiber_radius = 0.02f;
    s.alpha = true;
    s.progress = false;
    const Image img = ReferenceRenderer(bundle(), env, fibre, s).render(camera_on(glm::vec3(0, 0.3f, 3), 32, 25));
    glm::dvec3 sum(0.0);
    double weight = 0;
    for (int i = 0; i < 32 * 32; ++i) {
        const float a = img.pixels[4 * i + 3];
        for (int c = 0; c < 3; ++c) sum[c] += a * img.pixels[4 * i + c];
        weight += a;
    }
    EXPECT_GT(weight, 50.0);
    return sum / std::max(weight, 1e-9);
}

TEST(Reference, IsotropicWhiteFurnaceConservesEnergyThroughManyBounces) {
    // Furnace: fibres that scatter everything (albedo 1) in a constant unit environment are at radiance 1
    // everywhere, however many times light bounces between them. This checks the path tracer itself (NEE,
    // direction sampling, MIS weights, shadow rays, Russian roulette, self-intersection skipping).
    // 32×32 px × 16 spp over the bundle: ~6 000 paths on hair; measured per-path standard deviation ≈ 0.35,
    // so the mean has σ ≈ 0.005 and 0.02 is 4σ.
    const glm::dvec3 mean = bundle_furnace_mean(IsotropicFiber(glm::vec3(1.0f)), kMaxReferenceDepth);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 1.0, 0.02) << "channel " << c;
}

TEST(Reference, MarschnerTableMatchesTheExactModel) {
    // The renderer samples the lighting module's exact N_t on a grid (32 |θd| × 129 |φ|) and interpolates.
    // Off-grid, the interpolated value must stay within 2 % of the lobe's peak value (plus 1e-4 absolute):
    // the grid is fine enough for the narrowest lobe (TRT roughened by w_c = 0.15 rad spans ~12 φ steps); measured: < 0.8 %.
    const shading::HairParams p = shading::default_hair_params();
    const MarschnerFiber fibre(p);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> td(0.0f, 1.4f), ph(-kPi, kPi);
    for (int lobe = 0; lobe < 3; ++lobe) {
        double peak = 0, worst = 0;
        for (int i = 0; i < 40; ++i) {
            const float theta_d = td(rng), phi = ph(rng);
            const glm::dvec3 exact = shading::reference::N_exact(lobe, p, p.eta, theta_d, phi);
            const glm::vec3 table = fibre.N(lobe, p.eta, theta_d, phi);
            peak = std::max(peak, exact.x);
            worst = std::max(worst, std::abs(exact.x - table.x));
        }
        std::printf("lobe %d: worst |table - exact| = %.2e, %.2f %% of the peak %.4f\n", lobe, worst, 100.0 * worst / peak, peak);
        EXPECT_LT(worst, 0.02 * peak + 1e-4) << "lobe " << lobe << " peak " << peak;
    }
}

TEST(Reference, IsolatedFibreMatchesTheLightingModuleBruteForce) {
    // One fibre, one SRBF light, single scattering: the radiance the reference renderer traces must equal
    // the lighting module's brute-force 𝓜 = ∫ G_j S cos θi dωi (shading::reference::single, 000 eq. 11 by
    // dense quadrature). Tolerance 4 %: 20 000 paths give ≈1 % standard error, and the tabulated N_t adds
    // up to ~1 % (test above).
    const shading::HairParams p = shading::default_hair_params();
    const MarschnerFiber fibre(p);
    const FiberFrame f = fibre_frame_x();
    struct Case {
        float theta_o, phi_o, theta_j, phi_j, lambda_j;
    };
    for (const Case c : {Case{0.2f, 0.3f, -0.1f, 0.5f, 0.3f}, Case{-0.3f, 1.2f, 0.25f, -2.0f, 0.5f}, Case{0.1f, 0.0f, 0.0f, 3.0f, 0.4f}}) {
        SrbfLight light;
        light.L = glm::vec3(1.0f);
        light.omega = direction(c.theta_j, c.phi_j, f);
        light.lambda = c.lambda_j;
        const ReferenceEnvironment env = ReferenceEnvironment::from_srbf({light}, "one light");
        ReferenceSettings s;
        s.max_depth = 1;
        s.fiber_radius = 0.05f;
        s.progress = false;
        const ReferenceRenderer r(single_fibre(), env, fibre, s);
        const glm::vec3 wo = direction(c.theta_o, c.phi_o, f);
        const glm::vec4 traced = r.trace(5.0f * wo, -wo, 20000, 3);
        ASSERT_GT(traced.w, 0.99f);
        const glm::dvec3 brute = shading::reference::single(p, c.theta_o, c.phi_o, c.theta_j, c.phi_j, c.lambda_j);
        std::printf("θo %+.2f φo %+.2f θj %+.2f φj %+.2f λ %.2f: traced %.5f %.5f %.5f, brute force %.5f %.5f %.5f\n", c.theta_o,
                    c.phi_o, c.theta_j, c.phi_j, c.lambda_j, traced.x, traced.y, traced.z, brute.x, brute.y, brute.z);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(traced[k], brute[k], 0.04 * brute[k] + 1e-4)
                << "channel " << k << " θo " << c.theta_o << " φo " << c.phi_o << " θj " << c.theta_j << " φj " << c.phi_j;
    }
}

TEST(Reference, WithoutShadowsAnOccluderDoesNotDarkenTheFibre) {
    // The fibre of single_fibre() and a parallel occluder 0.3 away towards a narrow light: with shadows the
    // occluder blocks most of the light; with shadows off the fibre is lit exactly as if alone (same seed,
    // same paths: no tolerance beyond float summation order, which is the same too).
    const shading::HairParams p = shading::default_hair_params();
    const MarschnerFiber fibre(p);
    const FiberFrame f = fibre_frame_x();
    SrbfLight light;
    light.L = glm::vec3(1.0f);
    light.omega = direction(-0.1f, 2.5f, f);
    light.lambda = 0.1f;
    const ReferenceEnvironment env = ReferenceEnvironment::from_srbf({light}, "one light");
    Strands pair = single_fibre();
    const glm::vec3 c = 0.3f * light.omega;
    pair.add_strand({c - glm::vec3(1, 0, 0), c + glm::vec3(1, 0, 0)});
    const glm::vec3 wo = direction(0.2f, 0.3f, f);
    const auto trace = [&](const Strands& strands, bool shadows) {
        ReferenceSettings s;
        s.max_depth = 1;
        s.fiber_radius = 0.05f;
        s.progress = false;
        s.shadows = shadows;
        const ReferenceRenderer r(strands, env, fibre, s);
        return r.trace(5.0f * wo, -wo, 4000, 3);
    };
    const glm::vec4 alone = trace(single_fibre(), true), shadowed = trace(pair, true), unshadowed = trace(pair, false);
    std::printf("alone %.5f, occluded with shadows %.5f, without shadows %.5f (green)\n", alone.y, shadowed.y, unshadowed.y);
    ASSERT_GT(alone.w, 0.99f);  // every path hits the fibre, not the occluder
    ASSERT_GT(unshadowed.w, 0.99f);
    EXPECT_LT(shadowed.y, 0.5f * alone.y);
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(unshadowed[k], alone[k]) << "channel " << k;
}

shading::HairParams paper_longitudinal(shading::HairParams p) {
    p.longitudinal = 1.0f;
    return p;
}

TEST(Reference, MarschnerWhiteFurnace) {
    // A single fibre with σa = 0 under a constant unit environment; its directional albedo ∫ S cos θi dωi by
    // quadrature (400 × 800 cells), and the path tracer's radiance at three θo (20 000 paths: ≈1.5 % standard
    // error on the spiky R/TRT lobes; 5 %).
    //  - Energy-conserving M_t (the default: ∫ M_t dθi = 1): R + TT + TRT carry the energy of the paths with
    //    at most one internal reflection, so the albedo is below 1 by the TRRT… residual (4–10 % at η = 1.55,
    //    more at grazing θd where Fresnel keeps more light inside), except for the geometric factor
    //    cos²θi / cos²θd of 000 eq. 6, which is 1 only at the specular θi = −θo: the α shifts and widths move
    //    the lobes off it. Measured 0.96, 1.009, 0.817 at θo = 0, 0.4, −0.8 and 1.097, 0.674 at ±1.3 (grazing:
    //    the factor departs most, and the cut lobes' normalisation is largest). Bands stated: [0.8, 1.02] for
    //    |θo| ≤ 0.8; [0.6, 1.12] at |θo| = 1.3.
    //  - 000's literal M_t (longitudinal = paper): normalised in θh, so 2× in θi: the albedo lies in
    //    [1.5, 2.05], and it is the energy-conserving one times 2 wherever no lobe is cut by θi = ±π/2.
    const FiberFrame f = fibre_frame_x();
    const MarschnerFiber fibre(clear_hair());
    const MarschnerFiber paper(paper_longitudinal(clear_hair()));
    const ReferenceEnvironment env = ReferenceEnvironment::constant(glm::vec3(1.0f));
    ReferenceSettings s;
    s.max_depth = 1;
    s.fiber_radius = 0.05f;
    s.progress = false;
    const ReferenceRenderer r(single_fibre(), env, fibre, s);
    for (const float theta_o : {0.0f, 0.4f, -0.8f, 1.3f, -1.3f}) {
        const glm::vec3 wo = direction(theta_o, 0.7f, f);
        const glm::vec3 albedo = fiber_albedo(fibre, f, wo, 400);
        const glm::vec3 albedo_paper = fiber_albedo(paper, f, wo, 400);
        std::printf("θo %+.1f: albedo %.4f %.4f %.4f, paper %.4f\n", theta_o, albedo.x, albedo.y, albedo.z, albedo_paper.x);
        const bool grazing = std::abs(theta_o) > 1.0f;
        for (int k = 0; k < 3; ++k) {
            EXPECT_GT(albedo[k], grazing ? 0.6f : 0.8f) << "θo " << theta_o;
            EXPECT_LT(albedo[k], grazing ? 1.12f : 1.02f) << "θo " << theta_o;
        }
        if (std::abs(theta_o) < 1.0f) {
            EXPECT_GT(albedo_paper.x, 1.5f) << "θo " << theta_o;
            EXPECT_LT(albedo_paper.x, 2.05f) << "θo " << theta_o;
            const glm::vec4 traced = r.trace(5.0f * wo, -wo, 20000, 9);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(traced[k], albedo[k], 0.05 * albedo[k]) << "θo " << theta_o;
        }
    }
}

TEST(Reference, MarschnerBundleFurnaceStaysAtOrBelowOne) {
    // The 40-fibre bundle of clear (σa = 0) Marschner fibres under a constant unit environment, light
    // scattering between fibres up to 64 times: energy conservation means no pixel of the hair can
    // exceed the environment, so the coverage-weighted mean stays ≤ 1 (+ 0.02, 4σ of 6 000 paths, as the
    // isotropic furnace). Measured 0.58: each bounce loses the TRRT… residual and light leaves the bundle.
    // 000's literal M_t gains energy at every bounce and must exceed it (> 1.2; measured 87 at 64 bounces:
    // the 2× compounds, which is why multiple scattering made the reference so bright).
    const glm::dvec3 conserving = bundle_furnace_mean(MarschnerFiber(clear_hair()), 64);
    const glm::dvec3 paper = bundle_furnace_mean(MarschnerFiber(paper_longitudinal(clear_hair())), 64);
    std::printf("bundle furnace: energy-conserving %.4f %.4f %.4f, paper %.4f\n", conserving.x, conserving.y, conserving.z, paper.x);
    for (int c = 0; c < 3; ++c) EXPECT_LE(conserving[c], 1.02) << "channel " << c;
    EXPECT_GT(paper.x, 1.2);
}

TEST(Reference, MarschnerScatteringIsReciprocal) {
    // S(ωi, ωo) = S(ωo, ωi). 000's model is exactly reciprocal (M in θh, N in |θd| and φ); only the
    // tabulated N_t's interpolation separates the two (0.5 %). The energy-conserving M_t divides by its
    // integral over θi for the outgoing θo, which differs from the incoming one's where a lobe is cut by
    // θ = ±π/2 (TRT first: centred at 2α_TRT − θo = 0.39 − θo rad, 0.52 wide): measured worst 7.6 % for
    // |θ| ≤ 0.8 (bound 10 %) and 49 % for |θ| ≤ 1.4 (reported, not bounded): the price of d'Eon's
    // normalisation, paid at grazing angles.
    const FiberFrame f = fibre_frame_x();
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (const bool conserving : {false, true}) {
        shading::HairParams p = shading::default_hair_params();
        if (!conserving) p = paper_longitudinal(p);
        const MarschnerFiber fibre(p);
        double worst = 0, worst_wide = 0;
        for (int n = 0; n < 2000; ++n) {
            const float limit = n < 1000 ? 0.8f : 1.4f;
            const glm::vec3 wi = direction(limit * (2 * u(rng) - 1), 2 * kPi * u(rng), f);
            const glm::vec3 wo = direction(limit * (2 * u(rng) - 1), 2 * kPi * u(rng), f);
            const glm::vec3 a = fibre.S(f, wi, wo), b = fibre.S(f, wo, wi);
            const float peak = std::max(a.x, b.x);
            if (peak < 0.05f) continue;  // relative errors of near-zero values say nothing
            const double d = std::abs(a.x - b.x) / peak;
            (n < 1000 ? worst : worst_wide) = std::max(n < 1000 ? worst : worst_wide, d);
        }
        std::printf("%s: worst relative |S(i,o) - S(o,i)| %.4f for |θ| <= 0.8, %.4f for |θ| <= 1.4\n",
                    conserving ? "energy-conserving" : "paper", worst, worst_wide);
        EXPECT_LT(worst, conserving ? 0.10 : 0.005);
    }
}

TEST(Reference, DeterministicForASeedOnAnyThreadCount) {
    const MarschnerFiber fibre(shading::default_hair_params());
    const ReferenceEnvironment env = ReferenceEnvironment::constant(glm::vec3(1.0f));
    ReferenceSettings s;
    s.samples_per_pixel = 2;
    s.progress = false;
    s.fiber_radius = 0.02f;
    s.threads = 1;
    const Camera cam = camera_on(glm::vec3(0, 0.3f, 3), 24, 30);
    const Image one = ReferenceRenderer(bundle(), env, fibre, s).render(cam);
    s.threads = 3;
    const Image three = ReferenceRenderer(bundle(), env, fibre, s).render(cam);
    EXPECT_EQ(one.pixels, three.pixels);
    s.seed = 2;
    const Image other = ReferenceRenderer(bundle(), env, fibre, s).render(cam);
    EXPECT_NE(one.pixels, other.pixels);
}

TEST(Reference, EnvironmentSamplingMatchesItsDensity) {
    // Importance sampling from a map: E[L(ω)/p(ω)] = ∫ L dω (the map's energy) — checks that the sampled
    // pixel, the direction inside it and the pdf agree, with the mapping of shaders/envmap.glsl. 200 000
    // samples of an 16×8 map with a bright pixel: relative standard error < 0.3 %, tolerance 1 %.
    EnvMap map(16, 8);
    for (int r = 0; r < 8; ++r)
        for (int c = 0; c < 16; ++c) map.at(c, r) = glm::vec3(0.1f + 0.05f * c, 0.2f, 0.05f * r);
    map.at(5, 2) = glm::vec3(40.0f, 30.0f, 20.0f);
    const glm::dvec3 energy = envmap_energy(map);
    const ReferenceEnvironment env = ReferenceEnvironment::from_map(map, "test map");
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    glm::dvec3 sum(0.0);
    constexpr int n = 200000;
    for (int i = 0; i < n; ++i) {
        glm::vec3 d;
        float p;
        const glm::vec3 L = env.sample(u(rng), u(rng), u(rng), u(rng), d, p);
        ASSERT_GT(p, 0.0f);
        ASSERT_NEAR(p, env.pdf(d), 1e-3f * p);
        ASSERT_EQ(L, env.radiance(d));
        sum += glm::dvec3(L) / double(p);
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / n, energy[c], 0.01 * energy[c]);
}

TEST(ReferenceCli, RendersAndRejectsBadInputWithoutOutput) {
    const fs::path dir = test::scratch_dir("reference-cli");
    const std::string out = (dir / "ref.exr").string();
    const test::RunResult ok = test::run_coif("reference --width 24 --height 16 --spp 1 --max-depth 2 -o '" + out + "'");
    ASSERT_EQ(ok.exit_code, 0) << ok.err;
    EXPECT_THAT(ok.err, HasSubstr("1 spp"));
    EXPECT_THAT(ok.err, HasSubstr("time:"));
    EXPECT_EQ(read_image(out).width, 24);
    fs::remove(out);
    for (const std::string& bad : {"--strands '" + (dir / "missing.hair").string() + "'", std::string("--eta nan"),
                                  std::string("--sigma-a 0.1 nan 0.2"), std::string("--env-constant 1 1 -1"),
                                  "--env '" + (dir / "missing.exr").string() + "'", std::string("--radius -1")}) {
        const test::RunResult r = test::run_coif("reference --width 8 --height 8 --spp 1 " + bad + " -o '" + out + "'");
        EXPECT_EQ(r.exit_code, 1) << bad << ": " << r.err;
        EXPECT_THAT(r.err, HasSubstr("coif: error:")) << bad;
        EXPECT_FALSE(fs::exists(out)) << bad;
    }
    fs::remove_all(dir);
}

TEST(Reference, SlowConvergenceBetweenSeeds) {
    // The noise floor of comparisons: two reference renders of the bundle that differ only in the seed.
    // The tone-mapped mean FLIP between them must fall as samples grow (64 → 512 spp), and at 512 spp it must
    // be below the project's goal of 0.10 for a full render, or the reference could not resolve that goal.
    // Measured: 0.154 at 64 spp, 0.078 at 512 spp (96×96, 40-fibre bundle).
    const MarschnerFiber fibre(shading::default_hair_params());
    const ReferenceEnvironment env = ReferenceEnvironment::constant(glm::vec3(1.0f));
    const Camera cam = camera_on(glm::vec3(0, 0.3f, 3), 96, 30);
    double previous = 1.0;
    for (const int spp : {64, 512}) {
        ReferenceSettings s;
        s.samples_per_pixel = spp;
        s.progress = false;
        s.fiber_radius = 0.01f;
        const Image a = ReferenceRenderer(bundle(), env, fibre, s).render(cam);
        s.seed = 2;
        const Image b = ReferenceRenderer(bundle(), env, fibre, s).render(cam);
        const CompareResult r = compare_images(a, b, {});
        std::printf("convergence at %d spp: PSNR %s dB, SSIM %.4f, FLIP %.4f (tone-mapped, hair)\n", spp,
                    format_metric(r.tone_mapped.psnr_db, 2).c_str(), r.tone_mapped.ssim, r.tone_mapped.flip);
        EXPECT_LT(r.tone_mapped.flip, previous);
        previous = r.tone_mapped.flip;
    }
    EXPECT_LT(previous, 0.1);
}

}  // namespace
}  // namespace coif
