#include "shaders/lighting_check.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>
#include <random>

#include "models/core/parallel.h"
#include "models/core/random.h"
#include "models/core/units.h"
#include "shaders/marschner_reference.h"

namespace coif::shading::check {

namespace {

// Energy of an SRBF light of unit coefficient: ∫G dω = πλ²(1 - e^{-4/λ²}).
double srbf_energy(double lambda) { return kPi * lambda * lambda * (1.0 - std::exp(-4.0 / (lambda * lambda))); }

// Runs fn(i) for i in [0, n) on every hardware thread, calling progress (serialised) after each.
template <class Fn>
void parallel_for_with_progress(int n, Fn fn, const std::function<void()>& progress) {
    std::mutex progress_mutex;
    parallel_for(static_cast<std::size_t>(std::max(n, 0)), 0, [&](std::size_t i) {
        fn(static_cast<int>(i));
        if (progress) {
            const std::lock_guard lock(progress_mutex);
            progress();
        }
    });
}

double weighted_quantile(std::vector<std::pair<double, double>> ew, double q) {
    std::sort(ew.begin(), ew.end());
    double total = 0.0;
    for (const auto& [e, w] : ew) total += w;
    if (!(total > 0.0)) return 0.0;
    double cum = 0.0;
    for (const auto& [e, w] : ew) {
        cum += w;
        if (cum >= q * total) return e;
    }
    return ew.back().first;
}

double rel_error(glm::dvec3 approx, glm::dvec3 ref) {
    const double r = ref.x + ref.y + ref.z;
    const double a = approx.x + approx.y + approx.z;
    if (!(r > 0.0)) return a == 0.0 ? 0.0 : 1.0;
    return std::abs(a - r) / r;
}

}  // namespace

std::vector<Config> random_configs(int count, std::uint64_t seed) {
    Rng rng = seeded_rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const auto dir = [&](float& theta, float& phi) {
        theta = float(std::asin(2.0 * U(rng) - 1.0));  // uniform on the sphere: sin θ uniform
        phi = float(2.0 * kPi * U(rng) - kPi);
    };
    std::vector<Config> out(size_t(std::max(count, 0)));
    for (Config& c : out) {
        dir(c.theta_j, c.phi_j);
        c.lambda_j = float(0.05 * std::pow(2.0 / 0.05, U(rng)));
        dir(c.theta_o, c.phi_o);
        const float eta = float(1.4 + 0.4 * U(rng));
        const glm::vec3 sigma_a(3.0 * U(rng), 3.0 * U(rng), 3.0 * U(rng));
        const float alpha_R = float(-10.0 * kRadiansPerDegree * U(rng));
        const float beta_R = float((2.0 + 13.0 * U(rng)) * kRadiansPerDegree);
        const float ecc = float(0.85 + 0.3 * U(rng));
        const float w_c = float(0.05 + 0.25 * U(rng));
        c.params = linked_hair_params(eta, sigma_a, alpha_R, beta_R, ecc, w_c);
        c.sigma_f2 = float(0.05 * U(rng));
    }
    return out;
}

Stats error_stats(const std::vector<double>& errors, const std::vector<double>& weights) {
    Stats s;
    s.count = int(errors.size());
    if (errors.empty()) return s;
    // Unweighted figures count only configurations whose weight is at least 1 % of the mean: below
    // that the reference is ~0 and a relative error says nothing.
    double mean_weight = 0.0;
    for (double w : weights) mean_weight += w / double(weights.size());
    std::vector<std::pair<double, double>> ew, e1;
    for (size_t i = 0; i < errors.size(); ++i) {
        ew.emplace_back(errors[i], weights[i]);
        if (weights[i] >= 0.01 * mean_weight) e1.emplace_back(errors[i], 1.0);
    }
    s.median = weighted_quantile(ew, 0.5);
    s.p95 = weighted_quantile(ew, 0.95);
    s.median_unweighted = weighted_quantile(e1, 0.5);
    s.p95_unweighted = weighted_quantile(e1, 0.95);
    for (size_t i = 0; i < errors.size(); ++i)  // max over the same configurations
        if (weights[i] >= 0.01 * mean_weight) s.max = std::max(s.max, errors[i]);
    return s;
}

std::vector<SingleRow> check_single(const std::vector<Config>& configs, const std::vector<int>& segments,
                                    const std::function<void()>& progress) {
    struct Variant {
        std::string name;
        LightingConfig config;
    };
    std::vector<Variant> variants;
    for (int m : segments) variants.push_back({"improved", default_config(m)});
    for (int m : segments) variants.push_back({"paper", paper_config(m)});
    const size_t n = configs.size();
    std::vector<std::vector<double>> errors(variants.size(), std::vector<double>(n));
    std::vector<double> weights(n);
    const LutSet tables = global_lighting_tables().set();
    parallel_for_with_progress(
        int(n),
        [&](int i) {
            const Config& c = configs[size_t(i)];
            const glm::dvec3 ref = reference::single(c.params, c.theta_o, c.phi_o, c.theta_j, c.phi_j, c.lambda_j);
            weights[size_t(i)] = (ref.x + ref.y + ref.z) / srbf_energy(c.lambda_j);
            LutBinding bind(tables);
            for (size_t v = 0; v < variants.size(); ++v) {
                glsl::vec4 f0123, f45;
                glsl::srbf_point_setup(c.params, variants[v].config, f0123, f45);
                const glm::vec3 a = glsl::srbf_single(c.params, variants[v].config, f0123, f45, c.theta_o, c.phi_o,
                                                      c.theta_j, c.phi_j, c.lambda_j);
                errors[v][size_t(i)] = rel_error(glm::dvec3(a), ref);
            }
        },
        progress);
    std::vector<SingleRow> rows;
    for (size_t v = 0; v < variants.size(); ++v)
        rows.push_back({variants[v].name, variants[v].config.segments, error_stats(errors[v], weights)});
    return rows;
}

namespace {

struct Accum {
    double max = 0, sum2 = 0;
    int n = 0;
    void add(double e) {
        e = std::abs(e);
        max = std::max(max, e);
        sum2 += e * e;
        ++n;
    }
    ApproxRow row(std::string name, std::string metric) const {
        return {std::move(name), std::move(metric), max, n ? std::sqrt(sum2 / n) : 0.0, n};
    }
};

// ∫ |fit - exact| dφ / ∫ exact over φ ∈ [-π, π) (midpoint, `n` points), summed over RGB.
template <class Fit, class Exact>
double l1_relative(Fit fit, Exact exact, int n) {
    double diff = 0.0, total = 0.0;
    for (int i = 0; i < n; ++i) {
        const double phi = -kPi + (i + 0.5) * 2.0 * kPi / n;
        const glm::dvec3 f = fit(phi), e = exact(phi);
        for (int c = 0; c < 3; ++c) {
            diff += std::abs(f[c] - e[c]);
            total += e[c];
        }
    }
    return total > 0.0 ? diff / total : 0.0;
}

}  // namespace

std::vector<ApproxRow> check_approximations(const std::function<void()>& progress) {
    using namespace glsl;
    std::vector<ApproxRow> rows;
    LutBinding bind(global_lighting_tables().set());
    const auto tick = [&] {
        if (progress) progress();
    };
    {  // 𝒞_k look-ups between grid points vs direct integration
        Accum acc;
        for (int i = 0; i < 23; ++i) {
            const double lambda = 0.01 * std::pow(500.0, (i + 0.37) / 23.0);
            for (int j = 0; j < 29; ++j) {
                const double dphi = kPi * (j + 0.41) / 29.0;
                vec4 lo, hi;
                fetch_Ck(float(lambda), float(dphi), lo, hi);
                const float table[7] = {lo.x, lo.y, lo.z, lo.w, hi.x, hi.y, hi.z};
                for (int k = 0; k < 7; ++k) acc.add(table[k] - ck_direct(k, lambda, dphi));
            }
        }
        rows.push_back(acc.row("C_k table (eq. 14), k=0..6", "abs. error of C_k / int g^c (values in [0,1])"));
        tick();
    }
    for (int trt = 0; trt < 2; ++trt) {  // H_k look-ups vs direct integration
        Accum acc;
        for (int i = 0; i < 17; ++i) {
            const double eta = 1.3 + 1.3 * (i + 0.43) / 17.0;
            for (int j = 0; j < 17; ++j) {
                const double theta_d = 1.5 * (j + 0.39) / 17.0;
                const vec3 t = trt ? fetch_H_TRT(float(eta), float(theta_d)) : fetch_H_TT(float(eta), float(theta_d));
                const double h0 = h_direct(trt, 0, eta, theta_d);
                for (int k = 0; k < 3; ++k) acc.add((t[k] - h_direct(trt, 2 * k, eta, theta_d)) / h0);
            }
        }
        rows.push_back(acc.row(trt ? "H_k^TRT table (eq. 23), k=0,2,4" : "H_k^TT table (eq. 19), k=0,2,4",
                               "abs. error / H_0"));
        tick();
    }
    {  // Fresnel: Schlick (000) and the polynomial fit vs exact
        Accum schlick, fit;
        for (int i = 0; i < 21; ++i) {
            const float eta = float(1.2 + 1.3 * i / 20.0);
            vec4 f0123, f45;
            fetch_fresnel_fit(eta, f0123, f45);
            for (int j = 0; j <= 100; ++j) {
                const float mu = float(j / 100.0);
                const double exact = fresnel_dielectric(eta, mu);
                const double f0 = fresnel_schlick_f0(eta);
                schlick.add(f0 + (1.0 - f0) * std::pow(1.0 - mu, 5.0) - exact);
                const double p = f0123.x + mu * (f0123.y + mu * (f0123.z + mu * (f0123.w + mu * (f45.x + mu * f45.y))));
                fit.add(p - exact);
            }
        }
        rows.push_back(schlick.row("Fresnel, Schlick (000 4.2.1)", "abs. error, eta in [1.2,2.5], all angles"));
        rows.push_back(fit.row("Fresnel, degree-5 fit (ours)", "abs. error, eta in [1.2,2.5], all angles"));
        tick();
    }
    for (int variant = 0; variant < 3; ++variant) {  // Taylor expansions of T and T², and our interpolation
        const bool squared = variant == 1;
        Accum acc;
        for (double sa : {0.2, 0.6, 1.0, 3.0})
            for (int j = 0; j < 7; ++j) {
                const float theta_d = float(1.2 * j / 6.0);
                const float eta = 1.55f;
                const float eta_p = eta_prime(eta, theta_d);
                const vec3 sp = sigma_a_prime(vec3(float(sa)), eta, theta_d);
                vec3 a0, a2, a4;
                if (variant == 0) taylor_T(sp, eta_p, a0, a2, a4);
                else if (variant == 1) taylor_T2(sp, eta_p, a0, a2, a4);
                else interp_T(sp, eta_p, a0, a2, a4);
                for (int k = 0; k <= 100; ++k) {
                    const float h = float(-1.0 + 2.0 * k / 100.0);
                    const double exact = std::pow(double(attenuation_T(sp, h, eta_p).x), squared ? 2.0 : 1.0);
                    const double approx = a0.x + a2.x * h * h + a4.x * h * h * h * h;
                    acc.add(approx - exact);
                }
            }
        rows.push_back(acc.row(variant == 0 ? "T Taylor (eq. 18)" : (variant == 1 ? "T^2 Taylor (eq. 22)" : "T interpolated at h^2 = 0, 1/2, 1 (ours)"),
                               "abs. error, sigma_a in {0.2,0.6,1,3}, theta_d <= 1.2, |h| <= 1"));
        tick();
    }
    {  // N_TT as one circular Gaussian (and N_TRT) vs exact, L1 relative to the exact energy
        Accum tt, trt, tt_e, trt_e, tt_ep, trt_ep;
        for (float eta : {1.4f, 1.55f, 1.8f})
            for (float theta_d : {0.0f, 0.5235988f, 1.0471976f})
                for (float sa : {0.0f, 0.5f, 2.0f})
                    for (float w_c : {0.05f, 0.15f, 0.3f}) {
                        HairParams p = linked_hair_params(eta, vec3(sa), -0.1f, 0.1f, 1.0f, w_c);
                        LightingConfig cfg = default_config(4);
                        if (w_c == 0.15f) {
                            vec3 b, lam;
                            N_TT_fit(eta, p.sigma_a, theta_d, false, b, lam);
                            tt.add(l1_relative(
                                [&](double phi) {
                                    vec3 r(0.0f);
                                    for (int c = 0; c < 3; ++c) r[c] = b[c] * circ_gauss(float(phi), COIF_PI, lam[c]);
                                    return glm::dvec3(r);
                                },
                                [&](double phi) { return reference::N_exact(LOBE_TT, p, eta, theta_d, phi); }, 256));
                            const glm::dvec3 e = reference::energy_exact(LOBE_TT, p, eta, theta_d);
                            for (int c = 0; c < 3; ++c)
                                tt_e.add((b[c] * circ_integral(lam[c], false) - e[c]) / e[c]);
                            N_TT_fit(eta, p.sigma_a, theta_d, true, b, lam);
                            for (int c = 0; c < 3; ++c)
                                tt_ep.add((b[c] * circ_integral(lam[c], true) - e[c]) / e[c]);
                        }
                        const TrtFit fit = N_TRT_fit(eta, p.sigma_a, theta_d, w_c, p.delta_eta_p, false);
                        trt.add(l1_relative([&](double phi) { return glm::dvec3(N_TRT_fit_value(fit, float(phi))); },
                                            [&](double phi) { return reference::N_exact(LOBE_TRT, p, eta, theta_d, phi); },
                                            256));
                        const glm::dvec3 e = reference::energy_exact(LOBE_TRT, p, eta, theta_d);
                        double fit_e = 0.0;
                        {
                            constexpr int n = 512;
                            for (int i = 0; i < n; ++i)
                                fit_e += N_TRT_fit_value(fit, float(-kPi + (i + 0.5) * 2.0 * kPi / n)).x * 2.0 * kPi / n;
                        }
                        trt_e.add((fit_e - e.x) / e.x);
                        {
                            const TrtFit pf = N_TRT_fit(eta, p.sigma_a, theta_d, w_c, p.delta_eta_p, true);
                            double pe = 0.0;
                            constexpr int n = 512;
                            for (int i = 0; i < n; ++i)
                                pe += N_TRT_fit_value(pf, float(-kPi + (i + 0.5) * 2.0 * kPi / n)).x * 2.0 * kPi / n;
                            trt_ep.add((pe - e.x) / e.x);
                        }
                        (void)cfg;
                    }
        rows.push_back(tt.row("N_TT one circular Gaussian (eq. 16)", "int|fit-exact| / int exact"));
        rows.push_back(tt_ep.row("N_TT energy, 000 (Taylor T, sqrt(pi) lambda)", "rel. error of int N_TT"));
        rows.push_back(tt_e.row("N_TT energy, ours (interpolated T, Bessel)", "rel. error of int N_TT"));
        rows.push_back(trt.row("N_TRT 3/1 circular Gaussians (eq. 20)", "int|fit-exact| / int exact (w_c-smoothed)"));
        rows.push_back(trt_ep.row("N_TRT energy, 000 (Taylor T^2, sqrt(pi) lambda)", "rel. error of int N_TRT"));
        rows.push_back(trt_e.row("N_TRT energy, ours (interpolated T^2, Bessel)", "rel. error of int N_TRT"));
        tick();
    }
    {  // the paper's ∫g^c ≈ √πλ
        Accum acc;
        for (int i = 0; i <= 40; ++i) {
            const float lambda = float(0.05 * std::pow(40.0, i / 40.0));
            acc.add(circ_integral(lambda, true) / circ_integral(lambda, false) - 1.0);
        }
        rows.push_back(acc.row("int g^c = sqrt(pi) lambda (000 4.2.3)", "rel. error, lambda in [0.05, 2]"));
        tick();
    }
    return rows;
}

std::vector<MultipleRow> check_multiple(int param_sets, int per_set, std::uint64_t seed,
                                        const std::function<void()>& progress) {
    const std::vector<Config> sets = random_configs(param_sets, seed);
    std::vector<Config> all;
    // Each parameter set fills its own slot; the slots are joined in set order, so the figures do not
    // depend on the thread count.
    struct Errors {
        std::vector<double> eg, el, et, w_g, w_l, w_t;
    };
    std::vector<Errors> by_set(static_cast<size_t>(std::max(param_sets, 0)));
    parallel_for_with_progress(
        param_sets,
        [&](int s) {
            Errors& out = by_set[size_t(s)];
            HairParams p = sets[size_t(s)].params;
            p.ecc_a = 1.0f;  // dual scattering uses the circular fibre (srbf_multiple.glsl)
            const LightingEvaluator eval(p, default_config(4));
            const reference::ZinkeTable table = reference::zinke_table(p, 129);
            const std::vector<Config> views = random_configs(per_set, seed * 7919 + std::uint64_t(s) + 1);
            for (const Config& c : views) {
                const glm::dvec3 g_ref = reference::ms_global(p, c.theta_o, c.phi_o, c.theta_j, c.phi_j, c.lambda_j, c.sigma_f2);
                const glm::dvec3 l_ref = reference::ms_local(p, table, c.theta_o, c.phi_o, c.theta_j, c.phi_j, c.lambda_j, c.sigma_f2);
                const glm::dvec3 g = eval.ms_global(c.theta_o, c.phi_o, c.theta_j, c.phi_j, c.lambda_j, c.sigma_f2);
                const glm::dvec3 l = eval.ms_local(c.theta_o, c.phi_o, c.theta_j, c.phi_j, c.lambda_j, c.sigma_f2);
                const double e = srbf_energy(c.lambda_j);
                const glm::dvec3 t_ref = g_ref + double(p.d_b) * l_ref, t = g + double(p.d_b) * l;
                out.eg.push_back(rel_error(g, g_ref));
                out.w_g.push_back((g_ref.x + g_ref.y + g_ref.z) / e);
                out.el.push_back(rel_error(l, l_ref));
                out.w_l.push_back((l_ref.x + l_ref.y + l_ref.z) / e);
                out.et.push_back(rel_error(t, t_ref));
                out.w_t.push_back((t_ref.x + t_ref.y + t_ref.z) / e);
            }
        },
        progress);
    std::vector<double> eg, el, et, w_g, w_l, w_t;
    const auto append = [](std::vector<double>& to, const std::vector<double>& from) { to.insert(to.end(), from.begin(), from.end()); };
    for (const Errors& r : by_set) {
        append(eg, r.eg), append(w_g, r.w_g), append(el, r.el), append(w_l, r.w_l), append(et, r.et), append(w_t, r.w_t);
    }
    return {{"global M^G", error_stats(eg, w_g)},
            {"local M^L", error_stats(el, w_l)},
            {"M^G + d_b M^L", error_stats(et, w_t)}};
}

std::vector<CostRow> count_fetches(int segments) {
    const std::vector<Config> configs = random_configs(40, 99);
    double single = 0, multiple = 0, setup = 0;
    for (const Config& c : configs) {
        HairParams p = c.params;
        const LightingEvaluator eval(p, default_config(segments));
        auto bind = eval.bind();
        glsl::vec4 f0123, f45;
        std::uint64_t n0 = lut_fetch_count();
        glsl::srbf_point_setup(p, eval.config(), f0123, f45);
        std::uint64_t n1 = lut_fetch_count();
        glsl::srbf_single(p, eval.config(), f0123, f45, c.theta_o, c.phi_o, c.theta_j, c.phi_j, c.lambda_j);
        std::uint64_t n2 = lut_fetch_count();
        glsl::srbf_multiple(p, eval.config(), f0123, f45, c.theta_o, c.phi_o, c.theta_j, c.phi_j, c.lambda_j, c.sigma_f2);
        std::uint64_t n3 = lut_fetch_count();
        setup += double(n1 - n0);
        single += double(n2 - n1);
        multiple += double(n3 - n2);
    }
    const double n = double(configs.size());
    return {{"per shading point (Fresnel fit, eta only)", setup / n},
            {"single scattering, per light", single / n},
            {"multiple scattering, per light", multiple / n}};
}

}  // namespace coif::shading::check
