#include "shaders/marschner_reference.h"

#include <algorithm>
#include <cmath>

#include "models/core/units.h"
#include "shaders/hair_parameters.h"

namespace coif::shading::reference {

namespace {

double wrap(double x) { return x - 2.0 * kPi * std::floor((x + kPi) / (2.0 * kPi)); }

double gc(double x, double lambda) {
    const double s = std::sin(0.5 * x);
    return std::exp(-4.0 * s * s / (lambda * lambda));
}

double gauss_u(double x, double mu, double lambda) {
    const double d = (x - mu) / lambda;
    return std::exp(-d * d) / (std::sqrt(kPi) * lambda);
}

// Gauss-Hermite rule for ∫ e^{-t²} f(t) dt (Numerical Recipes' gauher).
struct GaussHermite {
    std::vector<double> x, w;
    explicit GaussHermite(int n) : x(n), w(n) {
        const double pim4 = 0.7511255444649425;
        double z = 0.0, pp = 0.0;
        for (int i = 0; i < (n + 1) / 2; ++i) {
            if (i == 0) z = std::sqrt(2.0 * n + 1) - 1.85575 * std::pow(2.0 * n + 1, -0.16667);
            else if (i == 1) z -= 1.14 * std::pow(double(n), 0.426) / z;
            else if (i == 2) z = 1.86 * z - 0.86 * x[0];
            else if (i == 3) z = 1.91 * z - 0.91 * x[1];
            else z = 2.0 * z - x[i - 2];
            for (int it = 0; it < 100; ++it) {
                double p1 = pim4, p2 = 0.0;
                for (int j = 0; j < n; ++j) {
                    const double p3 = p2;
                    p2 = p1;
                    p1 = z * std::sqrt(2.0 / (j + 1)) * p2 - std::sqrt(double(j) / (j + 1)) * p3;
                }
                pp = std::sqrt(2.0 * n) * p2;
                const double z1 = z;
                z = z1 - p1 / pp;
                if (std::abs(z - z1) <= 1e-14) break;
            }
            x[i] = z;
            x[n - 1 - i] = -z;
            w[i] = 2.0 / (pp * pp);
            w[n - 1 - i] = w[i];
        }
    }
};

const GaussHermite& gh() {
    static const GaussHermite rule(32);
    return rule;
}

// ∫ g^c(y; 0, a) f(y) dy for a narrow (a <= ~0.5) circular Gaussian: Gauss-Hermite in y = a t with
// the smooth ratio g^c / g folded into the integrand.
template <class F>
double circ_weighted(double a, F f) {
    const GaussHermite& r = gh();
    double acc = 0.0;
    for (size_t i = 0; i < r.x.size(); ++i) {
        const double y = a * r.x[i];
        acc += r.w[i] * std::exp(r.x[i] * r.x[i]) * gc(y, a) * f(y);
    }
    return a * acc;
}

double circ_norm(double a) {
    return circ_weighted(a, [](double) { return 1.0; });
}

// (g^c(·;λ') ⊛ ĝ^c(·;w_c))(d): the SRBF's azimuthal kernel blurred by the TRT roughness.
double blurred_kernel(double d, double lambda_p, double w_c) {
    if (w_c <= lambda_p)
        return circ_weighted(w_c, [&](double y) { return gc(d - y, lambda_p); }) / circ_norm(w_c);
    return circ_weighted(lambda_p, [&](double y) { return gc(d - y, w_c); }) / circ_norm(w_c);
}

glm::dvec3 A_of(int lobe, const HairParams& p, double eta, double theta_d, double h) {
    return glm::dvec3(glsl::attenuation_A(lobe, float(eta), p.sigma_a, float(theta_d), float(h)));
}

double phi_of(int lobe, double h, double eta_p) {
    return 2.0 * lobe * std::asin(std::clamp(h / eta_p, -1.0, 1.0)) - 2.0 * std::asin(std::clamp(h, -1.0, 1.0)) +
           lobe * kPi;
}

double eta_p_of(double eta, double theta_d) { return double(glsl::eta_prime(float(eta), float(theta_d))); }

double max_slope(int lobe, double eta_p) { return lobe == glsl::LOBE_TRT ? 2.0 + 4.0 / eta_p : 2.0; }

// ½ ∫_{-1}^{1} A_t(h) K(φ_t(h)) dh in γ = asin h (midpoint rule, n steps).
template <class K>
glm::dvec3 h_integral(int lobe, const HairParams& p, double eta, double theta_d, int n, K kernel) {
    const double eta_p = eta_p_of(eta, theta_d);
    const double dg = kPi / n;
    glm::dvec3 acc(0.0);
    for (int i = 0; i < n; ++i) {
        const double g = -0.5 * kPi + (i + 0.5) * dg;
        const double h = std::sin(g);
        const double k = kernel(phi_of(lobe, h, eta_p));
        if (k == 0.0) continue;
        acc += A_of(lobe, p, eta, theta_d, h) * (k * std::cos(g));
    }
    return 0.5 * dg * acc;
}

int steps_for(double slope, double width) { return std::clamp(int(std::ceil(kPi * slope / (0.25 * width))), 512, 60000); }

// N_TRT roughened, at one azimuth, for index `eta`.
glm::dvec3 trt_rough(const HairParams& p, double eta, double theta_d, double phi) {
    const double eta_p = eta_p_of(eta, theta_d);
    const double z = circ_norm(p.w_c);
    return h_integral(glsl::LOBE_TRT, p, eta, theta_d, steps_for(max_slope(glsl::LOBE_TRT, eta_p), p.w_c),
                      [&](double ph) { return gc(phi - ph, p.w_c) / z; });
}

// Σ over roots h of φ_t(h) = φ of ½ A_t(h) / |dφ/dh| (000 eq. 9).
glm::dvec3 sum_over_roots(int lobe, const HairParams& p, double eta, double theta_d, double phi) {
    const double eta_p = eta_p_of(eta, theta_d);
    const auto f = [&](double h) { return wrap(phi_of(lobe, h, eta_p) - phi); };
    constexpr int scan = 4000;
    glm::dvec3 acc(0.0);
    double h_prev = std::sin(-0.5 * kPi + 1e-9), f_prev = f(h_prev);
    for (int i = 1; i <= scan; ++i) {
        const double h = std::sin(-0.5 * kPi + kPi * i / scan - (i == scan ? 1e-9 : 0.0));
        const double fh = f(h);
        if ((f_prev <= 0.0) != (fh <= 0.0) && std::abs(fh - f_prev) < kPi) {
            double a = h_prev, b = h, fa = f_prev;
            for (int it = 0; it < 60; ++it) {
                const double m = 0.5 * (a + b), fm = f(m);
                if ((fa <= 0.0) == (fm <= 0.0)) { a = m; fa = fm; } else { b = m; }
            }
            const double r = 0.5 * (a + b);
            const double dphi = 2.0 * lobe / std::sqrt(eta_p * eta_p - r * r) - 2.0 / std::sqrt(std::max(1.0 - r * r, 1e-300));
            acc += 0.5 * A_of(lobe, p, eta, theta_d, r) / std::max(std::abs(dphi), 1e-300);
        }
        h_prev = h;
        f_prev = fh;
    }
    return acc;
}

// Inner integral with eccentricity: η*(φh) varies with φi = φj + x, so the 2D integral over (h, x) is
// done directly. For each h the roughness kernel ĝ^c(Δ - x - φ(h); w_c) confines x to a window of
// ±(5.5 w_c + 0.15) around its centre at η*(x = 0) (0.15 rad bounds how far φ(h) moves as η* changes
// across the window; beyond 5.5 w_c the kernel is below e^{-30}).
glm::dvec3 inner_eccentric(const HairParams& p, double theta_d, double lambda_p, double dphi, double cos_base,
                           double sin_base) {
    const double w_c = p.w_c;
    const double z = circ_norm(w_c);
    const double eta0 = glsl::eta_star(p.eta, p.ecc_a, float(cos_base));
    const double eta_p0 = eta_p_of(eta0, theta_d);
    const int n_g = steps_for(max_slope(glsl::LOBE_TRT, eta_p0), w_c);
    const double dg = kPi / n_g;
    const double half = 5.5 * w_c + 0.15;
    const double dx_target = 0.7 * std::min(lambda_p, w_c);
    const int n_x = std::max(16, int(std::ceil(2.0 * half / dx_target)));
    const double dx = 2.0 * half / n_x;
    glm::dvec3 acc(0.0);
    for (int i = 0; i < n_g; ++i) {
        const double g = -0.5 * kPi + (i + 0.5) * dg;
        const double h = std::sin(g);
        const double x0 = wrap(dphi - phi_of(glsl::LOBE_TRT, h, eta_p0));
        for (int k = 0; k < n_x; ++k) {
            const double x = x0 - half + (k + 0.5) * dx;
            const double w = gc(x, lambda_p);
            if (w < 1e-30) continue;
            const double cos_2phi_h = cos_base * std::cos(x) - sin_base * std::sin(x);
            const double eta_e = glsl::eta_star(p.eta, p.ecc_a, float(cos_2phi_h));
            const double eta_p = eta_p_of(eta_e, theta_d);
            const double kern = gc(dphi - x - phi_of(glsl::LOBE_TRT, h, eta_p), w_c) / z;
            if (kern < 1e-30) continue;
            acc += A_of(glsl::LOBE_TRT, p, eta_e, theta_d, h) * (w * kern * std::cos(g));
        }
    }
    return 0.5 * dg * dx * acc;
}

}  // namespace

glm::dvec3 N_exact(int lobe, const HairParams& p, double eta, double theta_d, double phi) {
    if (lobe == glsl::LOBE_TRT) return trt_rough(p, eta, theta_d, phi);
    return sum_over_roots(lobe, p, eta, theta_d, phi);
}

glm::dvec3 N_TRT_unsmoothed(const HairParams& p, double eta, double theta_d, double phi) {
    return sum_over_roots(glsl::LOBE_TRT, p, eta, theta_d, phi);
}

glm::dvec3 energy_exact(int lobe, const HairParams& p, double eta, double theta_d) {
    return h_integral(lobe, p, eta, theta_d, 4000, [](double) { return 1.0; });
}

glm::dvec3 inner_exact(int lobe, const HairParams& p, double eta, double theta_d, double lambda_p, double dphi) {
    const double eta_p = eta_p_of(eta, theta_d);
    if (lobe == glsl::LOBE_TRT) {
        const double width = std::min(std::sqrt(lambda_p * lambda_p + double(p.w_c) * p.w_c), kPi);
        return h_integral(lobe, p, eta, theta_d, steps_for(max_slope(lobe, eta_p), width),
                          [&](double ph) { return blurred_kernel(dphi - ph, lambda_p, p.w_c); });
    }
    return h_integral(lobe, p, eta, theta_d, steps_for(max_slope(lobe, eta_p), std::min(lambda_p, kPi)),
                      [&](double ph) { return gc(dphi - ph, lambda_p); });
}

glm::dvec3 single_lobe(int lobe, const HairParams& p, double theta_o, double phi_o, double theta_j, double phi_j,
                       double lambda_j) {
    const double alpha = glsl::lobe_alpha(p, lobe), beta = glsl::lobe_beta(p, lobe);
    const double mu2 = 2.0 * alpha - theta_o, l2 = 2.0 * beta;
    // Beyond these windows g^c_j or M_t is below e^{-25} of its peak.
    const double s = std::min(1.0, std::sqrt(25.0 / 4.0) * lambda_j);
    const double dj = 2.0 * std::asin(s);
    const double lo = std::max({-0.5 * kPi, mu2 - 5.0 * l2, theta_j - dj});
    const double hi = std::min({0.5 * kPi, mu2 + 5.0 * l2, theta_j + dj});
    if (!(hi > lo)) return glm::dvec3(0.0);
    const double lp = lambda_j * l2 / std::sqrt(lambda_j * lambda_j + l2 * l2);
    const double step = std::min(0.5 * lp, 0.03);
    const int n = std::max(16, int(std::ceil((hi - lo) / step)));
    const double dt = (hi - lo) / n;
    const double dphi = wrap(phi_o - phi_j);
    const double cos_j = std::cos(theta_j);
    const double cos_base = std::cos(phi_j + phi_o), sin_base = std::sin(phi_j + phi_o);
    glm::dvec3 acc(0.0);
    for (int i = 0; i < n; ++i) {
        const double ti = lo + (i + 0.5) * dt;
        const double ci = std::cos(ti);
        if (ci <= 0.0) continue;
        const double theta_d = 0.5 * (theta_o - ti), cd = std::cos(theta_d);
        const double weight = gc(ti - theta_j, lambda_j) * gauss_u(0.5 * (ti + theta_o), alpha, beta) * ci * ci /
                              std::max(cd * cd, 1e-12);
        if (weight < 1e-300) continue;
        const double lambda_p = std::min(lambda_j / std::sqrt(std::max(ci * cos_j, 1e-300)), 1e4);
        const glm::dvec3 inner = (lobe == glsl::LOBE_TRT && p.ecc_a != 1.0f)
                                     ? inner_eccentric(p, theta_d, lambda_p, dphi, cos_base, sin_base)
                                     : inner_exact(lobe, p, p.eta, theta_d, lambda_p, dphi);
        acc += weight * inner;
    }
    return acc * dt * double(glsl::M_norm(p, lobe, float(theta_o)));
}

glm::dvec3 single(const HairParams& p, double theta_o, double phi_o, double theta_j, double phi_j, double lambda_j) {
    glm::dvec3 r(0.0);
    for (int lobe = 0; lobe < kLobeCount; ++lobe) r += single_lobe(lobe, p, theta_o, phi_o, theta_j, phi_j, lambda_j);
    return r;
}

namespace {

// Forward and backward azimuthal moments ∫ w(|φ|) N_t(θd, φ) dφ, w = |φ| or π - |φ| (000 eq. 33).
void azimuthal_moments(int lobe, const HairParams& p, double theta_d, glm::dvec3& fwd, glm::dvec3& bwd) {
    const double eta_p = eta_p_of(p.eta, theta_d);
    constexpr int n = 512;
    const double dg = kPi / n;
    fwd = bwd = glm::dvec3(0.0);
    for (int i = 0; i < n; ++i) {
        const double g = -0.5 * kPi + (i + 0.5) * dg;
        const double h = std::sin(g);
        const double ph = phi_of(lobe, h, eta_p);
        double wf = 0.0;
        if (lobe == glsl::LOBE_TRT) {
            wf = circ_weighted(p.w_c, [&](double y) { return std::abs(wrap(ph + y)); }) / circ_norm(p.w_c);
        } else {
            wf = std::abs(wrap(ph));
        }
        const glm::dvec3 a = A_of(lobe, p, p.eta, theta_d, h) * (0.5 * std::cos(g) * dg);
        fwd += a * wf;
        bwd += a * (kPi - wf);
    }
}

glm::dvec3 lerp_table(const std::vector<double>& xs, const std::vector<glm::dvec3>& ys, double x) {
    const double t = std::clamp((x - xs.front()) / (xs.back() - xs.front()), 0.0, 1.0) * (xs.size() - 1);
    const size_t i = std::min(size_t(t), xs.size() - 2);
    const double f = t - i;
    return ys[i] * (1.0 - f) + ys[i + 1] * f;
}

}  // namespace

glm::dvec3 ZinkeTable::A_b_at(double x) const { return lerp_table(theta_d, A_b, x); }
glm::dvec3 ZinkeTable::Delta_b_at(double x) const { return lerp_table(theta_d, Delta_b, x); }
glm::dvec3 ZinkeTable::sigma_b_at(double x) const { return lerp_table(theta_d, sigma_b, x); }

ZinkeTable zinke_table(const HairParams& p, int points) {
    ZinkeTable t;
    const size_t n = size_t(points);
    t.theta_d.resize(n);
    for (auto* v : {&t.a_f, &t.a_b, &t.alpha_f, &t.alpha_b, &t.beta_f2, &t.beta_b2, &t.A_b, &t.Delta_b, &t.sigma_b})
        v->assign(n, glm::dvec3(0.0));
    for (size_t k = 0; k < n; ++k) {
        const double x = -0.5 * kPi + kPi * double(k) / double(n - 1);
        t.theta_d[k] = x;
        glm::dvec3 af(0.0), ab(0.0), alf(0.0), alb(0.0), bf(0.0), bb(0.0);
        for (int lobe = 0; lobe < kLobeCount; ++lobe) {
            const double alpha = glsl::lobe_alpha(p, lobe), beta = glsl::lobe_beta(p, lobe);
            // (1/π) ∫ M_t((x+θo)/2) cos θo cos x / cos²((x-θo)/2) m(θd = (x-θo)/2) dθo (000 eq. 33, unseparated)
            const double mu = 2.0 * alpha - x, l = 2.0 * beta;
            const double lo = std::max(-0.5 * kPi, mu - 7.0 * l), hi = std::min(0.5 * kPi, mu + 7.0 * l);
            glm::dvec3 f(0.0), b(0.0);
            if (hi > lo) {
                const int steps = std::max(24, int(std::ceil((hi - lo) / std::min(0.5 * l, 0.02))));
                const double dt = (hi - lo) / steps;
                for (int i = 0; i < steps; ++i) {
                    const double to = lo + (i + 0.5) * dt;
                    const double c = std::cos(0.5 * (x - to));
                    const double norm = p.longitudinal >= 0.5f ? 1.0 : 2.0 * double(glsl::M_norm(p, lobe, float(to)));
                    const double w = gauss_u(0.5 * (x + to), alpha, beta) * std::cos(to) * std::cos(x) /
                                     std::max(c * c, 1e-12) * dt / (2.0 * kPi) * norm;  // 1/(2π): see zinke_lobe_a
                    glm::dvec3 mf, mb;
                    azimuthal_moments(lobe, p, 0.5 * (x - to), mf, mb);
                    f += w * mf;
                    b += w * mb;
                }
            }
            const double var = 0.5 * beta * beta;
            f = glm::max(f, glm::dvec3(0.0)) + 1e-12;  // the same floor as zinke_terms (grazing θd)
            b = glm::max(b, glm::dvec3(0.0)) + 1e-12;
            af += f;
            ab += b;
            alf += f * alpha;
            alb += b * alpha;
            bf += f * var;
            bb += b * var;
        }
        t.a_f[k] = af;
        t.a_b[k] = ab;
        t.alpha_f[k] = alf / af;
        t.alpha_b[k] = alb / ab;
        t.beta_f2[k] = bf / af;
        t.beta_b2[k] = bb / ab;
        glm::vec3 A, D, S;
        glsl::zinke_backscatter(glm::vec3(af), glm::vec3(ab), glm::vec3(t.alpha_f[k]), glm::vec3(t.alpha_b[k]),
                                glm::vec3(t.beta_f2[k]), glm::vec3(t.beta_b2[k]), p.d_b, A, D, S);
        t.A_b[k] = glm::dvec3(A);
        t.Delta_b[k] = glm::dvec3(D);
        t.sigma_b[k] = glm::dvec3(S);
    }
    return t;
}

glm::dvec3 ms_global(const HairParams& p, double theta_o, double phi_o, double theta_j, double phi_j, double lambda_j,
                     double sigma_f2) {
    const double lambda_f = std::sqrt(lambda_j * lambda_j + 2.0 * std::max(sigma_f2, 0.0));
    const double dphi = wrap(phi_o - phi_j);
    glm::dvec3 total(0.0);
    for (int lobe = 0; lobe < kLobeCount; ++lobe) {
        const double alpha = glsl::lobe_alpha(p, lobe), beta = glsl::lobe_beta(p, lobe);
        const double mu2 = 2.0 * alpha - theta_o, l2 = 2.0 * beta;
        const double lo = std::max({-0.5 * kPi, mu2 - 7.0 * l2, theta_j - 7.0 * lambda_f});
        const double hi = std::min({0.5 * kPi, mu2 + 7.0 * l2, theta_j + 7.0 * lambda_f});
        if (!(hi > lo)) continue;
        const double lp = lambda_f * l2 / std::sqrt(lambda_f * lambda_f + l2 * l2);
        const int n = std::max(16, int(std::ceil((hi - lo) / std::min(0.5 * lp, 0.02))));
        const double dt = (hi - lo) / n;
        for (int i = 0; i < n; ++i) {
            const double ti = lo + (i + 0.5) * dt;
            const double ci = std::cos(ti);
            if (ci <= 0.0) continue;
            const double theta_d = 0.5 * (theta_o - ti), cd = std::cos(theta_d);
            const double w = gauss_u(ti, theta_j, lambda_f) * gauss_u(0.5 * (ti + theta_o), alpha, beta) * ci /
                             std::max(cd * cd, 1e-12);
            if (w < 1e-300) continue;
            // (1/π) ∫_{Δ-π/2}^{Δ+π/2} N_t: the window's indicator (blurred by w_c for TRT).
            const glm::dvec3 ng = h_integral(lobe, p, p.eta, theta_d, 4096, [&](double ph) {
                const double d = wrap(ph - dphi);
                if (lobe != glsl::LOBE_TRT) return std::abs(d) <= 0.5 * kPi ? 1.0 : 0.0;
                return 0.5 * (std::erf((0.5 * kPi - d) / p.w_c) + std::erf((0.5 * kPi + d) / p.w_c));
            });
            total += w * ng / kPi * dt * double(glsl::M_norm(p, lobe, float(theta_o)));
        }
    }
    return total;
}

glm::dvec3 ms_local(const HairParams& params, const ZinkeTable& table, double theta_o, double phi_o, double theta_j,
                    double phi_j, double lambda_j, double sigma_f2) {
    const double lambda_f = std::sqrt(lambda_j * lambda_j + 2.0 * std::max(sigma_f2, 0.0));
    const double dphi = wrap(phi_o - phi_j);
    const double azimuthal = (kPi - std::abs(dphi)) / (kPi * kPi);
    const double lo = std::max(-0.5 * kPi, theta_j - 7.0 * lambda_f), hi = std::min(0.5 * kPi, theta_j + 7.0 * lambda_f);
    if (!(hi > lo)) return glm::dvec3(0.0);
    const int n = std::max(64, int(std::ceil((hi - lo) / 0.004)));
    const double dt = (hi - lo) / n;
    glm::dvec3 acc(0.0);
    for (int i = 0; i < n; ++i) {
        const double ti = lo + (i + 0.5) * dt;
        const double ci = std::cos(ti);
        if (ci <= 0.0) continue;
        const double theta_d = 0.5 * (theta_o - ti), cd = std::cos(theta_d);
        const glm::dvec3 A = table.A_b_at(theta_d), D = table.Delta_b_at(theta_d), S = table.sigma_b_at(theta_d);
        for (int c = 0; c < 3; ++c) {
            const double lb = 2.0 * std::sqrt(2.0) * std::max(S[c], 1e-3);
            // The backward lobe 2 g^u(θi; 2Δ_b − θo, λb), divided by its θi integral when energy-conserving
            // (srbf_multiple.glsl's header).
            const double mu = 2.0 * D[c] - theta_o;
            const double norm = params.longitudinal >= 0.5f
                                    ? 1.0
                                    : 1.0 / std::max(0.5 * (std::erf((0.5 * kPi - mu) / lb) - std::erf((-0.5 * kPi - mu) / lb)) * 2.0, 1e-6);
            acc[c] += gauss_u(ti, theta_j, lambda_f) * 2.0 * gauss_u(ti, mu, lb) * norm * 2.0 * A[c] * ci / std::max(cd * cd, 1e-12);
        }
    }
    return acc * dt * azimuthal;
}

}  // namespace coif::shading::reference
