// One SRBF light at a fibre point that sees the light through other fibres: single scattering with
// the effective transmittance T̃ (000 eq. 2) and dual-scattering multiple scattering with the forward
// transmittance T_f and spread σ̄_f² of the shadow path (000 eq. 3-5), combined as Zinke et al. 2008
// (Algorithm 1) combine them, so that the unscattered light is not counted twice:
//
//   direct  = T̃ (𝓜 + d_b 𝓜^L(λ_j))                    light that reached the point unscattered
//   scatter = d_f max(T_f − T̃, 0) (𝓜^G + d_b 𝓜^L)(λ_f)  light forward-scattered on the way
//   T_f = exp(−n (1 − ā_f(θ_j))),  σ̄_f² = n ā̄_f β̄_f²(θ_j)   (zinke_forward, tabulated in lut_ms_af)
//
// n is the optical depth of the shadow path (the renderer's shadow pass: the *mean* number of fibres
// a ray meets), T̃ the unoccluded fraction of the light's lobe (exp(−n) for one ray; the pass averages
// over the lobe). Zinke counts the fibres in front, K, and writes T_f = ā_f^K; with K Poisson of mean
// n (the same model that gives T̃ = P(K = 0) = e^−n), the expected forward transmittance is
// E[ā_f^K] = exp(−n (1 − ā_f)), and the light that arrives was scattered E[K | arrived] = n ā_f times,
// which sets its spread (ā̄_f: the mean of the three channels, since the spread is one number).
// ā_f^n with the mean put for K is not that: for brown hair ā_f ≈ 0.36 < e^−1, so ā_f^n fell below
// T̃ = e^−n at every depth and no forward-scattered light was left. ā_f is read at θd = θ_j: the
// fibres on the path are taken parallel to this one (Zinke's assumption). d_f is Zinke's density
// factor (≈ 0.7). With n = 0 and T̃ = 1 this is single scattering plus d_b times the local (backward)
// multiple scattering: a lone fibre.
//
// 000 writes L = Σ_j L_j [T̃ 𝓜 + T_f (𝓜^G + d_b 𝓜^L)], which at n = 0 adds single scattering twice
// (𝓜^G → 𝓜 as σ_f → 0); we keep Zinke's split.
//
// The light's power. 𝓜^G and 𝓜^L integrate S against the spread ψ_f, a normalised distribution (its
// integral is 1 for every λ_j): they are per unit *power* (radiance × sr) of the light, while 𝓜 of
// single scattering integrates L_j G_j itself and is per unit L_j. 000 eq. 3 multiplies ψ_f by L_j alone;
// taken literally, a light's multiple scattering would not depend on its width, and a narrow light
// (λ_j = 0.033, 0.0034 sr) would scatter as much as the whole sky. So the multiple-scattering part is
// multiplied by the light's power per unit L_j, ∫ G_j dω = srbf_integral(λ_j) (shaders/envmap.glsl).
// GLSL compiled also as C++.
#ifndef COIF_SHADERS_LIGHTING_SRBF_SHADOWED_GLSL
#define COIF_SHADERS_LIGHTING_SRBF_SHADOWED_GLSL

#include "shaders/envmap.glsl"
#include "shaders/lighting/srbf_multiple.glsl"

const float MS_DEFAULT_D_F = 0.7;  // Zinke et al. 2008: density factor of forward scattering
// Below this weight (T̃, or d_f (T_f − T̃)) a term is skipped: it scales quantities of the order of the
// unshadowed ones, so skipping changes a light's contribution by less than 1e-4 of its unshadowed
// value. Deep inside hair most pairs fall below it (the default style: mean T̃ 0.12, n ≈ 60).
const float MS_NEGLIGIBLE = 1e-4;

// Σ of the enabled single-scattering lobes (bit 1 << LOBE_t for each lobe t; shading::kLobes) of one light.
COIF_FN vec3 srbf_single_lobes(HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, int lobes, float theta_o,
                               float phi_o, float theta_j, float phi_j, float lambda_j) {
    vec3 m = vec3(0.0);
    if ((lobes & (1 << LOBE_R)) != 0) m += srbf_single_lobe(LOBE_R, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_j);
    if ((lobes & (1 << LOBE_TT)) != 0) m += srbf_single_lobe(LOBE_TT, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_j);
    if ((lobes & (1 << LOBE_TRT)) != 0) m += srbf_single_lobe(LOBE_TRT, hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_j);
    return m;
}

// The forward-scattered light's multiple scattering of one light per unit of its share d_f max(T_f − T̃, 0) and per
// unit of the light's power (srbf_shadowed_multiple's second term), for `fibres` met on the way, with `fw` the fibres'
// forward scattering fetch_ms_forward(θ_j, σa): the spread of n ā_f scatterings.
COIF_FN vec3 srbf_forward_multiple(HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float theta_o, float phi_o,
                                   float theta_j, float phi_j, float lambda_j, float fibres, vec4 fw) {
    float scatterings = fibres * (fw.x + fw.y + fw.z) / 3.0;
    return srbf_multiple(hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_j, scatterings * fw.w);
}

// The multiple-scattering part (direct local term plus forward-scattered light) of one light, per
// unit radiance L_j (the light's power srbf_integral(λ_j) times 𝓜^G, 𝓜^L; see the header);
// `direct` = T̃, `fibres` = n.
COIF_FN vec3 srbf_shadowed_multiple(HairParams hp, LightingConfig cfg, vec4 f0123, vec4 f45, float d_f, float theta_o,
                                    float phi_o, float theta_j, float phi_j, float lambda_j, float direct,
                                    float fibres) {
    vec3 ms = vec3(0.0);
    if (direct > MS_NEGLIGIBLE) ms = direct * hp.d_b * srbf_ms_local(hp, cfg, theta_o, phi_o, theta_j, phi_j, lambda_j);
    if (fibres > 0.0) {
        vec4 fw = fetch_ms_forward(theta_j, hp.sigma_a);
        vec3 a_f = vec3(fw.x, fw.y, fw.z);
        vec3 T_f = exp(-fibres * (vec3(1.0) - a_f));
        vec3 share = d_f * max(T_f - vec3(direct), vec3(0.0));
        if (max(max(share.x, share.y), share.z) > MS_NEGLIGIBLE)
            ms += share * srbf_forward_multiple(hp, cfg, f0123, f45, theta_o, phi_o, theta_j, phi_j, lambda_j, fibres, fw);
    }
    return srbf_integral(lambda_j) * ms;
}

#endif
