#pragma once
// The lighting module (shaders/lighting/, shaders/lighting.h) on the GL side, for every program that
// evaluates the SRBF Marschner lighting: it includes shaders/lighting/luts_gl.glsl (the table samplers,
// named as kLutUniformNames) and declares `uniform HairParams u_hair; uniform LightingConfig u_config;`.
//   - LightingTextures: the global tables (shading::global_lighting_tables) and the dual-scattering tables
//     of one hair parameter set as textures, rebuilt only when the parameters change;
//   - set_lighting_uniforms: u_hair.* and u_config.*;
//   - make_lights_buffer: the SRBF lights as shaders/gl/srbf_lights.glsl reads them (storage binding 3).
// Used by the strand renderer (online/strand_renderer.h) and the shell renderer's lighting pass.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "online/gl.h"
#include "shaders/lighting.h"
#include "shaders/srbf_light.h"

namespace coif::gl {

// The sampler names of shaders/lighting/luts_gl.glsl, in shading::LutSet order.
inline constexpr std::array<const char*, shading::kLutCount> kLutUniformNames = {
    "lut_ck_lo", "lut_ck_hi", "lut_h_tt", "lut_h_trt", "lut_half_mass", "lut_fresnel_fit", "lut_own_cluster",
    "lut_ms_ab", "lut_ms_sat_delta", "lut_ms_sat_sigma", "lut_ms_af"};

// True when (a, ca) and (b, cb) give the same dual-scattering tables (every field they read,
// shading::kHairParamsFields' in_ms_tables, and every config field).
bool same_lighting_tables(const shading::HairParams& a, const shading::LightingConfig& ca, const shading::HairParams& b,
                          const shading::LightingConfig& cb);

class LightingTextures {
public:
    LightingTextures();  // the global tables; needs a current GL context

    // Makes the dual-scattering tables those of (hair, config), building them only when they differ
    // from the last call's (validates: coif::Error). Returns true when it built them.
    bool update(const shading::HairParams& hair, const shading::LightingConfig& config);
    // Binds table i to texture unit first_unit + i and the program's sampler of that name to it (the
    // program must be in use).
    void bind(const Program& program, int first_unit) const;

private:
    std::array<Texture, shading::kLutCount> luts_;
    bool have_ms_ = false;
    shading::HairParams hair_{};
    shading::LightingConfig config_{};
};

// u_hair.* and u_config.* of the program in use: every field of shading::kHairParamsFields and
// shading::kLightingConfigFields.
void set_lighting_uniforms(const Program& program, const shading::HairParams& hair, const shading::LightingConfig& config);

// The defines that make shaders/gl/srbf_lights.glsl's lighting configuration, lobes (bit 1 << shading::LOBE_*) and
// dual scattering compile-time constants, so that the compiler drops what they switch off and unrolls the
// quadrature: SRBF_CONFIG (a LightingConfig constructor of every shading::kLightingConfigFields field, in order),
// SRBF_LOBES, SRBF_MULTIPLE. A program built with them is one variant of these three; without them it reads uniforms.
std::vector<std::string> srbf_variant_defines(const shading::LightingConfig& config, int lobes, bool multiple);

// The lights as the std430 array `GpuLight lights[]` of shaders/gl/srbf_lights.glsl ((unit ω, λ), (L, 0) each);
// validates each light (shading::validate_light: coif::Error).
Buffer make_lights_buffer(std::span<const SrbfLight> lights);

}  // namespace coif::gl
