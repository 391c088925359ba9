// The own cluster's shadow on a shell fragment, by the fragment's side of its cluster toward the light
// (docs/quality.md, "The own cluster's shadow per fragment"). GLSL compiled also as C++
// (shaders/glsl_prelude.h); see the rules there.
//
// A cluster's cross-section is taken as a disc of radius R holding fibres at a uniform density; τ_R is
// the optical depth of one radius, κ_shadow Σ ᾱ over the layers at the fragment's (i, k) (ᾱ each sector's
// mean α: 004 eq. 12's units, which counts only the layers outside a fragment, for light from outside;
// this is eq. 12 turned toward each light). A fibre at ρR from the axis, whose radial direction makes the in-plane
// angle Δ with the light, sees the light through the chord
//     s(ρ, Δ) = −ρ cos Δ + √(1 − ρ² sin² Δ)        (in units of R; 1 − ρ facing it, 1 + ρ away)
// of its own cluster, so its light is multiplied by O(Δ) = exp(−τ s(ρ, Δ)), with τ = τ_R times
// own_cluster_stretch (the ray's path across the disc grows as the light turns along the hair). Shadows between clusters then start outside the own cluster (shaders/gl/shell_shadow.comp).
//
// The shells' Fourier path holds the lights only as harmonics of their azimuth (shell_lighting.comp:
// Σ_j w_j cos kψ_j, …, k ≤ 4) and the records' re(Δ) as harmonics of the light's azimuth Δ from the
// fragment's radial direction. O multiplies re for every light alike (τ then folds the lights' angles to
// the axis into one value per lighting sample), so the product h(Δ) = re(Δ) O(Δ) takes re's place.
// O is even in Δ, so O = o_0 + Σ_m o_m cos mΔ, and h's harmonics 0..4 need o_0..o_8 only (re has none above
// 4): own_cluster_harmonics multiplies the two series exactly. o_0..o_8 depend on (τ, ρ) alone and are read
// from a table (lut_own_cluster, below), computed once in double precision by shading::own_cluster_direct;
// the read is bilinear, so the error is the table's interpolation: below 1e-3 of re's mean (measured 4.9e-4)
// over τ ≤ 16 and every ρ, the kink at ρ = 1 included (tests/shading/test_own_cluster.cpp; the 16-point
// rule over Δ per fragment that the table replaced was off by 4 % at ρ = 1, at 16 exponentials a fragment). The shells take ρ at each layer
// mesh's own surface, the outer layer's at ρ = 1 (its middle measured darker against the reference:
// docs/quality.md).
#ifndef COIF_SHADERS_LIGHTING_OWN_CLUSTER_GLSL
#define COIF_SHADERS_LIGHTING_OWN_CLUSTER_GLSL

#include "shaders/lighting/luts.glsl"

// lut_own_cluster: o_0..o_8 over x = τ / (τ + OWN_TAU_SCALE) ∈ [0, OWN_X_MAX] (OWN_N_TAU columns; τ beyond
// the last, 198, reads it) and v = √(1 − ρ) ∈ [0, 1] (OWN_N_RHO rows per block: dense toward the surface, ρ = 1,
// where O changes fastest with ρ at large τ), in three blocks of rows: (o_0, o_1, o_2, o_3), (o_4, o_5, o_6, o_7),
// (o_8, 0, 0, 0). A fetch stays within its block (the block's first and last rows sit on ρ = 1 and 0).
const int OWN_N_TAU = 128;
const int OWN_N_RHO = 49;
const float OWN_TAU_SCALE = 2.0;
const float OWN_X_MAX = 0.99;

// s(ρ, Δ) above, from cos Δ and sin Δ.
COIF_FN float own_cluster_path(float rho, float cos_d, float sin_d) {
    return max(-rho * cos_d + sqrt(max(1.0 - rho * rho * sin_d * sin_d, 0.0)), 0.0);
}

// How much longer than the in-plane chord a ray along the unit direction d runs through a cluster of axis T:
// 1 / the sine of its angle to the axis, at most 4 (a ray along the hair would cross it endlessly; 4 radii is
// about where the hair around it takes over). The shadow pass starts its rays this many radii out.
COIF_FN float own_cluster_stretch(vec3 d, vec3 T) {
    return 1.0 / max(length(d - dot(d, T) * T), 0.25);
}

// How far a ray from the axis along the unit direction d runs before it leaves the own cluster, whose cross-section
// is the ellipse of half-axes A along the unit e1 (⟂ T) and B along T × e1: the ellipse's radius in the direction of
// d's part across the axis, 1 / √((u·e1 / A)² + (u·(T × e1) / B)²) for that unit u, times own_cluster_stretch. A flat
// cluster is crossed along its short axis in B, not in its widest half-axis, so that the shadow pass counts the
// neighbours beside it (docs/quality.md, "The shadow rays leave the own cluster through its ellipse").
COIF_FN float own_cluster_exit(vec3 d, vec3 T, vec3 e1, float A, float B) {
    vec3 across = d - dot(d, T) * T;
    float len = length(across);
    float stretch = own_cluster_stretch(d, T);
    if (len < 1e-6) return max(A, B) * stretch;
    vec3 u = across / len;
    float x = dot(u, e1) / max(A, 1e-6);
    float y = dot(u, cross(T, e1)) / max(B, 1e-6);
    return stretch / sqrt(max(x * x + y * y, 1e-12));
}

// Where the shadow pass starts a ray from the axis (before its two voxels of the grid's blur): where it leaves the own
// cluster (own_cluster_exit), or with `narrow` (ShellSettings::shadow_neighbours) at most the narrow half-axis min(A, B)
// times the stretch. The fitted clusters are flat ribbons that overlap: a ray leaving along the wide axis crosses the
// neighbours' fibres inside the ellipse, which neither the grid (past them) nor the own cluster's factor (its own
// layers) counted (docs/quality.md, "Forward scattering through the own cluster, and the neighbours in its ellipse").
COIF_FN float own_cluster_shadow_start(vec3 d, vec3 T, vec3 e1, float A, float B, bool narrow) {
    float exit_at = own_cluster_exit(d, T, e1, A, B);
    return narrow ? min(exit_at, min(A, B) * own_cluster_stretch(d, T)) : exit_at;
}

// The own cluster's optical depth per radius at a fragment whose unit radial direction is r: τ_R = κ_shadow Σ ᾱ, or on
// the cluster's side toward the hair's inside at least the shadow grid's fibres across it per radius, `inner` the
// vector weight · τ_out · (toward the hair's outside) of shaders/gl/shell_shadow.comp inner_depth, in r's frame. Light
// from outside crosses such a side's whole cluster, whose fibres the records' coverage undercounts; the cluster's outer
// side keeps Σ ᾱ, the coverage through which the camera sees into it (docs/quality.md, "The cluster's side toward the
// hair's inside").
COIF_FN float own_cluster_tau(float tau_r, vec2 inner, vec2 r) { return max(tau_r, -dot(inner, r)); }
COIF_FN float own_cluster_tau(float tau_r, vec3 inner, vec3 r) { return max(tau_r, -dot(inner, r)); }

COIF_FN float own_cluster_transmittance(float tau, float rho, float cos_d, float sin_d) {
    return exp(-tau * own_cluster_path(rho, cos_d, sin_d));
}

// τ and ρ of the table's grid point (column i, row j of a block).
COIF_FN float own_cluster_tau_at(int i) {
    float x = lut_point_lin(i, 0.0, OWN_X_MAX, OWN_N_TAU);
    return OWN_TAU_SCALE * x / (1.0 - x);
}
COIF_FN float own_cluster_rho_at(int j) {
    float v = float(j) / float(OWN_N_RHO - 1);
    return 1.0 - v * v;
}

// O's cosine harmonics at (τ, ρ): o0123 = (o_0, …, o_3), o4567, o8. Three bilinear fetches; two where the shells use
// re's harmonics up to 3 only (SHELL_FOURIER ≤ 3): o_8 multiplies re's fourth harmonic alone in the product below, so
// it is left 0 there without changing h.
COIF_FN void fetch_own_cluster(float tau, float rho, OUT(vec4) o0123, OUT(vec4) o4567, OUT(float) o8) {
    float u = lut_coord_lin(tau / (tau + OWN_TAU_SCALE), 0.0, OWN_X_MAX, OWN_N_TAU);
    float row = sqrt(clamp(1.0 - rho, 0.0, 1.0)) * float(OWN_N_RHO - 1) + 0.5;
    float rows = float(3 * OWN_N_RHO);
    o0123 = COIF_LUT(lut_own_cluster, vec2(u, row / rows));
    o4567 = COIF_LUT(lut_own_cluster, vec2(u, (row + float(OWN_N_RHO)) / rows));
#if defined(SHELL_FOURIER) && SHELL_FOURIER <= 3
    o8 = 0.0;
#else
    o8 = COIF_LUT(lut_own_cluster, vec2(u, (row + float(2 * OWN_N_RHO)) / rows)).x;
#endif
}

// O's harmonics at (τ, ρ) in the form the product below takes: p_0 = o_0 and p_m = o_m / 2 (O as Σ_m p_|m| e^{imΔ}),
// p1234 = (p_1, …, p_4), p5678 = (p_5, …, p_8). Three bilinear fetches.
COIF_FN void own_cluster_series(float tau, float rho, OUT(float) p0, OUT(vec4) p1234, OUT(vec4) p5678) {
    vec4 o0123;
    vec4 o4567;
    float o8;
    fetch_own_cluster(tau, rho, o0123, o4567, o8);
    p0 = o0123.x;
    p1234 = 0.5 * vec4(o0123.y, o0123.z, o0123.w, o4567.x);
    p5678 = 0.5 * vec4(o4567.y, o4567.z, o4567.w, o8);
}

// re's harmonics in, h = re · O's out, in the shells' layout: c01 = (a0, a1, b1), c23 = (a2, b2, a3, b3),
// c4 = (a4, b4), re(Δ) = a0 + Σ_k a_k cos kΔ + b_k sin kΔ; O's series (p0, p1234, p5678) as own_cluster_series gives it:
//   h_0 = a0 p_0 + Σ_k a_k p_k,  a_n = 2 a0 p_n + Σ_k a_k (p_|n−k| + p_{n+k}),  b_n = Σ_k b_k (p_|n−k| − p_{n+k}).
COIF_FN void own_cluster_product(float p0, vec4 p1234, vec4 p5678, vec3 c01, vec4 c23, vec2 c4, OUT(vec3) h01,
                                 OUT(vec4) h23, OUT(vec2) h4) {
    // For n = 1..4 (the vectors' components): u_k = p_|n−k|, w_k = p_{n+k}.
    vec4 u1 = vec4(p0, p1234.x, p1234.y, p1234.z);
    vec4 u2 = vec4(p1234.x, p0, p1234.x, p1234.y);
    vec4 u3 = vec4(p1234.y, p1234.x, p0, p1234.x);
    vec4 u4 = vec4(p1234.z, p1234.y, p1234.x, p0);
    vec4 w1 = vec4(p1234.y, p1234.z, p1234.w, p5678.x);
    vec4 w2 = vec4(p1234.z, p1234.w, p5678.x, p5678.y);
    vec4 w3 = vec4(p1234.w, p5678.x, p5678.y, p5678.z);
    vec4 w4 = vec4(p5678.x, p5678.y, p5678.z, p5678.w);
    float a0 = c01.x;
    vec4 a = vec4(c01.y, c23.x, c23.z, c4.x);
    vec4 b = vec4(c01.z, c23.y, c23.w, c4.y);
    vec4 an = 2.0 * a0 * p1234 + a.x * (u1 + w1) + a.y * (u2 + w2) + a.z * (u3 + w3) + a.w * (u4 + w4);
    vec4 bn = b.x * (u1 - w1) + b.y * (u2 - w2) + b.z * (u3 - w3) + b.w * (u4 - w4);
    h01 = vec3(a0 * p0 + dot(a, p1234), an.x, bn.x);
    h23 = vec4(an.y, bn.y, an.z, bn.z);
    h4 = vec2(an.w, bn.w);
}

// h = re · O at (τ, ρ): own_cluster_series then own_cluster_product.
COIF_FN void own_cluster_harmonics(float tau, float rho, vec3 c01, vec4 c23, vec2 c4, OUT(vec3) h01, OUT(vec4) h23,
                                   OUT(vec2) h4) {
    float p0;
    vec4 p1234;
    vec4 p5678;
    own_cluster_series(tau, rho, p0, p1234, p5678);
    own_cluster_product(p0, p1234, p5678, c01, c23, c4, h01, h23, h4);
}

// The own cluster with the light that its fibres scatter forward (SHELL_OWN 2; docs/quality.md, "Forward scattering
// through the own cluster, and the neighbours in its ellipse"). As the shadows between clusters split a light's path
// (shaders/lighting/srbf_shadowed.glsl), the light reaching a fibre through its own cluster is the unscattered share
// O(τ) plus d_f times the forward-scattered share's excess, d_f (O_f − O), with O_f = E[ā_f^K] = O(τ (1 − ā_f)) for K
// Poisson of mean τ s. In all, per channel (ā_f: the fibre's forward attenuation in that channel):
//     (1 − d_f) O(τ) + d_f O(τ (1 − ā_f))
// Its series, for one channel of loss = 1 − ā_f; own_cluster_product then takes it as it takes O's.
COIF_FN void own_cluster_forward_series(float tau, float rho, float loss, float d_f, float p0, vec4 p1234, vec4 p5678,
                                        OUT(float) q0, OUT(vec4) q1234, OUT(vec4) q5678) {
    own_cluster_series(tau * loss, rho, q0, q1234, q5678);
    q0 = mix(p0, q0, d_f);
    q1234 = mix(p1234, q1234, d_f);
    q5678 = mix(p5678, q5678, d_f);
}

#endif
