// Multiple scattering of one SRBF light in closed form (000 §4.3): dual scattering (Zinke et al.
// 2008) with the circular-Gaussian N_t of srbf_single.glsl. GLSL compiled also as C++.
//
//   L^D = D Σ_j L_j T_f,j (𝓜^G_j + d_b 𝓜^L_j)                                     (000 eq. 3-4)
//   𝓜^G = Σ_t ∫ ψ_f S_t cos θi dωi,    𝓜^L = ∫ ψ_f S_back cos θi dωi              (eq. 27, 29)
//   ψ_f = s̃_f(φj, φi) g^u(θi; θj, λ_f) / cos θi,  s̃_f = 1/π on the half circle |φi - φj| < π/2
//
// Inputs the renderer supplies per light (Ren et al. 2010 / Zinke 2008 shadow sampling): T_f (it
// only scales the result, so it is applied by the caller) and σ̄_f², the *variance* (rad²) of the
// longitudinal spread accumulated along the shadow path. The spread's bandwidth (000's σ_f, our λ_f)
// is λ_f = sqrt(λj² + 2 σ̄_f²) since a bandwidth λ has variance λ²/2.
//
// Departures from 000, each for a stated reason:
//   - ψ_f divides by cos θi inside the integral (Zinke's normalised spread); 000 eq. 27 moves it out
//     as 1/cos θj, which diverges for a light along the fibre.
//   - Zinke's backward lobe is a normalised Gaussian in θh with mean Δ̄_b and *standard deviation*
//     σ̄_b (the shifts ᾱ and variances β̄² it is built from live in θh); 000 eq. 29 writes it in
//     θi + θo. In θi it is 2 g^u(θi; 2Δ̄_b - θo, 2√2 σ̄_b), which, like 000's M_t, integrates to ~2 over θi;
//     with the energy-conserving convention (HairParams::longitudinal = 0, marschner.glsl M_norm) it is
//     divided by that integral for the given θo, so that the local lobe carries Ā_b and no more.
//   - The variances β̄_f², β̄_b² average the lobes' variances β_t²/2 (our β is a bandwidth).
//   - Eccentricity is not applied to multiple scattering (its η* depends on φi, which dual
//     scattering averages out); the 1D tables use η.
#ifndef COIF_SHADERS_LIGHTING_SRBF_MULTIPLE_GLSL
#define COIF_SHADERS_LIGHTING_SRBF_MULTIPLE_GLSL

#include "shaders/lighting/srbf_single.glsl"

const float MS_DEFAULT_D_B = 0.7;   // 000 §3: d_b between 0.6 and 0.8
const int ZINKE_SEGMENTS = 8;       // linear-quadrature segments of the 1D tables (built once per edit)
const int ZINKE_PHI_STEPS = 96;     // midpoint steps of the azimuthal moments ∫ w(φ) N_t(φ) dφ

// J_k(v) = ∫_0^v cos^k t dt, k = 0..6 (recursion J_k = cos^{k-1}v sin v / k + (k-1)/k J_{k-2}).
COIF_FN void cos_power_integrals(float v, OUT(vec4) j_lo, OUT(vec4) j_hi) {
    float s = sin(v);
    float c = cos(v);
    float j0 = v;
    float j1 = s;
    float j2 = c * s / 2.0 + j0 / 2.0;
    float j3 = c * c * s / 3.0 + 2.0 * j1 / 3.0;
    float j4 = c * c * c * s / 4.0 + 3.0 * j2 / 4.0;
    float j5 = c * c * c * c * s / 5.0 + 4.0 * j3 / 5.0;
    float j6 = c * c * c * c * c * s / 6.0 + 5.0 * j4 / 6.0;
    j_lo = vec4(j0, j1, j2, j3);
    j_hi = vec4(j4, j5, j6, 0.0);
}

// ∫_0^y |cos(t/2)|^k dt for any y: whole periods (each 4 J_k(π/2), Wallis' integrals) plus the rest.
COIF_FN void cos_half_power_cumulative(float y, OUT(vec4) w_lo, OUT(vec4) w_hi) {
    float n = floor((y + COIF_PI) / COIF_TWO_PI);
    float r = y - COIF_TWO_PI * n;
    vec4 j_lo;
    vec4 j_hi;
    cos_power_integrals(0.5 * r, j_lo, j_hi);
    vec4 period_lo = 4.0 * vec4(COIF_HALF_PI, 1.0, COIF_PI / 4.0, 2.0 / 3.0);
    vec4 period_hi = 4.0 * vec4(3.0 * COIF_PI / 16.0, 8.0 / 15.0, 5.0 * COIF_PI / 32.0, 0.0);
    w_lo = n * period_lo + 2.0 * j_lo;
    w_hi = n * period_hi + 2.0 * j_hi;
}

// 𝓝^G_t(Δ, θd) = (1/π) ∫_{Δ-π/2}^{Δ+π/2} N_t(θd, ψ) dψ (000 eq. 28), closed form for N_R and
// one half-mass fetch per circular Gaussian for N_TT, N_TRT.
COIF_FN vec3 srbf_N_global(int lobe, HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float theta_d, float dphi) {
    if (lobe == LOBE_R) {
        vec4 c_lo;
        vec4 c_hi;
        N_R_coefficients(hp.eta, theta_d, cfg.paper_schlick, f0123, f45, c_lo, c_hi);
        vec4 a_lo;
        vec4 a_hi;
        vec4 b_lo;
        vec4 b_hi;
        cos_half_power_cumulative(dphi - COIF_HALF_PI, a_lo, a_hi);
        cos_half_power_cumulative(dphi + COIF_HALF_PI, b_lo, b_hi);
        return vec3(max(dot(c_lo, b_lo - a_lo) + dot(c_hi, b_hi - a_hi), 0.0) * COIF_INV_PI);
    }
    vec3 r = vec3(0.0);
    if (lobe == LOBE_TT && !cfg.paper_tt) {
        // Ours: the exact N_TT over the half circle, i.e. ½ ∫ A_TT dh between the inverted window edges
        // (the window [Δ-π/2, Δ+π/2] against N_TT's support |φ-π| < reach, in up to two pieces).
        float eta_p = eta_prime(hp.eta, theta_d);
        float reach = COIF_PI - 2.0 * safe_asin(1.0 / eta_p);
        float dc = wrap_pi(dphi - COIF_PI);
        for (int k = -1; k <= 1; ++k) {
            float lo = max(dc + float(k) * COIF_TWO_PI - COIF_HALF_PI, -reach);
            float hi = min(dc + float(k) * COIF_TWO_PI + COIF_HALF_PI, reach);
            if (hi > lo) r += N_TT_interval(hp.eta, hp.sigma_a, theta_d, lo, hi);
        }
        return r * COIF_INV_PI;
    }
    if (lobe == LOBE_TT) {
        vec3 b;
        vec3 lam;
        N_TT_fit(hp.eta, hp.sigma_a, theta_d, cfg.paper_norm, b, lam);
        for (int c = 0; c < 3; ++c)
            r[c] = b[c] * circ_integral(lam[c], cfg.paper_norm) * fetch_half_mass(lam[c], dphi - COIF_PI);
        return r * COIF_INV_PI;
    }
    TrtFit fit = N_TRT_fit(hp.eta, hp.sigma_a, theta_d, hp.w_c, hp.delta_eta_p, cfg.paper_norm);
    if (fit.three) {
        r = fit.b1 * (circ_integral(fit.w1, cfg.paper_norm) * (fetch_half_mass(fit.w1, dphi - fit.phi_star) +
                                                              fetch_half_mass(fit.w1, dphi + fit.phi_star))) +
            fit.b2 * (circ_integral(fit.phi_star, cfg.paper_norm) * fetch_half_mass(fit.phi_star, dphi));
    } else {
        for (int c = 0; c < 3; ++c)
            r[c] = fit.b3[c] * circ_integral(fit.lambda3[c], cfg.paper_norm) * fetch_half_mass(fit.lambda3[c], dphi);
    }
    return r * COIF_INV_PI;
}

// Bandwidth of the forward-scattering spread of a light (see the header).
COIF_FN float ms_lambda_f(float lambda_j, float sigma_f2) {
    return sqrt(lambda_j * lambda_j + 2.0 * max(sigma_f2, 0.0));
}

// 𝓜^G_t for one lobe (000 eq. 27, ψ_f normalised as in the header).
COIF_FN vec3 srbf_ms_global_lobe(int lobe, HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float theta_o,
                                 float phi_o, float theta_j, float phi_j, float lambda_f) {
    float alpha = lobe_alpha(hp, lobe);
    float beta = lobe_beta(hp, lobe);
    GaussProduct gp = gauss_product(theta_j, lambda_f, 2.0 * alpha - theta_o, 2.0 * beta);
    float scale = gp.c / (COIF_PI * lambda_f * beta) * M_norm(hp, lobe, theta_o);  // g^u(θi;θj,λf) · M_t
    float dphi = wrap_pi(phi_o - phi_j);
    int m = clamp(cfg.segments, 2, LIGHTING_MAX_SEGMENTS);
    float x_prev = -COIF_HALF_PI;
    vec3 f_prev = vec3(0.0);
    vec3 acc = vec3(0.0);
    for (int s = 1; s <= m; ++s) {
        float x = quadrature_abscissa(s, m, gp.mu, gp.lambda);
        vec3 f = vec3(0.0);
        float ci = cos(x);
        if (s < m && ci > 1e-6) {
            float theta_d = 0.5 * (theta_o - x);
            float cd = cos(theta_d);
            f = srbf_N_global(lobe, hp, cfg, f0123, f45, theta_d, dphi) * (ci / max(cd * cd, 1e-8));
        }
        acc += gauss_linear_segment(x_prev, x, f_prev, f, gp.mu, gp.lambda);
        x_prev = x;
        f_prev = f;
    }
    return scale * max(acc, vec3(0.0));
}

// The θd interval that θi ∈ [θj - λf, θj + λf] maps to (000 eq. 31), at least 1e-3 wide.
COIF_FN void ms_theta_d_window(float theta_o, float theta_j, float lambda_f, OUT(float) a, OUT(float) b) {
    a = clamp(0.5 * (theta_o - theta_j - lambda_f), -COIF_HALF_PI, COIF_HALF_PI);
    b = clamp(0.5 * (theta_o - theta_j + lambda_f), -COIF_HALF_PI, COIF_HALF_PI);
    if (b - a < 1e-3) {
        float mid = clamp(0.5 * (a + b), -COIF_HALF_PI + 5e-4, COIF_HALF_PI - 5e-4);
        a = mid - 5e-4;
        b = mid + 5e-4;
    }
}

// 𝓜^L (000 eq. 29-31): the azimuthal factor (π - |φo - φj|)/π² (eq. 30) times a θi integral whose
// Gaussian uses the means Δ̃_b, σ̃_b of Δ̄_b, σ̄_b over the light's spread (two fetches each into the
// summed-area tables); then the linear quadrature of Ā_b(θd) cos θi / cos²θd, per colour channel.
COIF_FN vec3 srbf_ms_local(HairParams hp, LightingConfig cfg, float theta_o, float phi_o, float theta_j, float phi_j,
                           float lambda_f) {
    vec3 sigma_a = hp.sigma_a;
    float dphi = wrap_pi(phi_o - phi_j);
    float azimuthal = (COIF_PI - abs(dphi)) / (COIF_PI * COIF_PI);
    float a;
    float b;
    ms_theta_d_window(theta_o, theta_j, lambda_f, a, b);
    vec3 delta_mean = (fetch_ms_sat_delta(b, sigma_a) - fetch_ms_sat_delta(a, sigma_a)) / (b - a);
    vec3 sigma_mean = (fetch_ms_sat_sigma(b, sigma_a) - fetch_ms_sat_sigma(a, sigma_a)) / (b - a);
    int m = clamp(cfg.segments, 2, LIGHTING_MAX_SEGMENTS);
    vec3 result = vec3(0.0);
    for (int c = 0; c < 3; ++c) {
        float lambda_b = 2.0 * sqrt(2.0) * max(sigma_mean[c], 1e-3);
        GaussProduct gp = gauss_product(theta_j, lambda_f, 2.0 * delta_mean[c] - theta_o, lambda_b);
        // 2/cos²θd (S_back) · g^u(θi;θj,λf) · 2 g^u(θi; 2Δ̃-θo, λb) / cos θi · cos θi ... see header
        float scale = 4.0 * azimuthal * gp.c / (COIF_PI * lambda_f * lambda_b);
        if (hp.longitudinal < 0.5) {  // ∫ 2 g^u(θi; μ, λb) dθi over [-π/2, π/2] = erf_diff
            float mu = 2.0 * delta_mean[c] - theta_o;
            scale /= max(erf_diff((-COIF_HALF_PI - mu) / lambda_b, (COIF_HALF_PI - mu) / lambda_b), 1e-6);
        }
        float x_prev = -COIF_HALF_PI;
        float f_prev = 0.0;
        float acc = 0.0;
        for (int s = 1; s <= m; ++s) {
            float x = quadrature_abscissa(s, m, gp.mu, gp.lambda);
            float f = 0.0;
            float ci = cos(x);
            if (s < m && ci > 1e-6) {
                float theta_d = 0.5 * (theta_o - x);
                float cd = cos(theta_d);
                f = fetch_ms_Ab(theta_d, sigma_a[c]) * ci / max(cd * cd, 1e-8);
            }
            acc += gauss_linear_segment(x_prev, x, vec3(f_prev), vec3(f), gp.mu, gp.lambda).x;
            x_prev = x;
            f_prev = f;
        }
        result[c] = scale * max(acc, 0.0);
    }
    return result;
}

// 𝓜^G + d_b 𝓜^L of one light (the caller multiplies by T_f and L_j).
COIF_FN vec3 srbf_multiple(HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float theta_o, float phi_o,
                           float theta_j, float phi_j, float lambda_j, float sigma_f2) {
    float lambda_f = ms_lambda_f(lambda_j, sigma_f2);
    vec3 g_sum = srbf_ms_global_lobe(LOBE_R, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_f) +
                  srbf_ms_global_lobe(LOBE_TT, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_f) +
                  srbf_ms_global_lobe(LOBE_TRT, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_f);
    return g_sum + hp.d_b * srbf_ms_local(hp, cfg, theta_o, phi_o, theta_j, phi_j, lambda_f);
}

// ---- Zinke's dual-scattering terms from the circular-Gaussian N_t (000 eq. 32-33) -----------------

// The fitted N_t(θd, φ) itself (η, no eccentricity).
COIF_FN vec3 N_fit_value(int lobe, HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float theta_d, float phi) {
    if (lobe == LOBE_R) {
        vec4 c_lo;
        vec4 c_hi;
        N_R_coefficients(hp.eta, theta_d, cfg.paper_schlick, f0123, f45, c_lo, c_hi);
        return vec3(N_R_poly_value(c_lo, c_hi, phi));
    }
    if (lobe == LOBE_TT) {
        vec3 b;
        vec3 lam;
        N_TT_fit(hp.eta, hp.sigma_a, theta_d, cfg.paper_norm, b, lam);
        vec3 r = vec3(0.0);
        for (int c = 0; c < 3; ++c) r[c] = b[c] * circ_gauss(phi, COIF_PI, lam[c]);
        return r;
    }
    return N_TRT_fit_value(N_TRT_fit(hp.eta, hp.sigma_a, theta_d, hp.w_c, hp.delta_eta_p, cfg.paper_norm), phi);
}

// ā_{f,t}(x) and ā_{b,t}(x) (000 eq. 33): the θo factor (1/2π) ∫ M_t((x+θo)/2) cos θo cos x / cos²((x-θo)/2) dθo
// by the linear quadrature (M_t((x+θo)/2) = g(θo; 2α-x, 2β)/(√πβ)), times the azimuthal factor
// 2 ∫_0^π w(φ) N_t(θd, φ) dφ with w = φ forward, π - φ backward (000 supplement §7), by the
// midpoint rule over the fitted N_t (fitted once per call).
COIF_FN void zinke_lobe_a(int lobe, HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float x, OUT(vec3) a_f,
                          OUT(vec3) a_b) {
    float alpha = lobe_alpha(hp, lobe);
    float beta = lobe_beta(hp, lobe);
    float mu = 2.0 * alpha - x;
    float lambda = 2.0 * beta;
    float cx = cos(x);
    float x_prev = -COIF_HALF_PI;
    float f_prev = 0.0;
    float acc = 0.0;
    for (int s = 1; s <= ZINKE_SEGMENTS; ++s) {
        float t = quadrature_abscissa(s, ZINKE_SEGMENTS, mu, lambda);
        float f = 0.0;
        if (s < ZINKE_SEGMENTS) {
            float c = cos(0.5 * (x - t));
            // Energy-conserving M_t: each outgoing θo = t has its own normalisation, 2 M_norm(t) ≈ 1 against
            // the 1/(2π) below (exactly 1 unless the lobe is cut by ±π/2).
            f = cos(t) * cx / max(c * c, 1e-8) * (hp.longitudinal >= 0.5 ? 1.0 : 2.0 * M_norm(hp, lobe, t));
        }
        acc += gauss_linear_segment(x_prev, t, vec3(f_prev), vec3(f), mu, lambda).x;
        x_prev = t;
        f_prev = f;
    }
    // 1/(2π), not 000 eq. 32's 1/π: M_t (eq. 7) is normalised in θh, so it integrates to 2 over θo,
    // and with 1/π a clear fibre would get ā_f + ā_b ≈ 2; Zinke's Ā_b, Δ̄_b need fractions (<= 1).
    float theta_part = 0.5 * COIF_INV_PI * acc / (COIF_SQRT_PI * beta);
    // 000 eq. 33 evaluates N_t at θd = x ("scattering occurs at θo = -θi"); M_t centres θo at 2α - x,
    // where the difference angle (x - θo)/2 is x - α. We use that centre: with α_R = -7.5° it halves
    // the error of Ā_b at |θd| ~ 1 (measured against the unseparated integral, `coif lighting check`).
    float theta_d = clamp(x - alpha, -COIF_HALF_PI + 1e-3, COIF_HALF_PI - 1e-3);
    vec4 c_lo = vec4(0.0);
    vec4 c_hi = vec4(0.0);
    vec3 tt_b = vec3(0.0);
    vec3 tt_lambda = vec3(1.0);
    TrtFit trt;
    if (lobe == LOBE_R) N_R_coefficients(hp.eta, theta_d, cfg.paper_schlick, f0123, f45, c_lo, c_hi);
    else if (lobe == LOBE_TT) N_TT_fit(hp.eta, hp.sigma_a, theta_d, cfg.paper_norm, tt_b, tt_lambda);
    else trt = N_TRT_fit(hp.eta, hp.sigma_a, theta_d, hp.w_c, hp.delta_eta_p, cfg.paper_norm);
    vec3 fwd = vec3(0.0);
    vec3 bwd = vec3(0.0);
    float dphi = COIF_PI / float(ZINKE_PHI_STEPS);
    for (int i = 0; i < ZINKE_PHI_STEPS; ++i) {
        float phi = (float(i) + 0.5) * dphi;
        vec3 n;
        if (lobe == LOBE_R) {
            n = vec3(N_R_poly_value(c_lo, c_hi, phi));
        } else if (lobe == LOBE_TT) {
            n = vec3(0.0);
            for (int c = 0; c < 3; ++c) n[c] = tt_b[c] * circ_gauss(phi, COIF_PI, tt_lambda[c]);
        } else {
            n = N_TRT_fit_value(trt, phi);
        }
        fwd += phi * n;
        bwd += (COIF_PI - phi) * n;
    }
    a_f = theta_part * 2.0 * dphi * fwd;
    a_b = theta_part * 2.0 * dphi * bwd;
}

// Zinke et al. 2008 §4: average backscattering attenuation Ā_b, shift Δ̄_b and deviation σ̄_b from
// the forward/backward attenuations ā, shifts ᾱ and variances β̄² (one bounce of back scattering
// plus three, A_1 + A_3).
COIF_FN void zinke_backscatter(vec3 af, vec3 ab, vec3 alpha_f, vec3 alpha_b, vec3 beta_f2, vec3 beta_b2, float d_b,
                               OUT(vec3) A_b, OUT(vec3) Delta_b, OUT(vec3) sigma_b) {
    vec3 af2 = min(af * af, vec3(0.99));
    vec3 ab2 = ab * ab;
    vec3 ab3 = ab2 * ab;
    vec3 one_m = 1.0 - af2;
    vec3 A1 = ab * af2 / one_m;
    vec3 A3 = ab3 * af2 / (one_m * one_m * one_m);
    A_b = A1 + A3;
    Delta_b = alpha_b * (1.0 - 2.0 * ab2 / (one_m * one_m)) +
              alpha_f * (2.0 * one_m * one_m + 4.0 * af2 * ab2) / (one_m * one_m * one_m);
    vec3 bf = sqrt(max(beta_f2, vec3(0.0)));
    vec3 bb = sqrt(max(beta_b2, vec3(0.0)));
    vec3 num = ab * sqrt(max(2.0 * beta_f2 + beta_b2, vec3(0.0))) + ab3 * sqrt(max(2.0 * beta_f2 + 3.0 * beta_b2, vec3(0.0)));
    vec3 den = max(ab + ab3 * (2.0 * bf + 3.0 * bb), vec3(1e-20));
    sigma_b = (1.0 + d_b * af2) * num / den;
}

// Σ over the lobes of the forward/backward attenuations ā_f, ā_b and of their shift- and
// variance-weighted sums (the moments that zinke_terms and zinke_forward normalise). At grazing θd
// every ā is ~0 (and may come out -1e-20): the weights get a floor so that the weighted means stay
// defined (they fall back to the plain mean of the lobes).
COIF_FN void zinke_lobe_sums(HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float x, OUT(vec3) af,
                             OUT(vec3) ab, OUT(vec3) alpha_f, OUT(vec3) alpha_b, OUT(vec3) beta_f2, OUT(vec3) beta_b2) {
    af = vec3(0.0);
    ab = vec3(0.0);
    alpha_f = vec3(0.0);
    alpha_b = vec3(0.0);
    beta_f2 = vec3(0.0);
    beta_b2 = vec3(0.0);
    for (int lobe = 0; lobe < 3; ++lobe) {
        vec3 f;
        vec3 bk;
        zinke_lobe_a(lobe, hp, cfg, f0123, f45, x, f, bk);
        f = max(f, vec3(0.0)) + 1e-12;
        bk = max(bk, vec3(0.0)) + 1e-12;
        float alpha = lobe_alpha(hp, lobe);
        float var = 0.5 * lobe_beta(hp, lobe) * lobe_beta(hp, lobe);
        af += f;
        ab += bk;
        alpha_f += f * alpha;
        alpha_b += bk * alpha;
        beta_f2 += f * var;
        beta_b2 += bk * var;
    }
}

// The three 1D functions of θd that local multiple scattering tabulates (000 §5), from the fitted N_t.
COIF_FN void zinke_terms(HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float x, OUT(vec3) A_b,
                         OUT(vec3) Delta_b, OUT(vec3) sigma_b) {
    vec3 af;
    vec3 ab;
    vec3 alpha_f;
    vec3 alpha_b;
    vec3 beta_f2;
    vec3 beta_b2;
    zinke_lobe_sums(hp, cfg, f0123, f45, x, af, ab, alpha_f, alpha_b, beta_f2, beta_b2);
    vec3 inv_f = 1.0 / af;
    vec3 inv_b = 1.0 / ab;
    zinke_backscatter(af, ab, alpha_f * inv_f, alpha_b * inv_b, beta_f2 * inv_f, beta_b2 * inv_b, hp.d_b, A_b,
                      Delta_b, sigma_b);
}

// What one fibre does to light passing forward through it (Zinke et al. 2008 §4, the shadow path of
// 000 eq. 3 and 5): the forward attenuation ā_f(θd) = Σ_t ā_{f,t} and the ā_f-weighted mean
// longitudinal variance β̄_f² (rad², per channel). K fibres on the path give Zinke's T_f = ā_f^K and
// σ̄_f² = K β̄_f²; srbf_shadowed.glsl takes the mean of both over a Poisson K of the shadow pass's
// optical depth n.
COIF_FN void zinke_forward(HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float x, OUT(vec3) a_f,
                           OUT(vec3) beta_f2) {
    vec3 ab;
    vec3 alpha_f;
    vec3 alpha_b;
    vec3 bf2;
    vec3 beta_b2;
    zinke_lobe_sums(hp, cfg, f0123, f45, x, a_f, ab, alpha_f, alpha_b, bf2, beta_b2);
    beta_f2 = bf2 / a_f;
}

#endif
