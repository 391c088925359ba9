#include "shaders/lighting_tables.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/units.h"
#include "shaders/lighting.h"

namespace coif::glsl {
#include "shaders/lighting/own_cluster.glsl"
}  // namespace coif::glsl

#ifndef COIF_LIGHTING_TABLES_GENERATOR
namespace coif::embedded {  // the tables computed at build time (shaders/CMakeLists.txt)
std::optional<std::span<const unsigned char>> lighting_tables_data(std::string_view path);
}
#endif

namespace coif::shading {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Rows y = 0..height-1 of `fill(y)` on every hardware thread (the tables are independent per row).
template <class Fn>
void parallel_rows(int height, Fn fill) {
    parallel_for(static_cast<std::size_t>(std::max(height, 0)), 0, [&](std::size_t y) { fill(static_cast<int>(y)); });
}

double von_mises_weight(double x, double lambda) {
    const double s = std::sin(0.5 * x);
    return std::exp(-4.0 * s * s / (lambda * lambda));
}

// E[|cos((Δ-x)/2)|^k] for k = 0..6 under the normalised g^c(x; 0, λ).
std::array<double, 7> ck_all(double lambda, double dphi) {
    std::array<double, 7> acc{};
    double norm = 0.0;
    const bool narrow = lambda < 0.3;
    const int n = narrow ? 401 : 1024;
    const double x0 = narrow ? -12.0 * lambda : -kPi;
    const double dx = narrow ? 24.0 * lambda / (n - 1) : 2.0 * kPi / n;
    for (int i = 0; i < n; ++i) {
        const double x = x0 + i * dx;
        double w = von_mises_weight(x, lambda);
        if (narrow && (i == 0 || i == n - 1)) w *= 0.5;
        const double c = std::abs(std::cos(0.5 * (dphi - x)));
        double p = 1.0;
        for (int k = 0; k < 7; ++k) {
            acc[k] += w * p;
            p *= c;
        }
        norm += w;
    }
    for (double& a : acc) a /= norm;
    return acc;
}

// (H_0, H_2, H_4) of TT or TRT: ∫_{-1}^{1} (1-F)² [F] h^k dh with h = sin γ.
std::array<double, 3> h_all(bool trt, double eta, double theta_d) {
    constexpr int n = 2000;
    std::array<double, 3> acc{};
    const double dg = kPi / n;
    for (int i = 0; i < n; ++i) {
        const double g = -0.5 * kPi + (i + 0.5) * dg;
        const double h = std::sin(g);
        const double f = glsl::fresnel_h(float(eta), float(theta_d), float(h));
        double v = (1.0 - f) * (1.0 - f) * (trt ? f : 1.0) * std::cos(g) * dg;
        const double h2 = h * h;
        acc[0] += v;
        acc[1] += v * h2;
        acc[2] += v * h2 * h2;
    }
    return acc;
}

// Coefficients of the relative least-squares fit F(η, μ) ≈ Σ_{n<6} f_n μ^n on μ ∈ [0, 1].
std::array<double, 6> fresnel_fit_coefficients(double eta) {
    std::array<double, 6> f{};
    if (eta <= 1.0 + 1e-9) return f;
    constexpr int samples = 256;
    double a[6][7] = {};
    for (int i = 0; i < samples; ++i) {
        const double mu = 0.5 - 0.5 * std::cos(kPi * (i + 0.5) / samples);  // Chebyshev nodes
        const double F = glsl::fresnel_dielectric(float(eta), float(mu));
        const double w = 1.0 / F;  // between absolute and relative: N_R needs both ends
        double p[6];
        p[0] = 1.0;
        for (int k = 1; k < 6; ++k) p[k] = p[k - 1] * mu;
        for (int r = 0; r < 6; ++r) {
            for (int c = 0; c < 6; ++c) a[r][c] += w * p[r] * p[c];
            a[r][6] += w * p[r] * F;
        }
    }
    for (int col = 0; col < 6; ++col) {  // Gaussian elimination with partial pivoting
        int piv = col;
        for (int r = col + 1; r < 6; ++r)
            if (std::abs(a[r][col]) > std::abs(a[piv][col])) piv = r;
        for (int c = 0; c < 7; ++c) std::swap(a[col][c], a[piv][c]);
        for (int r = 0; r < 6; ++r) {
            if (r == col) continue;
            const double m = a[r][col] / a[col][col];
            for (int c = col; c < 7; ++c) a[r][c] -= m * a[col][c];
        }
    }
    for (int k = 0; k < 6; ++k) f[k] = a[k][6] / a[k][k];
    return f;
}

}  // namespace

double ck_direct(int k, double lambda_p, double dphi) { return ck_all(lambda_p, dphi)[std::clamp(k, 0, 6)]; }

double h_direct(bool trt, int k, double eta, double theta_d) {
    return h_all(trt, eta, theta_d)[std::clamp(k / 2, 0, 2)];
}

double half_mass_direct(double lambda, double delta) {
    if (lambda < 0.02) {  // g^c is a Gaussian to float precision over its support
        return 0.5 * (std::erf((delta + 0.5 * kPi) / lambda) - std::erf((delta - 0.5 * kPi) / lambda));
    }
    constexpr int n = 1024;  // spacing 0.006 rad: spectrally accurate for λ >= 0.02 away from the edges
    double inside = 0.0, all = 0.0;
    for (int i = 0; i < n; ++i) {
        const double x = -kPi + (i + 0.5) * 2.0 * kPi / n;
        const double w = von_mises_weight(x, lambda);
        all += w;
        double d = x - delta;
        d -= 2.0 * kPi * std::floor((d + kPi) / (2.0 * kPi));
        if (std::abs(d) <= 0.5 * kPi) inside += w;
    }
    // The indicator makes the midpoint rule first order; refine the two edges with a fine local sum.
    const double h = 2.0 * kPi / n;
    double correction = 0.0;
    for (double edge : {delta - 0.5 * kPi, delta + 0.5 * kPi}) {
        const double cell0 = std::floor((edge + kPi) / h);
        const double a = -kPi + cell0 * h, b = a + h;
        const double mid = 0.5 * (a + b);
        double md = mid - delta;
        md -= 2.0 * kPi * std::floor((md + kPi) / (2.0 * kPi));
        const bool mid_inside = std::abs(md) <= 0.5 * kPi;
        constexpr int sub = 64;
        double exact = 0.0;
        for (int s = 0; s < sub; ++s) {
            const double x = a + (s + 0.5) * h / sub;
            double d = x - delta;
            d -= 2.0 * kPi * std::floor((d + kPi) / (2.0 * kPi));
            if (std::abs(d) <= 0.5 * kPi) exact += von_mises_weight(x, lambda) / sub;
        }
        correction += exact - (mid_inside ? von_mises_weight(mid, lambda) : 0.0);
    }
    return (inside + correction) / all;
}

std::array<double, 9> own_cluster_direct(double tau, double rho) {
    // O is even in Δ: o_0 = (1/π) ∫_0^π O dΔ, o_m = (2/π) ∫_0^π O cos mΔ dΔ, by the trapezoid rule on 4096 intervals
    // (cos mΔ by Chebyshev's recurrence). O is smooth but for the kink at Δ = π/2 when ρ = 1 (where the chord turns
    // from 0 to −2 cos Δ), a grid point: the rule stays second order there, its error far below the table's
    // interpolation (tests/shading/test_own_cluster.cpp).
    constexpr int n = 4096;
    std::array<double, 9> o{};
    for (int q = 0; q <= n; ++q) {
        const double d = kPi * q / n;
        const double c = std::cos(d);
        // The chord as the shaders compute it (float: its rounding, ~1e-7 of a radius, is far below the table's error).
        const double path = glsl::own_cluster_path(float(rho), float(c), float(std::sin(d)));
        const double w = (q == 0 || q == n ? 0.5 : 1.0) * std::exp(-tau * path);
        double prev = 1.0, cur = c;  // cos 0Δ, cos Δ
        o[0] += w;
        for (int m = 1; m < 9; ++m) {
            o[m] += w * cur;
            const double next = 2.0 * c * cur - prev;
            prev = cur;
            cur = next;
        }
    }
    o[0] /= n;
    for (int m = 1; m < 9; ++m) o[m] *= 2.0 / n;
    return o;
}

LutSet LightingTables::set() const {
    LutSet s;
    s.images[int(Lut::lut_ck_lo)] = &ck_lo;
    s.images[int(Lut::lut_ck_hi)] = &ck_hi;
    s.images[int(Lut::lut_h_tt)] = &h_tt;
    s.images[int(Lut::lut_h_trt)] = &h_trt;
    s.images[int(Lut::lut_half_mass)] = &half_mass;
    s.images[int(Lut::lut_fresnel_fit)] = &fresnel_fit;
    s.images[int(Lut::lut_own_cluster)] = &own_cluster;
    return s;
}

LutSet MultipleScatteringTables::set() const {
    LutSet s;
    s.images[int(Lut::lut_ms_ab)] = &ab;
    s.images[int(Lut::lut_ms_sat_delta)] = &sat_delta;
    s.images[int(Lut::lut_ms_sat_sigma)] = &sat_sigma;
    s.images[int(Lut::lut_ms_af)] = &af;
    return s;
}

LightingTables build_lighting_tables() {
    using namespace glsl;
    const auto start = std::chrono::steady_clock::now();
    LightingTables t;
    t.ck_lo = LutImage(LUT_N_PHI, LUT_N_LAMBDA);
    t.ck_hi = LutImage(LUT_N_PHI, LUT_N_LAMBDA);
    t.half_mass = LutImage(LUT_N_PHI, LUT_N_LAMBDA);
    parallel_rows(LUT_N_LAMBDA, [&](int y) {
        const double lambda = lut_point_log(y, LUT_LAMBDA_MIN, LUT_LAMBDA_MAX, LUT_N_LAMBDA);
        for (int x = 0; x < LUT_N_PHI; ++x) {
            const double dphi = lut_point_lin(x, 0.0f, COIF_PI, LUT_N_PHI);
            const auto c = ck_all(lambda, dphi);
            t.ck_lo.at(x, y) = glm::vec4(c[0], c[1], c[2], c[3]);
            t.ck_hi.at(x, y) = glm::vec4(c[4], c[5], c[6], 0.0);
            t.half_mass.at(x, y) = glm::vec4(float(half_mass_direct(lambda, dphi)), 0.0f, 0.0f, 0.0f);
        }
    });
    t.h_tt = LutImage(LUT_N_THETA_D, LUT_N_ETA);
    t.h_trt = LutImage(LUT_N_THETA_D, LUT_N_ETA);
    t.fresnel_fit = LutImage(2, LUT_N_ETA);
    parallel_rows(LUT_N_ETA, [&](int y) {
        const double eta = lut_point_log(y, LUT_ETA_MIN, LUT_ETA_MAX, LUT_N_ETA);
        for (int x = 0; x < LUT_N_THETA_D; ++x) {
            const double theta_d = lut_point_lin(x, 0.0f, COIF_HALF_PI, LUT_N_THETA_D);
            const auto tt = h_all(false, eta, theta_d);
            const auto trt = h_all(true, eta, theta_d);
            t.h_tt.at(x, y) = glm::vec4(tt[0], tt[1], tt[2], 0.0);
            t.h_trt.at(x, y) = glm::vec4(trt[0], trt[1], trt[2], 0.0);
        }
        const auto f = fresnel_fit_coefficients(eta);
        t.fresnel_fit.at(0, y) = glm::vec4(f[0], f[1], f[2], f[3]);
        t.fresnel_fit.at(1, y) = glm::vec4(f[4], f[5], 0.0, 0.0);
    });
    t.own_cluster = LutImage(OWN_N_TAU, 3 * OWN_N_RHO);
    parallel_rows(OWN_N_RHO, [&](int y) {
        for (int x = 0; x < OWN_N_TAU; ++x) {
            const auto o = own_cluster_direct(own_cluster_tau_at(x), own_cluster_rho_at(y));
            t.own_cluster.at(x, y) = glm::vec4(o[0], o[1], o[2], o[3]);
            t.own_cluster.at(x, y + OWN_N_RHO) = glm::vec4(o[4], o[5], o[6], o[7]);
            t.own_cluster.at(x, y + 2 * OWN_N_RHO) = glm::vec4(o[8], 0.0, 0.0, 0.0);
        }
    });
    t.build_seconds = seconds_since(start);
    return t;
}

namespace {

// The tables in their byte order (lighting_tables_bytes), for reading (T = const LightingTables) or filling.
template <class T>
auto images_of(T& t) {
    return std::array{&t.ck_lo, &t.ck_hi, &t.h_tt, &t.h_trt, &t.half_mass, &t.fresnel_fit, &t.own_cluster};
}

}  // namespace

std::vector<std::byte> lighting_tables_bytes(const LightingTables& tables) {
    std::vector<std::byte> out;
    for (const LutImage* image : images_of(tables)) {
        const std::uint32_t size[2] = {static_cast<std::uint32_t>(image->width), static_cast<std::uint32_t>(image->height)};
        const auto* s = reinterpret_cast<const std::byte*>(size);
        out.insert(out.end(), s, s + sizeof size);
        const auto* p = reinterpret_cast<const std::byte*>(image->texels.data());
        out.insert(out.end(), p, p + image->texels.size() * sizeof(glm::vec4));
    }
    return out;
}

LightingTables lighting_tables_from_bytes(std::span<const std::byte> bytes) {
    LightingTables t;
    std::size_t at = 0;
    for (LutImage* image : images_of(t)) {
        std::uint32_t size[2] = {};
        if (bytes.size() - at < sizeof size) throw Error::parameter("lighting tables", "truncated");
        std::memcpy(size, bytes.data() + at, sizeof size);
        at += sizeof size;
        if (size[0] > 4096 || size[1] > 4096) throw Error::parameter("lighting tables", "absurd table size");
        *image = LutImage(static_cast<int>(size[0]), static_cast<int>(size[1]));
        const std::size_t n = image->texels.size() * sizeof(glm::vec4);
        if (bytes.size() - at < n) throw Error::parameter("lighting tables", "truncated");
        std::memcpy(image->texels.data(), bytes.data() + at, n);
        at += n;
    }
    if (at != bytes.size()) throw Error::parameter("lighting tables", "unexpected bytes after the last table");
    return t;
}

const LightingTables& global_lighting_tables() {
    static const LightingTables tables = [] {
#ifndef COIF_LIGHTING_TABLES_GENERATOR
        if (const auto bytes = embedded::lighting_tables_data("lighting_tables.bin"))
            return lighting_tables_from_bytes(std::as_bytes(*bytes));
#endif
        return build_lighting_tables();
    }();
    return tables;
}

MultipleScatteringTables build_ms_tables(const glsl::HairParams& params, const glsl::LightingConfig& config) {
    using namespace glsl;
    LutBinding bind(global_lighting_tables().set());
    const auto start = std::chrono::steady_clock::now();  // after the (one-time) global tables
    vec4 f0123, f45;
    srbf_point_setup(params, config, f0123, f45);
    MultipleScatteringTables t;
    t.ab = LutImage(LUT_N_MS, LUT_N_MS_SIGMA);
    t.sat_delta = LutImage(LUT_N_MS, LUT_N_MS_SIGMA);
    t.sat_sigma = LutImage(LUT_N_MS, LUT_N_MS_SIGMA);
    t.af = LutImage(LUT_N_MS, LUT_N_MS_SIGMA);
    const double h = double(COIF_PI) / (LUT_N_MS - 1);
    // Every term is channel-wise, so one call computes three σa levels at once (one per channel).
    for (int l0 = 0; l0 < LUT_N_MS_SIGMA; l0 += 3) {
        HairParams p = params;
        for (int c = 0; c < 3; ++c) p.sigma_a[c] = ms_sigma_level(std::min(l0 + c, LUT_N_MS_SIGMA - 1));
        std::vector<glm::dvec3> delta(LUT_N_MS), sigma(LUT_N_MS);
        std::vector<glm::vec3> ab(LUT_N_MS), af(LUT_N_MS), bf(LUT_N_MS);
        for (int i = 0; i < LUT_N_MS; ++i) {
            const float x = lut_point_lin(i, -COIF_HALF_PI, COIF_HALF_PI, LUT_N_MS);
            vec3 A_b, Delta_b, sigma_b, a_f, beta_f2;
            zinke_terms(p, config, f0123, f45, x, A_b, Delta_b, sigma_b);
            zinke_forward(p, config, f0123, f45, x, a_f, beta_f2);
            ab[i] = A_b;
            af[i] = a_f;
            bf[i] = beta_f2;
            delta[i] = glm::dvec3(Delta_b);
            sigma[i] = glm::dvec3(sigma_b);
        }
        // 1D summed-area tables (000 eq. 31): running trapezoid integrals from θd = -π/2 at the nodes.
        glm::dvec3 sd(0.0), ss(0.0);
        for (int i = 0; i < LUT_N_MS; ++i) {
            if (i > 0) {
                sd += 0.5 * h * (delta[i - 1] + delta[i]);
                ss += 0.5 * h * (sigma[i - 1] + sigma[i]);
            }
            for (int c = 0; c < 3 && l0 + c < LUT_N_MS_SIGMA; ++c) {
                const int row = l0 + c;
                t.ab.at(i, row) = glm::vec4(ab[i][c], 0.0f, 0.0f, 0.0f);
                t.sat_delta.at(i, row) = glm::vec4(static_cast<float>(sd[c]), 0.0f, 0.0f, 0.0f);
                t.sat_sigma.at(i, row) = glm::vec4(static_cast<float>(ss[c]), 0.0f, 0.0f, 0.0f);
                t.af.at(i, row) = glm::vec4(af[i][c], bf[i][c], 0.0f, 0.0f);
            }
        }
    }
    t.build_seconds = seconds_since(start);
    return t;
}

}  // namespace coif::shading
