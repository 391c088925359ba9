// The Marschner et al. 2003 hair scattering model as 000 §4.1 states it: the pieces shared by the
// run-time approximation (srbf_single.glsl, srbf_multiple.glsl) and the exact reference
// (shaders/marschner_reference.cpp). GLSL compiled also as C++.
//
// Hair-local frame (DESIGN.md, 000 §3): u = tangent root→tip, ω = [sinθ, cosθ cosφ, cosθ sinφ] in
// (u, v, w); θ ∈ [-π/2, π/2] longitudinal, φ azimuth from v. θd = (θo-θi)/2, φ = φo-φi.
// For an eccentric (elliptic) fibre the axis scaled by `a` (eq. 24) is v.
//
// Parameters (struct HairParams), radians in code, degrees only at the user interface:
//   eta        index of refraction η (> 1)
//   sigma_a    absorption per unit fibre *radius* (RGB, >= 0): a path through the fibre centre
//              (length 2 radii) attenuates by exp(-2 σa); path attenuation T = exp(-2 σa' cos γt)
//              with σa' = σa / cos θt (000 §4.1)
//   alpha_*    longitudinal shifts α_R, α_TT, α_TRT
//   beta_*     longitudinal widths: M_t(θh) = g^u(θh; α_t, β_t) (000 eq. 7). β is 000's bandwidth λ,
//              so the standard deviation of M_t is β/√2 (Marschner's β is a standard deviation).
//   ecc_a      eccentricity a (000 eq. 24; 1 = circular), in (1/√2, √2) so that η* stays > 1
//   w_c        azimuthal width of the TRT caustic lobes (000 eq. 20; bandwidth λ)
//   delta_eta_p  Δη', the range over which the caustic fades above η' = 2 (000 §4.2.4)
//   d_b        backward-scattering density factor of dual scattering (000 eq. 4)
//   longitudinal  0: energy-conserving M_t (the default): the Gaussian divided by its integral over θi for
//              the given θo, so that ∫ M_t dθi = 1 (d'Eon et al. 2011, which 000 cites); 1: 000's literal
//              M_t = g^u(θh), which integrates to ~2 over θi (docs/quality.md "Finding (energy)")
#ifndef COIF_SHADERS_LIGHTING_MARSCHNER_GLSL
#define COIF_SHADERS_LIGHTING_MARSCHNER_GLSL

#include "shaders/lighting/common.glsl"

struct HairParams {
    float eta;
    vec3 sigma_a;
    float alpha_R;
    float alpha_TT;
    float alpha_TRT;
    float beta_R;
    float beta_TT;
    float beta_TRT;
    float ecc_a;
    float w_c;
    float delta_eta_p;
    float d_b;
    float longitudinal;
};

const int LOBE_R = 0;
const int LOBE_TT = 1;
const int LOBE_TRT = 2;

COIF_FN float lobe_alpha(HairParams hp, int lobe) {
    return lobe == LOBE_R ? hp.alpha_R : (lobe == LOBE_TT ? hp.alpha_TT : hp.alpha_TRT);
}
COIF_FN float lobe_beta(HairParams hp, int lobe) {
    return lobe == LOBE_R ? hp.beta_R : (lobe == LOBE_TT ? hp.beta_TT : hp.beta_TRT);
}

// Unpolarised Fresnel reflectance of a dielectric of index η > 1 for light arriving from outside
// at an angle whose cosine is cos_i (the exact term; 000 uses Schlick's approximation for N_R).
// The internal reflection of TRT has the same reflectance (reciprocity), so one function serves.
COIF_FN float fresnel_dielectric(float eta, float cos_i) {
    float ci = clamp(cos_i, 0.0, 1.0);
    if (ci <= 0.0) return 1.0;  // grazing (also keeps η = 1 from 0/0)
    float sin_t2 = (1.0 - ci * ci) / (eta * eta);
    float ct = safe_sqrt(1.0 - sin_t2);
    float rs = (ci - eta * ct) / (ci + eta * ct);
    float rp = (eta * ci - ct) / (eta * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

// F(η, θd, h): the incidence angle on the cylinder has cosine cos θd · sqrt(1 - h²).
COIF_FN float fresnel_h(float eta, float theta_d, float h) {
    return fresnel_dielectric(eta, cos(theta_d) * safe_sqrt(1.0 - h * h));
}

// Schlick's approximation (000 §4.2.1): F0 + (1-F0)(1 - cos θd sqrt(1-h²))^5.
COIF_FN float fresnel_schlick_f0(float eta) {
    float r = (eta - 1.0) / (eta + 1.0);
    return r * r;
}

// Bravais' effective index for the azimuthal plane (000 Table 1): η' = sqrt(η² - sin²θd) / cos θd.
COIF_FN float eta_prime(float eta, float theta_d) {
    float s = sin(theta_d);
    return safe_sqrt(eta * eta - s * s) / max(cos(theta_d), 1e-4);
}

// σa' = σa / cos θt with sin θt = sin θd / η (000 Table 1).
COIF_FN vec3 sigma_a_prime(vec3 sigma_a, float eta, float theta_d) {
    float s = sin(theta_d) / eta;
    return sigma_a / max(safe_sqrt(1.0 - s * s), 1e-4);
}

// Exit azimuth of path p (0 = R, 1 = TT, 2 = TRT) entering at offset h (000 eq. 8), not wrapped.
COIF_FN float phi_of_h(int p, float h, float eta_p) {
    float fp = float(p);
    return 2.0 * fp * safe_asin(h / eta_p) - 2.0 * safe_asin(h) + fp * COIF_PI;
}

// Attenuation of one internal chord (000 §4.1): T = exp(-2 σa' sqrt(1 - h²/η'²)).
COIF_FN vec3 attenuation_T(vec3 sigma_ap, float h, float eta_p) {
    return exp(-2.0 * sigma_ap * safe_sqrt(1.0 - h * h / (eta_p * eta_p)));
}

// A_t(θd, h) of 000 eq. 10 with the exact Fresnel term.
COIF_FN vec3 attenuation_A(int lobe, float eta, vec3 sigma_a, float theta_d, float h) {
    float f = fresnel_h(eta, theta_d, h);
    if (lobe == LOBE_R) return vec3(f);
    float eta_p = eta_prime(eta, theta_d);
    vec3 t = attenuation_T(sigma_a_prime(sigma_a, eta, theta_d), h, eta_p);
    if (lobe == LOBE_TT) return (1.0 - f) * (1.0 - f) * t;
    return (1.0 - f) * (1.0 - f) * f * t * t;
}

// Marschner's eccentric index (000 eq. 24): η*(φh) = ((η1*+η2*) + cos 2φh (η1*-η2*)) / 2.
COIF_FN float eta_star_1(float eta, float a) { return 2.0 * (eta - 1.0) * a * a - eta + 2.0; }
COIF_FN float eta_star_2(float eta, float a) { return 2.0 * (eta - 1.0) / (a * a) - eta + 2.0; }
COIF_FN float eta_star(float eta, float a, float cos_2phi_h) {
    float e1 = eta_star_1(eta, a);
    float e2 = eta_star_2(eta, a);
    return 0.5 * ((e1 + e2) + cos_2phi_h * (e1 - e2));
}

// The factor that makes M_t energy-conserving for outgoing θo: 1 / ∫_{-π/2}^{π/2} M_t dθi. As a function of θi,
// 000's M_t = g^u(θh) = g(θi; 2α - θo, 2β) / (√π β), whose integral over [-π/2, π/2] is
// erf_diff((-π/2 - μ)/2β, (π/2 - μ)/2β) with μ = 2α - θo: 2 for a lobe well inside the range. It depends on θo
// only, so every closed form over the light's θi keeps its shape and is scaled by it. 1 with longitudinal = 1
// (000's literal form).
COIF_FN float M_norm(HairParams hp, int lobe, float theta_o) {
    if (hp.longitudinal >= 0.5) return 1.0;
    float mu = 2.0 * lobe_alpha(hp, lobe) - theta_o;
    float l = 2.0 * lobe_beta(hp, lobe);
    return 1.0 / max(erf_diff((-COIF_HALF_PI - mu) / l, (COIF_HALF_PI - mu) / l), 1e-6);
}

// M_t(θi, θo) = g^u(θh; α_t, β_t) (000 eq. 7), θh = (θi + θo)/2, times M_norm(θo).
COIF_FN float M_lobe(HairParams hp, int lobe, float theta_i, float theta_o) {
    return gauss_u(0.5 * (theta_i + theta_o), lobe_alpha(hp, lobe), lobe_beta(hp, lobe)) * M_norm(hp, lobe, theta_o);
}

#endif
