// SRBF circular-Gaussian Marschner lighting (issue 6) against the brute-force reference.
// Tolerances are stated beside each assertion with the reason for their size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "models/core/error.h"
#include "shaders/lighting.h"
#include "shaders/lighting_check.h"
#include "shaders/marschner_reference.h"

namespace {

using namespace coif::shading;
using coif::SrbfLight;

void print_single(const std::vector<check::SingleRow>& rows) {
    std::printf("variant   m    median   p95      max      | unweighted median  p95\n");
    for (const auto& r : rows)
        std::printf("%-9s %-4d %.4f   %.4f   %.4f   | %.4f            %.4f\n", r.variant.c_str(), r.segments, r.stats.median,
                    r.stats.p95, r.stats.max, r.stats.median_unweighted, r.stats.p95_unweighted);
}

const check::SingleRow& find_row(const std::vector<check::SingleRow>& rows, const std::string& v, int m) {
    for (const auto& r : rows)
        if (r.variant == v && r.segments == m) return r;
    throw std::runtime_error("row missing");
}

TEST(LutImage, SamplesLikeGlLinearClampToEdge) {
    LutImage img(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) img.at(x, y) = glm::vec4(float(x + 10 * y));
    // Texel centres read the texel exactly; half way between two centres is their mean; outside clamps.
    EXPECT_FLOAT_EQ(img.sample({0.125f, 0.25f}).x, 0.0f);
    EXPECT_FLOAT_EQ(img.sample({0.375f, 0.75f}).x, 11.0f);
    EXPECT_FLOAT_EQ(img.sample({0.25f, 0.25f}).x, 0.5f);
    EXPECT_FLOAT_EQ(img.sample({-3.0f, 5.0f}).x, 10.0f);
    EXPECT_FLOAT_EQ(img.sample({0.5f, 0.5f}).x, 6.5f);
}

TEST(LightingTables, BuildAndMatchDirectIntegration) {
    const LightingTables& t = global_lighting_tables();
    std::printf("tables built in %.3f s\n", t.build_seconds);
    const auto rows = check::check_approximations();
    for (const auto& r : rows) std::printf("%-48s max %.3e  rms %.3e  (%s)\n", r.name.c_str(), r.max, r.rms, r.metric.c_str());
    const auto get = [&](const std::string& prefix) {
        for (const auto& r : rows)
            if (r.name.rfind(prefix, 0) == 0) return r;
        throw std::runtime_error("missing row " + prefix);
    };
    // Bilinear look-ups between grid points of smooth functions on 000 §5's grids: interpolation error
    // ~ h²/8 f'' with h = 1/63 of the range, ~1e-3 of the value.
    EXPECT_LT(get("C_k table").max, 3e-3);
    EXPECT_LT(get("H_k^TT table").max, 5e-3);
    EXPECT_LT(get("H_k^TRT table").max, 1e-2);
    // Degree-5 polynomial in cos(incidence): the fit is an order of magnitude closer than Schlick.
    EXPECT_LT(get("Fresnel, degree-5 fit").max, 0.03);
    EXPECT_LT(get("Fresnel, degree-5 fit").max, 0.5 * get("Fresnel, Schlick").max);
    // Interpolation through three exact values of T (quadratic in h²): below 1e-3 absolute.
    EXPECT_LT(get("T interpolated").max, 1e-3);
    // Energies of the fitted N_TT / N_TRT (eq. 17, 19, 23) with our T: table + interpolation error only.
    EXPECT_LT(get("N_TT energy, ours").max, 0.01);
    EXPECT_LT(get("N_TRT energy, ours").max, 0.05);
}

TEST(SingleScattering, MatchesBruteForce) {
    // 100 random configurations in the ranges (the 1000-configuration run is
    // SlowSingleScattering.MatchesBruteForce1000). Issue 6's bound with m = 4: energy-weighted
    // median <= 2 %, p95 <= 5 %.
    const auto configs = check::random_configs(100, 2024);
    const auto rows = check::check_single(configs, {4});
    print_single(rows);
    const auto& r = find_row(rows, "improved", 4);
    EXPECT_LE(r.stats.median, 0.02);
    EXPECT_LE(r.stats.p95, 0.05);
}

TEST(SlowSingleScattering, MatchesBruteForce1000) {
    const auto configs = check::random_configs(1000, 1);
    const auto rows = check::check_single(configs, {2, 4, 6, 200});
    print_single(rows);
    const auto& r = find_row(rows, "improved", 4);
    EXPECT_LE(r.stats.median, 0.02);  // issue 6's bound
    EXPECT_LE(r.stats.p95, 0.05);     // issue 6's bound
}

TEST(MultipleScattering, MatchesBruteForceDualScattering) {
    const auto rows = check::check_multiple(1, 20, 7);
    for (const auto& r : rows)
        std::printf("%-16s median %.4f  p95 %.4f  max %.4f  (n=%d)\n", r.term.c_str(), r.stats.median, r.stats.p95, r.stats.max,
                    r.stats.count);
    // See SlowMultipleScattering for the bound's reasoning; 20 configurations of one parameter set
    // (to keep the default suite fast) get the median bound and a looser p95 (p95 of 20 is ~ the max).
    EXPECT_LE(rows[2].stats.median, 0.05);
    EXPECT_LE(rows[2].stats.p95, 0.25);
}

TEST(SlowMultipleScattering, MatchesBruteForceDualScattering) {
    const auto rows = check::check_multiple(8, 30, 11);
    for (const auto& r : rows)
        std::printf("%-16s median %.4f  p95 %.4f  max %.4f  (n=%d)\n", r.term.c_str(), r.stats.median, r.stats.p95, r.stats.max,
                    r.stats.count);
    // Bound (energy-weighted, like single scattering): the global term inherits the single-scattering
    // fits (measured ~0.4 % median, ~4 % p95); the local term replaces Δ̄_b, σ̄_b by their means over
    // the light's spread (000 eq. 31) and Zinke's ā by the separated eq. 33, measured ~4 % median,
    // ~8 % p95; it is scaled by d_b and carries less energy than the global term. We assert the sum
    // at median <= 3 %, p95 <= 8 %, and the local term alone at median <= 8 %, p95 <= 15 %.
    EXPECT_LE(rows[2].stats.median, 0.03);
    EXPECT_LE(rows[2].stats.p95, 0.08);
    EXPECT_LE(rows[1].stats.median, 0.08);
    EXPECT_LE(rows[1].stats.p95, 0.15);
}

TEST(Validation, RefusesUnphysicalParameters) {
    const auto expect_refused = [](HairParams p, const std::string& field) {
        try {
            validate(p, "test");
            FAIL() << "accepted bad " << field;
        } catch (const coif::Error& e) {
            EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
        }
    };
    HairParams p = default_hair_params();
    EXPECT_NO_THROW(validate(p));
    HairParams q = p;
    q.eta = 1.0f;
    expect_refused(q, "eta");
    q = p;
    q.eta = 0.8f;
    expect_refused(q, "eta");
    q = p;
    q.sigma_a.g = -0.1f;
    expect_refused(q, "sigma_a.g");
    q = p;
    q.beta_R = 0.0f;
    expect_refused(q, "beta_R");
    q = p;
    q.alpha_TT = std::numeric_limits<float>::quiet_NaN();
    expect_refused(q, "alpha_TT");
    q = p;
    q.w_c = std::numeric_limits<float>::infinity();
    expect_refused(q, "w_c");
    q = p;
    q.ecc_a = 0.6f;
    expect_refused(q, "eccentricity");
    EXPECT_THROW(validate(default_config(1)), coif::Error);
    EXPECT_THROW(validate_light(0.0f, {0, 1, 0}), coif::Error);
    EXPECT_THROW(validate_light(0.5f, {0, 0, 0}), coif::Error);
    EXPECT_THROW(LightingEvaluator{q}, coif::Error);
}

TEST(Robustness, CornerSweepNeverProducesNanOrInf) {
    // Every combination of extreme accepted values; angles include the poles θ = ±π/2 (light or view
    // along the fibre), φ at 0 and ±π. 4 m values × 3 configs.
    int evaluated = 0;
    for (float eta : {1.0001f, 1.55f, 9.99f})
        for (float sa : {0.0f, 3.0f, kMaxSigmaA})
            for (float beta : {2.0f * kMinBeta, 0.2f, kMaxBeta / 2.0f})  // β_TT = β/2, β_TRT = 2β stay accepted
                for (float a : {kMinEcc, 1.0f, kMaxEcc})
                    for (float w_c : {kMinLambda, 0.3f, 3.1f}) {
                        HairParams p = linked_hair_params(eta, glm::vec3(sa, 0.0f, 1.0f), -0.5f * beta, beta, a, w_c);
                        p.alpha_R = -kMaxAlpha / 2.0f;
                        p.alpha_TRT = kMaxAlpha;
                        validate(p);
                        if (sa == 3.0f && beta == 0.2f && a == 1.0f && w_c == 0.3f) continue;  // the middle: nothing new
                        const LightingEvaluator eval(p, default_config(4));
                        for (float th_o : {-1.5707964f, -0.3f, 1.5707964f})
                            for (float th_j : {-1.5707964f, 0.0f, 1.5707964f})
                                for (float ph : {0.0f, 3.1415927f, -3.1415927f})
                                    for (float lambda : {kMinLambda, 0.05f, kMaxLambda}) {
                                        const glm::vec3 s = eval.single(th_o, 0.0f, th_j, ph, lambda);
                                        const glm::vec3 m = eval.multiple(th_o, ph, th_j, 0.0f, lambda, 0.5f);
                                        for (int c = 0; c < 3; ++c) {
                                            ASSERT_TRUE(std::isfinite(s[c]) && s[c] >= 0.0f)
                                                << "single " << s[c] << " eta " << eta << " sa " << sa << " beta " << beta
                                                << " a " << a << " w_c " << w_c << " th_o " << th_o << " th_j " << th_j
                                                << " ph " << ph << " lambda " << lambda;
                                            ASSERT_TRUE(std::isfinite(m[c]) && m[c] >= 0.0f)
                                                << "multiple " << m[c] << " eta " << eta << " sa " << sa << " beta " << beta
                                                << " a " << a << " w_c " << w_c << " th_o " << th_o << " th_j " << th_j
                                                << " ph " << ph << " lambda " << lambda;
                                        }
                                        ++evaluated;
                                    }
                    }
    EXPECT_GT(evaluated, 10000);
}

TEST(Physics, AzimuthalMirrorSymmetryOfACircularFibre) {
    // A circular fibre is symmetric under φ → -φ: 𝓜(φo, φj) = 𝓜(-φo, -φj) up to float rounding.
    HairParams p = default_hair_params();
    const LightingEvaluator eval(p);
    for (float ph_o : {0.3f, 1.7f, -2.9f})
        for (float ph_j : {-0.4f, 2.2f}) {
            const glm::vec3 a = eval.single(0.2f, ph_o, -0.3f, ph_j, 0.3f);
            const glm::vec3 b = eval.single(0.2f, -ph_o, -0.3f, -ph_j, 0.3f);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-5f * (1.0f + a[c]));
        }
}

TEST(Reference, HSubstitutionMatchesDirectAzimuthalIntegralForR) {
    // The reference integrates N_t in h; for R, N_R(φ) = |cos(φ/2)| F / 4 is explicit, so the inner
    // integral can also be done directly over φ. Agreement to 5e-4 relative (20× below the smallest
    // error the reference is used to measure) checks the h route and its step count.
    const HairParams p = default_hair_params();
    for (double lambda_p : {0.05, 0.3, 1.5})
        for (double dphi : {0.0, 1.0, 2.8}) {
            const double theta_d = 0.3;
            const glm::dvec3 via_h = reference::inner_exact(0, p, p.eta, theta_d, lambda_p, dphi);
            double direct = 0.0;
            constexpr int n = 20000;
            for (int i = 0; i < n; ++i) {
                const double x = -M_PI + (i + 0.5) * 2.0 * M_PI / n;
                const double phi = dphi - x;
                const double s = std::sin(0.5 * x);
                const double f = coif::glsl::fresnel_h(p.eta, float(theta_d), float(-std::sin(0.5 * phi)));
                direct += std::exp(-4.0 * s * s / (lambda_p * lambda_p)) * 0.25 * std::abs(std::cos(0.5 * phi)) * f * 2.0 * M_PI / n;
            }
            EXPECT_NEAR(via_h.x, direct, 5e-4 * direct + 1e-12) << lambda_p << " " << dphi;
        }
}

TEST(Evaluator, MultipleScatteringScalesWithTheLightsPower) {
    // Two narrow lights from one direction with the same power L_j ∫G_j dω: multiple scattering spreads
    // the light far wider than either (β̄_f, the local lobe's σ̄_b), so what it gives must be the same, lit
    // or behind fibres. Before the power was applied (000 eq. 3 read literally: ψ_f times L_j) the
    // narrower light gave 4× more. 8 %: the lobes are not infinitely wide, so the wider light still samples
    // them more broadly (measured worst 4.1 %: blue behind 3 fibres, where the spread is narrowest).
    const LightingEvaluator eval(default_hair_params());
    const FibreFrame frame = FibreFrame::from_tangent({0, 1, 0}, {0, 0, 1});
    const glm::vec3 view(0.3f, 0.1f, 1.0f), towards(0.8f, 0.3f, 0.6f);
    const SrbfLight wide{glm::vec3(1.0f), towards, 0.04f};
    const SrbfLight narrow{glm::vec3(coif::glsl::srbf_integral(0.04f) / coif::glsl::srbf_integral(0.02f)), towards, 0.02f};
    for (const LightShadow shadow : {LightShadow{1.0f, 0.0f}, LightShadow{std::exp(-3.0f), 3.0f}}) {
        const glm::vec3 a = eval.shade(frame, view, std::span(&wide, 1), std::span(&shadow, 1)).multiple;
        const glm::vec3 b = eval.shade(frame, view, std::span(&narrow, 1), std::span(&shadow, 1)).multiple;
        for (int c = 0; c < 3; ++c) {
            std::printf("fibres %.0f channel %d: narrow / wide %.4f\n", shadow.fibres, c, b[c] / a[c]);
            EXPECT_GT(a[c], 0.0f);
            EXPECT_NEAR(b[c] / a[c], 1.0f, 0.08f) << "channel " << c << ", fibres " << shadow.fibres;
        }
    }
}

TEST(Evaluator, SumsLightsAndAppliesShadowTerms) {
    const LightingEvaluator eval(default_hair_params());
    const FibreFrame frame = FibreFrame::from_tangent({0, 1, 0}, {0, 0, 1});
    const SrbfLight a{{1.0f, 0.5f, 0.25f}, {1, 0.2f, 0.1f}, 0.3f}, b{{2.0f, 2.0f, 2.0f}, {-0.5f, -0.2f, 1}, 0.8f};
    const glm::vec3 view(0.3f, 0.1f, 1.0f);
    const SrbfLight both[] = {a, b};
    const PointLighting sum = eval.shade(frame, view, both);
    const PointLighting pa = eval.shade(frame, view, std::span(&a, 1));
    const PointLighting pb = eval.shade(frame, view, std::span(&b, 1));
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(sum.single[c], pa.single[c] + pb.single[c], 1e-6f * (1.0f + sum.single[c]));
        EXPECT_NEAR(sum.multiple[c], pa.multiple[c] + pb.multiple[c], 1e-6f * (1.0f + sum.multiple[c]));
    }
    // Unshadowed: single scattering plus d_b times the local multiple scattering (a lone fibre; no
    // global term, which would count the unscattered light twice). 𝓜^L and 𝓜^G are per unit power of
    // the light: the light's power per unit L_j is ∫G dω = srbf_integral(λ_j).
    float theta_o, phi_o, theta_j, phi_j;
    coif::glsl::hair_angles(glm::normalize(view), frame.u, frame.v, frame.w, theta_o, phi_o);
    coif::glsl::hair_angles(glm::normalize(a.omega), frame.u, frame.v, frame.w, theta_j, phi_j);
    const glm::vec3 local = eval.ms_local(theta_o, phi_o, theta_j, phi_j, a.lambda, 0.0f);
    const float power = coif::glsl::srbf_integral(a.lambda);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(pa.multiple[c], a.L[c] * power * eval.params().d_b * local[c], 1e-6f * (1.0f + pa.multiple[c]));
    // Half the lobe blocked, nothing scattered on the way: both parts halve.
    const LightShadow half{0.5f, 0.0f};
    const PointLighting shadowed = eval.shade(frame, view, std::span(&a, 1), std::span(&half, 1));
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(shadowed.single[c], 0.5f * pa.single[c], 1e-6f);
        EXPECT_NEAR(shadowed.multiple[c], 0.5f * pa.multiple[c], 1e-6f);
    }
    // Behind an optical depth of n = 3 fibres: T̃ = e^-3, T_f = exp(-3 (1 - ā_f)) (the Poisson mean of ā_f^K),
    // σ̄_f² = 3 ā̄_f β̄_f² from the forward table.
    const float n = 3.0f;
    const LightShadow behind{std::exp(-n), n};
    const PointLighting deep = eval.shade(frame, view, std::span(&a, 1), std::span(&behind, 1), true, 0.7f);
    const glm::vec4 fw = [&] {
        const LutBinding bind = eval.bind();
        return coif::glsl::fetch_ms_forward(theta_j, eval.params().sigma_a);
    }();
    EXPECT_GT(fw.x, 0.05f) << "a fibre passes some light forward";
    EXPECT_LT(fw.x, 1.0f) << "and absorbs or reflects some";
    const float scatterings = n * (fw.x + fw.y + fw.z) / 3.0f;
    const glm::vec3 spread = eval.multiple(theta_o, phi_o, theta_j, phi_j, a.lambda, scatterings * fw.w);
    for (int c = 0; c < 3; ++c) {
        const float T_f = std::exp(-n * (1.0f - fw[c]));
        // Forward-scattered light reaches the point in every channel, even for this brown hair whose
        // ā_f (0.36 / 0.27 / 0.15) is below e^-1: ā_f^n, with the mean depth put for the count, fell
        // below T̃ and left none.
        EXPECT_GT(T_f, 1.5f * behind.direct) << c;
        const float want = a.L[c] * power * (behind.direct * eval.params().d_b * local[c] +
                                            0.7f * std::max(T_f - behind.direct, 0.0f) * spread[c]);
        EXPECT_NEAR(deep.multiple[c], want, 1e-5f * (1.0f + want)) << c;
        EXPECT_NEAR(deep.single[c], behind.direct * pa.single[c], 1e-6f);
    }
    EXPECT_THROW(eval.shade(frame, view, std::span(&a, 1), std::span(&half, 1), true, 1.5f), coif::Error);
    const LightShadow bad{0.5f, std::nanf("")};
    EXPECT_THROW(eval.shade(frame, view, std::span(&a, 1), std::span(&bad, 1)), coif::Error);
    EXPECT_GT(sum.single.x, 0.0f);
    EXPECT_GT(sum.multiple.x, 0.0f);
}

}  // namespace

#include <filesystem>

#include "tests/common/run.h"

namespace {

TEST(LightingCli, PlotWritesFigureAndRefusesBadParameters) {
    const auto dir = coif::test::scratch_dir("lighting-plot");
    const auto ok = coif::test::run_coif("lighting plot -o '" + dir.string() + "'");
    ASSERT_EQ(ok.exit_code, 0) << ok.err;
    for (const char* name : {"n_tt", "n_trt", "t_taylor", "quadrature_integrand"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / (std::string(name) + ".png"))) << name;
        EXPECT_TRUE(std::filesystem::exists(dir / (std::string(name) + ".csv"))) << name;
    }
    // Parameter values outside the physical range: exit 1 with the field named, nothing new written.
    const auto bad_dir = coif::test::scratch_dir("lighting-plot-bad");
    for (const std::string args : {"--eta 1", "--sigma-a 0.1 -0.2 0.3", "--beta-r 0", "--eta nan"}) {
        const auto r = coif::test::run_coif("lighting plot -o '" + bad_dir.string() + "' " + args);
        EXPECT_EQ(r.exit_code, 1) << args;
        EXPECT_NE(r.err.find("coif: error:"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(bad_dir / "n_tt.png")) << args;
    }
}

}  // namespace

namespace coif::shading {
namespace {

// The tables every process reads are the ones computed at build time and embedded (shaders/CMakeLists.txt): they
// must be today's build_lighting_tables() bit for bit, or a change to the tables' code would go unseen.
TEST(LightingTables, EmbeddedTablesAreAFreshComputationBitForBit) {
    const LightingTables fresh = build_lighting_tables();
    const LightingTables& used = global_lighting_tables();
    EXPECT_EQ(lighting_tables_bytes(used), lighting_tables_bytes(fresh));
    EXPECT_EQ(used.build_seconds, 0.0) << "computed at run time: the embedded tables were not found";
    std::printf("lighting tables: %.0f ms to compute, read from the library instead\n", 1e3 * fresh.build_seconds);
    // The byte form round-trips and refuses a truncated copy.
    const std::vector<std::byte> bytes = lighting_tables_bytes(fresh);
    EXPECT_EQ(lighting_tables_bytes(lighting_tables_from_bytes(bytes)), bytes);
    EXPECT_THROW(lighting_tables_from_bytes(std::span<const std::byte>(bytes).first(bytes.size() - 1)), Error);
}

}  // namespace
}  // namespace coif::shading
