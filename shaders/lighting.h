#pragma once
// SRBF circular-Gaussian Marschner lighting (000 §3-§5, issue 6) for C++ callers: the run-time
// functions of shaders/lighting/*.glsl compiled as C++ (namespace coif::glsl), the tables they read,
// parameter validation and a CPU evaluator of the full lighting of one shading point.
//
// Conventions (DESIGN.md): hair-local frame u = tangent root→tip, v = the reference normal (φ = 0,
// the axis `a` scales for eccentric fibres), w = u × v; ω = [sinθ, cosθ cosφ, cosθ sinφ]; angles in
// radians; Gaussian widths are 000's bandwidths λ (variance λ²/2); σa per unit fibre radius (RGB).
// Radiance of one shading point (000 eq. 2-4 in Zinke's split, shaders/lighting/srbf_shadowed.glsl),
// with D the fibre diameter applied by the caller:
//   L_o = D Σ_j L_j [ T̃_j (𝓜_j + d_b 𝓜^L_j(λ_j)) + d_f max(T_f,j − T̃_j, 0) (𝓜^G_j + d_b 𝓜^L_j)(λ_f,j) ]
#include <span>
#include <string>

#include "shaders/glsl_prelude.h"
#include "shaders/lighting_tables.h"
#include "shaders/srbf_light.h"

namespace coif::glsl {
#include "shaders/lighting/srbf_shadowed.glsl"
}  // namespace coif::glsl

namespace coif::shading {

using HairParams = glsl::HairParams;
using LightingConfig = glsl::LightingConfig;

// Accepted parameter ranges (validate() refuses anything else, and NaN/Inf anywhere).
inline constexpr float kMinEta = 1.0f;          // exclusive: η must exceed 1
inline constexpr float kMaxEta = 10.0f;         // the tables' η range (000 §5)
inline constexpr float kMinBeta = 1e-3f;        // rad (0.06°); β = 0 is a delta lobe
inline constexpr float kMaxBeta = 1.5707963f;
inline constexpr float kMaxAlpha = 0.7853982f;  // |α| <= 45°
inline constexpr float kMinEcc = 0.7072f;       // a in (1/√2, √2) keeps η* > 1 (000 eq. 24)
inline constexpr float kMaxEcc = 1.4142f;
inline constexpr float kMinLambda = 1e-3f;      // SRBF and caustic bandwidths, rad
inline constexpr float kMaxLambda = 100.0f;
inline constexpr float kMaxSigmaA = 1e4f;       // per unit radius; beyond this TT/TRT are exactly 0 anyway
inline constexpr float kMinDeltaEtaPrime = 1e-3f;  // Δη' (000 §4.2.4): the caustic's fade range above η' = 2
inline constexpr float kMaxDeltaEtaPrime = 2.0f;

// η = 1.55, brown σa, α_R = -7.5°, β_R = 7.5° with 000's links, a = 1, w_c = 0.15 rad, Δη' = 0.3, d_b = 0.7.
HairParams default_hair_params();

// 000 §6: α_TT = -α_R/2, α_TRT = -3α_R/2, β_TT = β_R/2, β_TRT = 2β_R (radians).
HairParams linked_hair_params(float eta, glm::vec3 sigma_a, float alpha_R, float beta_R, float ecc_a, float w_c);
// The same links in place: TT and TRT follow p's α_R and β_R.
void link_lobes_to_R(HairParams& p);

// Throws coif::Error (place = `place`, e.g. "option --eta") naming the first bad field and the range.
void validate(const HairParams& params, const std::string& place = "hair parameters");
void validate(const LightingConfig& config, const std::string& place = "lighting config");
void validate_light(float lambda_j, glm::vec3 direction, const std::string& place = "SRBF light");

// m = 4 with the improvements of srbf_single.glsl (exact Fresnel fit, Bessel norms, θ correction).
LightingConfig default_config(int segments = 4);
// The paper as written: Schlick, √πλ, g^c_j(θi) ≈ g_j(θi).
LightingConfig paper_config(int segments = 4);

// Per-light visibility from the renderer's shadow pass (defaults: unshadowed). T_f and σ̄_f² follow
// from `fibres` (shaders/lighting/srbf_shadowed.glsl).
struct LightShadow {
    float direct = 1.0f;  // T̃: the light's unoccluded fraction (000 eq. 2's effective transmittance)
    float fibres = 0.0f;  // n: fibres met on the way to the light
};

struct FibreFrame {
    glm::vec3 u{1.0f, 0.0f, 0.0f}, v{0.0f, 1.0f, 0.0f}, w{0.0f, 0.0f, 1.0f};
    // u = tangent; v = the part of `normal_hint` orthogonal to u (any orthogonal axis if parallel).
    static FibreFrame from_tangent(glm::vec3 tangent, glm::vec3 normal_hint);
};

struct PointLighting {
    glm::vec3 single{0.0f};    // Σ_j L_j T̃_j 𝓜_j
    glm::vec3 multiple{0.0f};  // Σ_j L_j ∫G_j [T̃_j d_b 𝓜^L_j + d_f (T_f,j − T̃_j)⁺ (𝓜^G_j + d_b 𝓜^L_j)]
    glm::vec3 total() const { return single + multiple; }
};

// The CPU evaluator: validated parameters, the global tables and this parameter set's dual-scattering
// tables. Thread-safe for concurrent const calls.
class LightingEvaluator {
public:
    explicit LightingEvaluator(const HairParams& params, const LightingConfig& config = default_config());

    const HairParams& params() const { return params_; }
    const LightingConfig& config() const { return config_; }
    const MultipleScatteringTables& ms_tables() const { return ms_; }

    // All lights, all lobes, single + multiple scattering, at one shading point. `view` points from
    // the point towards the eye. `shadows` is empty (all unshadowed) or one entry per light. A light's
    // ω is normalised on use.
    PointLighting shade(const FibreFrame& frame, glm::vec3 view, std::span<const SrbfLight> lights,
                        std::span<const LightShadow> shadows = {}, bool multiple = true,
                        float d_f = glsl::MS_DEFAULT_D_F) const;

    // One light, in hair-frame angles: 𝓜 = Σ_t 𝓜_t (000 eq. 11), one lobe, and 𝓜^G + d_b 𝓜^L.
    glm::vec3 single(float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j) const;
    glm::vec3 single_lobe(int lobe, float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j) const;
    glm::vec3 multiple(float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j, float sigma_f2) const;
    glm::vec3 ms_global(float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j, float sigma_f2) const;
    glm::vec3 ms_local(float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j, float sigma_f2) const;

    // Binds the global and dual-scattering tables to this thread (for calling coif::glsl directly).
    LutBinding bind() const { return LutBinding(lut_set_); }

private:
    HairParams params_;
    LightingConfig config_;
    MultipleScatteringTables ms_;
    LutSet lut_set_;
    glm::vec4 f0123_{0.0f}, f45_{0.0f};
};

}  // namespace coif::shading
