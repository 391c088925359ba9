// Single scattering of one SRBF light in closed form (000 §4.2): the 1D circular-Gaussian form of
// the Marschner model integrated against G(ωi; ωj, λj). Everything here runs per shading point and
// per light; GLSL compiled also as C++ (the CPU evaluator, tests, tools).
//
//   𝓜_t(ωj, λj) = ∫ G_j(ωi) S_t(ωi, ωo) cos θi dωi                                    (000 eq. 11)
//              ≈ ∫ g_j(θi) M_t(θh) cos²θi / cos²θd · 𝓝_t(λ'_j, φo-φj, θd) dθi
//   𝓝_t(λ', Δ, θd) = ∫ g^c(x; 0, λ') N_t(θd, Δ - x) dx,  λ' = λj / sqrt(cos θi cos θj)  (eq. 12)
//
// N_R is a polynomial in |cos(φ/2)| (eq. 13, tables 𝒞_k), N_TT one circular Gaussian (eq. 16-19),
// N_TRT three or one (eq. 20-23, §4.2.4), with η̄* for eccentricity (eq. 25-26); products of circular
// Gaussians integrate in closed form; the outer θi integral is the linear quadrature of §4.2.2.
//
// Where this code departs from the paper it says so and why (each departure can be switched back
// with LightingConfig so that `coif lighting check` measures what it buys):
//   - paper_schlick: N_R with Schlick's Fresnel (000) or with an exact-Fresnel polynomial fit
//     (default; same 𝒞_k tables, two extra fetches per shading point).
//   - paper_norm: ∫g^c ≈ √πλ (000) or the exact 2π e^{-κ}I0(κ) (default).
//   - paper_theta_gauss: g^c_j(θi) ≈ g_j(θi) (000 eq. 11) or that plus the smooth correction
//     g^c_j/g_j folded into the linear quadrature's samples (default; matters for broad lights).
#ifndef COIF_SHADERS_LIGHTING_SRBF_SINGLE_GLSL
#define COIF_SHADERS_LIGHTING_SRBF_SINGLE_GLSL

#include "shaders/lighting/common.glsl"
#include "shaders/lighting/marschner.glsl"
#include "shaders/lighting/luts.glsl"

struct LightingConfig {
    int segments;            // m of the linear quadrature (000 §4.2.2), 2..256; 000 uses 4
    bool paper_schlick;
    bool paper_norm;         // also selects the Taylor series of T, T² (eq. 18, 22) over our interpolation
    bool paper_theta_gauss;
    bool paper_tt;           // 𝓝_TT from the single circular Gaussian alone (000) for every λ'
};

const int LIGHTING_MAX_SEGMENTS = 256;

// Longitudinal angle θ and azimuth φ of a unit direction in the hair frame (u tangent, v, w).
COIF_FN void hair_angles(vec3 dir, vec3 u, vec3 v, vec3 w, OUT(float) theta, OUT(float) phi) {
    theta = safe_asin(dot(dir, u));
    float x = dot(dir, v);
    float y = dot(dir, w);
    phi = (abs(x) + abs(y) > 1e-12) ? atan(y, x) : 0.0;
}

// ---- N_R (000 §4.2.1) --------------------------------------------------------------------------

// Coefficients C_k(θd, η), k = 0..6, of N_R = Σ C_k |cos(φ/2)|^k (000 eq. 13), with c = |cos(φ/2)|,
// u = cos θd and the cosine of incidence μ = u c:
//   Schlick: N_R = c/4 (F0 + (1-F0)(1-uc)^5)  →  C_1 = 1/4, C_{n+1} = (1-F0) C(5,n) (-u)^n / 4;
//   fitted:  N_R = c/4 Σ f_n (uc)^n           →  C_{n+1} = f_n u^n / 4.
COIF_FN void N_R_coefficients(float eta, float theta_d, bool schlick, vec4 f0123, vec4 f45,
                              OUT(vec4) c_lo, OUT(vec4) c_hi) {
    float u = cos(theta_d);
    float u2 = u * u;
    float u3 = u2 * u;
    float u4 = u2 * u2;
    float u5 = u4 * u;
    if (schlick) {
        float w = 1.0 - fresnel_schlick_f0(eta);
        c_lo = 0.25 * vec4(0.0, 1.0, -5.0 * w * u, 10.0 * w * u2);
        c_hi = 0.25 * vec4(-10.0 * w * u3, 5.0 * w * u4, -w * u5, 0.0);
    } else {
        c_lo = 0.25 * vec4(0.0, f0123.x, f0123.y * u, f0123.z * u2);
        c_hi = 0.25 * vec4(f0123.w * u3, f45.x * u4, f45.y * u5, 0.0);
    }
}

// N_R at one azimuth from its polynomial (for plots and tests).
COIF_FN float N_R_poly_value(vec4 c_lo, vec4 c_hi, float phi) {
    float c = abs(cos(0.5 * phi));
    float c2 = c * c;
    vec4 p_lo = vec4(1.0, c, c2, c2 * c);
    vec4 p_hi = vec4(c2 * c2, c2 * c2 * c, c2 * c2 * c2, 0.0);
    return max(dot(c_lo, p_lo) + dot(c_hi, p_hi), 0.0);
}

// 𝓝_R(λ', Δ, θd) = Σ_k C_k 𝒞_k(λ', Δ) (000 eq. 14); the table stores 𝒞_k / ∫g^c(λ').
COIF_FN float N_R_inner(vec4 c_lo, vec4 c_hi, float lambda_p, float dphi) {
    vec4 t_lo;
    vec4 t_hi;
    fetch_Ck(lambda_p, dphi, t_lo, t_hi);
    // The fitted polynomial may dip a hair below 0 where F ~ 0 (η -> 1): N_R is never negative.
    return circ_integral(lambda_p, false) * max(dot(c_lo, t_lo) + dot(c_hi, t_hi), 0.0);
}

// ---- Taylor expansions of T and T² (000 eq. 18, 22) ------------------------------------------------
// T(h) = exp(-2σ' sqrt(1 - h²/η'²)); with s = h²/η'², sqrt(1-s) = 1 - s/2 - s²/8 + O(s³), so
// T ≈ e^{-2σ'} (1 + σ' s + (σ'²/2 + σ'/4) s²) and T² the same with σ' → 2σ'.
// Returns per channel the coefficients (a_0, a_2, a_4) of h^0, h^2, h^4 through three vec3.
COIF_FN void taylor_T(vec3 sigma_ap, float eta_p, OUT(vec3) a0, OUT(vec3) a2, OUT(vec3) a4) {
    float q = 1.0 / (eta_p * eta_p);
    a0 = exp(-2.0 * sigma_ap);
    a2 = a0 * sigma_ap * q;
    a4 = a0 * (0.5 * sigma_ap * sigma_ap + 0.25 * sigma_ap) * (q * q);
}
COIF_FN void taylor_T2(vec3 sigma_ap, float eta_p, OUT(vec3) c0, OUT(vec3) c2, OUT(vec3) c4) {
    taylor_T(2.0 * sigma_ap, eta_p, c0, c2, c4);
}

// Ours: the quadratic in h² through the exact T at h² = 0, 1/2, 1. Same cost class (two more exp)
// but exact at the rim, where the Taylor series of eq. 18 loses up to 30 % of TRT's energy under
// strong absorption (4σ' sqrt(1-h²/η'²) is far from its expansion point); `coif lighting check`
// prints both.
COIF_FN void interp_T(vec3 sigma_ap, float eta_p, OUT(vec3) a0, OUT(vec3) a2, OUT(vec3) a4) {
    float q = 1.0 / (eta_p * eta_p);
    vec3 y0 = exp(-2.0 * sigma_ap);
    vec3 y1 = exp(-2.0 * sigma_ap * sqrt(1.0 - 0.5 * q));
    vec3 y2 = exp(-2.0 * sigma_ap * sqrt(max(1.0 - q, 0.0)));
    a0 = y0;
    a2 = -3.0 * y0 + 4.0 * y1 - y2;
    a4 = 2.0 * y0 - 4.0 * y1 + 2.0 * y2;
}

// T's coefficients (a_0, a_2, a_4): the Taylor series of 000 or our interpolation.
COIF_FN void T_coefficients(vec3 sigma_ap, float eta_p, bool paper, OUT(vec3) a0, OUT(vec3) a2, OUT(vec3) a4) {
    if (paper) taylor_T(sigma_ap, eta_p, a0, a2, a4);
    else interp_T(sigma_ap, eta_p, a0, a2, a4);
}

// ---- N_TT as one circular Gaussian (000 eq. 15-19) --------------------------------------------------

// N_TT ≈ b g^c(φ; π, λ) per channel. b = N_TT(π): the only root of φ(1,h) = π is h = 0, where
// |dφ/dh| = 2 - 2/η', so b = (1-F(θd,0))² e^{-2σ'} / (4 (1 - 1/η')). λ keeps the energy
// E = ∫N_TT dφ = ½ Σ_k a_k H_k^TT (eq. 17, 19).
COIF_FN void N_TT_fit(float eta, vec3 sigma_a, float theta_d, bool paper_norm, OUT(vec3) b, OUT(vec3) lambda) {
    float eta_p = eta_prime(eta, theta_d);
    vec3 sp = sigma_a_prime(sigma_a, eta, theta_d);
    float f0 = fresnel_dielectric(eta, cos(theta_d));
    vec3 a0;
    vec3 a2;
    vec3 a4;
    T_coefficients(sp, eta_p, paper_norm, a0, a2, a4);
    b = (1.0 - f0) * (1.0 - f0) * a0 / (4.0 * max(1.0 - 1.0 / eta_p, 1e-4));
    vec3 H = fetch_H_TT(eta, theta_d);
    vec3 energy = 0.5 * (a0 * H.x + a2 * H.y + a4 * H.z);
    for (int c = 0; c < 3; ++c) {
        lambda[c] = circ_fit_width(energy[c], b[c], paper_norm);
        if (lambda[c] > 100.0) b[c] = circ_fit_peak(energy[c], lambda[c], paper_norm);
        if (!(energy[c] > 0.0)) b[c] = 0.0;
    }
}

// ---- N_TT at one azimuth, and the hybrid inner integral (ours) -----------------------------------
// One circular Gaussian cannot follow N_TT's shape (flat top, compact support |φ-π| <= π - 2 asin(1/η'),
// a dip at π under strong absorption): pointwise it is off by 5-19 % (`coif lighting check`), and a
// sharp light sees N_TT pointwise; its tails also overshoot where the exact N_TT is already zero. For
// λ' <= 1.0 we therefore integrate the exact N_TT against the light's azimuthal kernel with 6-point
// Gauss-Hermite (N_TT evaluated by inverting φ(h): no table, ~10 Newton steps per node); above 1.3
// the kernel is nearly flat over N_TT's support, the Gaussian of 000 eq. 16 is accurate and used;
// in between the two are blended. (Thresholds measured: TT error 10 % -> 1.2 % of TT's energy.)

// The offset h with φ(1, h) - π = d for |d| < π - 2 asin(1/η') (TT's φ decreases monotonically in h),
// solved for a = asin h: φ(1, sin a) - π = 2 asin(sin a / η') - 2a is smooth on [-π/2, π/2], where in h
// the slope is infinite at |h| = 1. TT_INVERT_STEPS Newton steps from the chord a = -(π/2) d / reach,
// safeguarded by bisection. The error in h after 5 steps (measured in double precision over the whole
// support): 8e-16 at η' = 1.2, 6e-5 at η' = 1.05 (η' ≥ η always; hair's η is 1.55). A fixed count, not a
// test of convergence: a data-dependent exit made llvmpipe's lighting pass 1.6x slower. (Until now: 10
// Newton steps in h from the line through the slope at 0.)
const int TT_INVERT_STEPS = 5;
COIF_FN float tt_invert(float d, float eta_p) {
    float reach = COIF_PI - 2.0 * safe_asin(1.0 / eta_p);
    float lo = -COIF_HALF_PI;
    float hi = COIF_HALF_PI;
    float a = clamp(-COIF_HALF_PI * d / max(reach, 1e-6), -COIF_HALF_PI, COIF_HALF_PI);
    for (int it = 0; it < TT_INVERT_STEPS; ++it) {
        float s = sin(a);
        float f = 2.0 * safe_asin(s / eta_p) - 2.0 * a - d;   // decreasing in a
        if (f > 0.0) lo = a; else hi = a;
        float df = 2.0 * cos(a) / sqrt(max(eta_p * eta_p - s * s, 1e-12)) - 2.0;   // <= 2/η' - 2 < 0
        float an = a - f / min(df, -1e-6);
        a = (an >= lo && an <= hi) ? an : 0.5 * (lo + hi);
    }
    return sin(a);
}

// N_TT(θd, ψ) exactly: ½ A_TT(h) / |dφ/dh| at the single root h of φ(1,h) = ψ (000 eq. 9, 15).
COIF_FN vec3 N_TT_pointwise(float eta, vec3 sigma_a, float theta_d, float psi) {
    float eta_p = eta_prime(eta, theta_d);
    float d = wrap_pi(psi - COIF_PI);
    float reach = COIF_PI - 2.0 * safe_asin(1.0 / eta_p);
    if (abs(d) >= reach) return vec3(0.0);
    float h = tt_invert(d, eta_p);
    float df = 2.0 - 2.0 * sqrt(max(1.0 - h * h, 1e-12)) / sqrt(eta_p * eta_p - h * h);
    // |dφ/dh| = 2/sqrt(1-h²) - 2/sqrt(η'²-h²); dividing by it as (…)·sqrt(1-h²) keeps h → ±1 finite.
    vec3 a = attenuation_A(LOBE_TT, eta, sigma_a, theta_d, h);
    return 0.5 * a * sqrt(max(1.0 - h * h, 0.0)) / max(df, 1e-6);
}

// ∫ N_TT(θd, ψ) dψ over ψ - π ∈ [d0, d1] (|d| < π - 2 asin(1/η')): in h it is ½ ∫ A_TT dh between the
// inverted end points, by 4-point Gauss-Legendre.
COIF_FN vec3 N_TT_interval(float eta, vec3 sigma_a, float theta_d, float d0, float d1) {
    float eta_p = eta_prime(eta, theta_d);
    float ha = tt_invert(d1, eta_p);
    float hb = tt_invert(d0, eta_p);
    float mid = 0.5 * (ha + hb);
    float half_w = 0.5 * (hb - ha);
    vec3 acc = vec3(0.0);
    for (int i = 0; i < 2; ++i) {
        float t = i == 0 ? 0.339981043584856 : 0.861136311594053;
        float w = i == 0 ? 0.652145154862546 : 0.347854845137454;
        acc += w * (attenuation_A(LOBE_TT, eta, sigma_a, theta_d, mid - half_w * t) +
                    attenuation_A(LOBE_TT, eta, sigma_a, theta_d, mid + half_w * t));
    }
    return 0.5 * half_w * acc;
}

const float TT_HYBRID_LO = 1.0;
const float TT_HYBRID_HI = 1.3;

// ∫ g^c(x; 0, λ') N_TT(Δ - x) dx by 6-point Gauss-Hermite in x = λ' t (nodes ±t_i, weights w_i),
// with the ratio g^c/g folded into the weights.
COIF_FN vec3 N_TT_inner_pointwise(float eta, vec3 sigma_a, float theta_d, float lambda_p, float dphi) {
    vec3 acc = vec3(0.0);
    for (int i = 0; i < 3; ++i) {
        float t = i == 0 ? 0.436077411927617 : (i == 1 ? 1.335849074013697 : 2.350604973674492);
        float w = i == 0 ? 0.724629595224392 : (i == 1 ? 0.157067320322856 : 0.00453000990550885);
        float x = lambda_p * t;
        float ratio = w * exp(t * t) * circ_gauss(x, 0.0, lambda_p);
        acc += ratio * (N_TT_pointwise(eta, sigma_a, theta_d, dphi - x) + N_TT_pointwise(eta, sigma_a, theta_d, dphi + x));
    }
    return lambda_p * acc;
}

// ---- N_TRT as three or one circular Gaussians (000 eq. 20-23, §4.2.4) -------------------------------

struct TrtFit {
    vec3 b1;          // peaks of the two caustic lobes at ±φ* (η' < 2)
    vec3 b2;          // peak of the residue lobe at 0, width φ* (η' < 2)
    float phi_star;   // caustic azimuth φ*
    float w1;         // caustic width (w_c)
    vec3 b3;          // peak of the single lobe at 0 (η' >= 2)
    vec3 lambda3;     // its width λ3' (blended from w_c to λ3 over [2, 2+Δη'])
    bool three;       // η' < 2
};

COIF_FN TrtFit N_TRT_fit(float eta, vec3 sigma_a, float theta_d, float w_c, float delta_eta_p, bool paper_norm) {
    float eta_p = eta_prime(eta, theta_d);
    vec3 sp = sigma_a_prime(sigma_a, eta, theta_d);
    float f0 = fresnel_dielectric(eta, cos(theta_d));
    vec3 c0;
    vec3 c2;
    vec3 c4;
    T_coefficients(2.0 * sp, eta_p, paper_norm, c0, c2, c4);   // T² = T with 2σ'
    vec3 H = fetch_H_TRT(eta, theta_d);
    vec3 energy = max(0.5 * (c0 * H.x + c2 * H.y + c4 * H.z), vec3(0.0));   // eq. 23
    // N_TRT(0) from the root h = 0, |dφ/dh| = |4/η' - 2| (the grazing roots near |h| = 1 carry
    // (1-F)² ≈ 0 and are left out, as in 000).
    vec3 n0 = (1.0 - f0) * (1.0 - f0) * f0 * c0 / (2.0 * max(abs(4.0 / eta_p - 2.0), 1e-3));
    TrtFit fit;
    fit.w1 = w_c;
    fit.b1 = vec3(0.0);
    fit.b2 = vec3(0.0);
    fit.b3 = vec3(0.0);
    fit.lambda3 = vec3(w_c);
    fit.phi_star = 0.0;
    fit.three = eta_p < 2.0;
    if (fit.three) {
        float h_c = sqrt((4.0 - eta_p * eta_p) / 3.0);
        fit.phi_star = max(abs(wrap_pi(phi_of_h(2, h_c, eta_p))), 1e-3);
        float g0 = circ_gauss(0.0, fit.phi_star, w_c);
        fit.b2 = n0 * (1.0 - g0) * (1.0 - g0);                                  // eq. 21
        fit.b1 = max(energy - fit.b2 * circ_integral(fit.phi_star, paper_norm), vec3(0.0)) /
                 (2.0 * circ_integral(w_c, paper_norm));                        // energy-preserving b1
    } else {
        float s = smoothstep(2.0, 2.0 + delta_eta_p, eta_p);
        for (int c = 0; c < 3; ++c) {
            float lambda3 = circ_fit_width(energy[c], n0[c], paper_norm);
            fit.lambda3[c] = mix(w_c, min(lambda3, 1e3), s);
            fit.b3[c] = circ_fit_peak(energy[c], fit.lambda3[c], paper_norm);  // keeps the energy
        }
    }
    return fit;
}

COIF_FN vec3 N_TRT_fit_value(TrtFit fit, float phi) {
    if (fit.three)
        return fit.b1 * (circ_gauss(phi, fit.phi_star, fit.w1) + circ_gauss(phi, -fit.phi_star, fit.w1)) +
               fit.b2 * circ_gauss(phi, 0.0, fit.phi_star);
    vec3 r = vec3(0.0);
    for (int c = 0; c < 3; ++c) r[c] = fit.b3[c] * circ_gauss(phi, 0.0, fit.lambda3[c]);
    return r;
}

// ∫ g^c(x; 0, λ') N_TRT(Δ - x) dx for the fitted N_TRT (eq. 12 with products of circular Gaussians).
COIF_FN vec3 N_TRT_inner(TrtFit fit, float lambda_p, float dphi, bool paper_norm) {
    if (fit.three)
        return fit.b1 * (circ_product_integral(lambda_p, fit.w1, dphi - fit.phi_star, paper_norm) +
                         circ_product_integral(lambda_p, fit.w1, dphi + fit.phi_star, paper_norm)) +
               fit.b2 * circ_product_integral(lambda_p, fit.phi_star, dphi, paper_norm);
    vec3 r = vec3(0.0);
    for (int c = 0; c < 3; ++c)
        r[c] = fit.b3[c] * circ_product_integral(lambda_p, fit.lambda3[c], dphi, paper_norm);
    return r;
}

// η̄* (000 eq. 26): η* is linear in cos 2φh = cos(φi + φo) with φi = φj + x, x ~ g^c(x; 0, λ'), and
// the g^c-weighted mean of cos(φj + φo + x) is cos(φj + φo) I1(κ)/I0(κ), κ = 2/λ'². (000 reads the
// same mean from the 𝒞_0, 𝒞_2 tables; the Bessel ratio needs no fetch.)
COIF_FN float eta_star_mean(float eta, float ecc_a, float lambda_p, float cos_sum_phi) {
    float k = circ_kappa(lambda_p);
    return eta_star(eta, ecc_a, cos_sum_phi * bessel_i1e(k) / bessel_i0e(k));
}

// ---- per-lobe inner integral and the outer linear quadrature ------------------------------------

// Fresnel-fit coefficients of the shading point (zero when Schlick is used: no fetch).
COIF_FN void srbf_point_setup(HairParams hp, LightingConfig cfg, OUT(vec4) f0123, OUT(vec4) f45) {
    f0123 = vec4(0.0);
    f45 = vec4(0.0);
    if (!cfg.paper_schlick) fetch_fresnel_fit(hp.eta, f0123, f45);
}

// 𝓝_t(λ', Δ, θd) (000 eq. 12) for one lobe.
COIF_FN vec3 srbf_N_inner(int lobe, HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float theta_d,
                          float lambda_p, float dphi, float cos_sum_phi) {
    if (lobe == LOBE_R) {
        vec4 c_lo;
        vec4 c_hi;
        N_R_coefficients(hp.eta, theta_d, cfg.paper_schlick, f0123, f45, c_lo, c_hi);
        return vec3(N_R_inner(c_lo, c_hi, lambda_p, dphi));
    }
    if (lobe == LOBE_TT) {
        float blend = cfg.paper_tt ? 1.0 : smoothstep(TT_HYBRID_LO, TT_HYBRID_HI, lambda_p);
        vec3 r = vec3(0.0);
        if (blend > 0.0) {
            vec3 b;
            vec3 lam;
            N_TT_fit(hp.eta, hp.sigma_a, theta_d, cfg.paper_norm, b, lam);
            for (int c = 0; c < 3; ++c) r[c] = b[c] * circ_product_integral(lambda_p, lam[c], dphi - COIF_PI, cfg.paper_norm);
        }
        if (blend < 1.0)
            r = mix(N_TT_inner_pointwise(hp.eta, hp.sigma_a, theta_d, lambda_p, dphi), r, blend);
        return r;
    }
    float eta_e = hp.eta;
    if (hp.ecc_a != 1.0) eta_e = eta_star_mean(hp.eta, hp.ecc_a, lambda_p, cos_sum_phi);
    TrtFit fit = N_TRT_fit(eta_e, hp.sigma_a, theta_d, hp.w_c, hp.delta_eta_p, cfg.paper_norm);
    return N_TRT_inner(fit, lambda_p, dphi, cfg.paper_norm);
}

// λ' = λj / sqrt(cos θi cos θj), kept inside the tables' range (at λ' = 10 g^c is within 4 % of flat).
COIF_FN float effective_lambda(float lambda_j, float cos_i, float cos_j) {
    return clamp(lambda_j / sqrt(max(cos_i * cos_j, 1e-12)), LUT_LAMBDA_MIN, LUT_LAMBDA_MAX);
}

// The smooth factor of 000 eq. 11 at θi = x: cos²θi / cos²θd · 𝓝_t, times g^c_j/g_j unless the
// paper's Gaussian stand-in is asked for. 0 at the end points θi = ±π/2 (cos θi = 0).
COIF_FN vec3 srbf_single_integrand(int lobe, HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float x,
                                   float theta_o, float theta_j, float lambda_j, float dphi, float cos_sum_phi) {
    float ci = cos(x);
    if (ci <= 1e-6) return vec3(0.0);
    float theta_d = 0.5 * (theta_o - x);
    float cd = cos(theta_d);
    float lambda_p = effective_lambda(lambda_j, ci, cos(theta_j));
    vec3 n = srbf_N_inner(lobe, hp, cfg, f0123, f45, theta_d, lambda_p, dphi, cos_sum_phi);
    float weight = ci * ci / max(cd * cd, 1e-8);
    if (!cfg.paper_theta_gauss) {
        float d = x - theta_j;
        float s = sin(0.5 * d);
        weight *= exp(min((d * d - 4.0 * s * s) / (lambda_j * lambda_j), 30.0));
    }
    return n * weight;
}

// Sample m+1 abscissae of the linear quadrature for a Gaussian (μ, λ) on [-π/2, π/2]: the end points
// and m-1 points spread evenly over [μ - (m-2)λ/2, μ + (m-2)λ/2] clipped to the range (000 §4.2.2;
// clipping keeps large m meaningful, e.g. the m = 200 reference of 000 Fig. 5).
COIF_FN float quadrature_abscissa(int s, int m, float mu, float lambda) {
    if (s <= 0) return -COIF_HALF_PI;
    if (s >= m) return COIF_HALF_PI;
    float half_span = 0.5 * float(m - 2) * lambda;
    float lo = clamp(mu - half_span, -COIF_HALF_PI, COIF_HALF_PI);
    float hi = clamp(mu + half_span, -COIF_HALF_PI, COIF_HALF_PI);
    if (m == 2) return lo;
    return mix(lo, hi, float(s - 1) / float(m - 2));
}

// 𝓜_t(ωj, λj) of one lobe (000 eq. 11).
COIF_FN vec3 srbf_single_lobe(int lobe, HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float theta_o,
                              float phi_o, float theta_j, float phi_j, float lambda_j) {
    float alpha = lobe_alpha(hp, lobe);
    float beta = lobe_beta(hp, lobe);
    // g(θi; θj, λj) · M_t(θh), M_t(θh) = 2 g^u(θi; 2α - θo, 2β) = g(θi; 2α - θo, 2β) / (√π β) (eq. 7).
    GaussProduct gp = gauss_product(theta_j, lambda_j, 2.0 * alpha - theta_o, 2.0 * beta);
    float scale = gp.c / (COIF_SQRT_PI * beta) * M_norm(hp, lobe, theta_o);
    float dphi = wrap_pi(phi_o - phi_j);
    float cos_sum_phi = cos(phi_j + phi_o);
    int m = clamp(cfg.segments, 2, LIGHTING_MAX_SEGMENTS);
    float x_prev = -COIF_HALF_PI;
    vec3 f_prev = vec3(0.0);
    vec3 acc = vec3(0.0);
    for (int s = 1; s <= m; ++s) {
        float x = quadrature_abscissa(s, m, gp.mu, gp.lambda);
        vec3 f = vec3(0.0);
        if (s < m) f = srbf_single_integrand(lobe, hp, cfg, f0123, f45, x, theta_o, theta_j, lambda_j, dphi, cos_sum_phi);
        acc += gauss_linear_segment(x_prev, x, f_prev, f, gp.mu, gp.lambda);
        x_prev = x;
        f_prev = f;
    }
    // Non-negative samples integrate to >= 0; the max removes float round-off of the erf differences.
    return scale * max(acc, vec3(0.0));
}

// 𝓜 = Σ_t 𝓜_t for one SRBF light (ωj = (θj, φj) in the hair frame, bandwidth λj).
COIF_FN vec3 srbf_single(HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float theta_o, float phi_o,
                         float theta_j, float phi_j, float lambda_j) {
    return srbf_single_lobe(LOBE_R, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_j) +
           srbf_single_lobe(LOBE_TT, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_j) +
           srbf_single_lobe(LOBE_TRT, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_j);
}

#endif
