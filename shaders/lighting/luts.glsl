// Layout of the precomputed tables of the SRBF lighting and the typed look-ups into them.
// The tables are computed on the CPU at start-up (shaders/lighting_tables.cpp) and, in GL, uploaded
// as GL_RGBA32F textures with GL_LINEAR filtering and clamp-to-edge (online/). COIF_LUT(name, uv) is
// a bilinear fetch: in GL `textureLod(name, uv, 0.0)` (shaders/lighting/luts_gl.glsl), in C++ the
// CPU table bound to the thread (shaders/lut.h). Grid points sit on texel centres, so a parameter
// on the grid reads its texel exactly and between grid points the fetch interpolates linearly.
//
// Resolutions and ranges follow 000 §5 (128 samples for λ' and η, log-spaced over [0.001, 10] and
// [1, 10]; 64 samples for φo-φj and θd) unless a comment says otherwise.
#ifndef COIF_SHADERS_LIGHTING_LUTS_GLSL
#define COIF_SHADERS_LIGHTING_LUTS_GLSL

#include "shaders/lighting/common.glsl"

const float LUT_LAMBDA_MIN = 0.001;
const float LUT_LAMBDA_MAX = 10.0;
const int LUT_N_LAMBDA = 128;
const float LUT_ETA_MIN = 1.0;
const float LUT_ETA_MAX = 10.0;
const int LUT_N_ETA = 128;
const int LUT_N_PHI = 64;       // |φo - φj| ∈ [0, π] (the tables are even in it)
const int LUT_N_THETA_D = 64;   // |θd| ∈ [0, π/2] (H_k depends on cos θd only)
const int LUT_N_MS = 128;       // θd ∈ [-π/2, π/2] for the dual-scattering tables (000 §5)

// Texture coordinate of x on a grid of n points spread linearly (or logarithmically) over [x0, x1].
COIF_FN float lut_coord_lin(float x, float x0, float x1, int n) {
    float t = clamp((x - x0) / (x1 - x0), 0.0, 1.0);
    return (t * float(n - 1) + 0.5) / float(n);
}
COIF_FN float lut_coord_log(float x, float x0, float x1, int n) {
    float t = clamp(log(max(x, x0) / x0) / log(x1 / x0), 0.0, 1.0);
    return (t * float(n - 1) + 0.5) / float(n);
}
// Grid point i of the same grids (used by the table builder).
COIF_FN float lut_point_lin(int i, float x0, float x1, int n) {
    return x0 + (x1 - x0) * float(i) / float(n - 1);
}
COIF_FN float lut_point_log(int i, float x0, float x1, int n) {
    return x0 * exp(log(x1 / x0) * float(i) / float(n - 1));
}

// 𝒞_k(λ', Δφ) / ∫g^c(λ') for k = 0..3 (lo) and 4..6 (hi): two fetches (000 eq. 14).
COIF_FN void fetch_Ck(float lambda_p, float dphi, OUT(vec4) lo, OUT(vec4) hi) {
    vec2 uv = vec2(lut_coord_lin(abs(wrap_pi(dphi)), 0.0, COIF_PI, LUT_N_PHI),
                   lut_coord_log(lambda_p, LUT_LAMBDA_MIN, LUT_LAMBDA_MAX, LUT_N_LAMBDA));
    lo = COIF_LUT(lut_ck_lo, uv);
    hi = COIF_LUT(lut_ck_hi, uv);
}

// (H_0, H_2, H_4)^TT (000 eq. 19) and ^TRT (eq. 23) at (η, θd): one fetch each.
COIF_FN vec3 fetch_H_TT(float eta, float theta_d) {
    vec2 uv = vec2(lut_coord_lin(abs(theta_d), 0.0, COIF_HALF_PI, LUT_N_THETA_D),
                   lut_coord_log(eta, LUT_ETA_MIN, LUT_ETA_MAX, LUT_N_ETA));
    vec4 t = COIF_LUT(lut_h_tt, uv);
    return vec3(t.x, t.y, t.z);
}
COIF_FN vec3 fetch_H_TRT(float eta, float theta_d) {
    vec2 uv = vec2(lut_coord_lin(abs(theta_d), 0.0, COIF_HALF_PI, LUT_N_THETA_D),
                   lut_coord_log(eta, LUT_ETA_MIN, LUT_ETA_MAX, LUT_N_ETA));
    vec4 t = COIF_LUT(lut_h_trt, uv);
    return vec3(t.x, t.y, t.z);
}

// ∫_{δ-π/2}^{δ+π/2} g^c(x;0,λ) dx / ∫g^c(λ): the share of a circular Gaussian inside the half circle
// centred δ away from its mean (for 000 eq. 28; one fetch).
COIF_FN float fetch_half_mass(float lambda, float delta) {
    vec2 uv = vec2(lut_coord_lin(abs(wrap_pi(delta)), 0.0, COIF_PI, LUT_N_PHI),
                   lut_coord_log(lambda, LUT_LAMBDA_MIN, LUT_LAMBDA_MAX, LUT_N_LAMBDA));
    return COIF_LUT(lut_half_mass, uv).x;
}

// Coefficients f_0..f_5 of F(η, μ) ≈ Σ f_n μ^n, the exact Fresnel term fitted in the cosine of
// incidence μ (relative least squares; replaces Schlick in N_R, see srbf_single.glsl). Two fetches
// that depend on η only (per shading point, not per light).
COIF_FN void fetch_fresnel_fit(float eta, OUT(vec4) f0123, OUT(vec4) f45) {
    float v = lut_coord_log(eta, LUT_ETA_MIN, LUT_ETA_MAX, LUT_N_ETA);
    f0123 = COIF_LUT(lut_fresnel_fit, vec2(0.25, v));
    f45 = COIF_LUT(lut_fresnel_fit, vec2(0.75, v));
}

// Dual-scattering tables of one parameter set except σa (000 §5): per colour channel, over θd ∈
// [-π/2, π/2] (x) and the channel's absorption σa (y, LUT_N_MS_SIGMA levels of u = σa/(σa + 1), so
// [0, ∞) maps to [0, 1]): Ā_b, the running integrals ∫_{-π/2}^{θd} Δ̄_b and ∫ σ̄_b (1D summed-area
// tables, 000 eq. 31), and the forward terms ā_f, β̄_f² of the shadow path. Every dual-scattering
// term is computed channel by channel, so a table over one scalar σa serves all three channels — and
// σa can change per shading point (painted absorption) or per frame without rebuilding anything.
const int LUT_N_MS_SIGMA = 32;
COIF_FN float ms_coord(float theta_d) {
    return lut_coord_lin(theta_d, -COIF_HALF_PI, COIF_HALF_PI, LUT_N_MS);
}
COIF_FN float ms_sigma_coord(float sigma_a) {
    return lut_coord_lin(sigma_a / (sigma_a + 1.0), 0.0, 1.0, LUT_N_MS_SIGMA);
}
// σa of level l (the top level stands for σa → ∞).
COIF_FN float ms_sigma_level(int l) {
    float u = min(float(l) / float(LUT_N_MS_SIGMA - 1), 1.0 - 1e-5);
    return u / (1.0 - u);
}
COIF_FN float fetch_ms_Ab(float theta_d, float sigma_a) {
    return COIF_LUT(lut_ms_ab, vec2(ms_coord(theta_d), ms_sigma_coord(sigma_a))).x;
}
COIF_FN vec3 fetch_ms_sat_delta(float theta_d, vec3 sigma_a) {
    float x = ms_coord(theta_d);
    return vec3(COIF_LUT(lut_ms_sat_delta, vec2(x, ms_sigma_coord(sigma_a.x))).x,
                COIF_LUT(lut_ms_sat_delta, vec2(x, ms_sigma_coord(sigma_a.y))).x,
                COIF_LUT(lut_ms_sat_delta, vec2(x, ms_sigma_coord(sigma_a.z))).x);
}
COIF_FN vec3 fetch_ms_sat_sigma(float theta_d, vec3 sigma_a) {
    float x = ms_coord(theta_d);
    return vec3(COIF_LUT(lut_ms_sat_sigma, vec2(x, ms_sigma_coord(sigma_a.x))).x,
                COIF_LUT(lut_ms_sat_sigma, vec2(x, ms_sigma_coord(sigma_a.y))).x,
                COIF_LUT(lut_ms_sat_sigma, vec2(x, ms_sigma_coord(sigma_a.z))).x);
}
// Forward scattering through one fibre: ā_f(θd) per channel (xyz) and β̄_f² (rad²) averaged over the
// channels (w), see zinke_forward.
COIF_FN vec4 fetch_ms_forward(float theta_d, vec3 sigma_a) {
    float x = ms_coord(theta_d);
    vec4 r = COIF_LUT(lut_ms_af, vec2(x, ms_sigma_coord(sigma_a.x)));
    vec4 g = COIF_LUT(lut_ms_af, vec2(x, ms_sigma_coord(sigma_a.y)));
    vec4 b = COIF_LUT(lut_ms_af, vec2(x, ms_sigma_coord(sigma_a.z)));
    return vec4(r.x, g.x, b.x, (r.y + g.y + b.y) / 3.0);
}

#endif
