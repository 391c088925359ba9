#include "online/lighting_uniforms.h"

#include <cstdio>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "models/core/log.h"
#include "shaders/hair_parameters.h"

namespace coif::gl {

bool same_lighting_tables(const shading::HairParams& a, const shading::LightingConfig& ca, const shading::HairParams& b,
                          const shading::LightingConfig& cb) {
    for (const shading::HairParamsField& f : shading::kHairParamsFields)
        if (f.in_ms_tables && !std::visit([&](auto member) { return a.*member == b.*member; }, f.member)) return false;
    for (const shading::LightingConfigField& f : shading::kLightingConfigFields)
        if (!std::visit([&](auto member) { return ca.*member == cb.*member; }, f.member)) return false;
    return true;
}

LightingTextures::LightingTextures() {
    const shading::LutSet set = shading::global_lighting_tables().set();
    for (int i = 0; i < shading::kLutCount; ++i)
        if (set.images[i]) luts_[i] = make_lut_texture(*set.images[i]);
}

bool LightingTextures::update(const shading::HairParams& hair, const shading::LightingConfig& config) {
    if (have_ms_ && same_lighting_tables(hair_, config_, hair, config)) return false;
    log_message(LogLevel::info, "building the dual-scattering tables of these hair parameters");
    const shading::LightingEvaluator evaluator(hair, config);  // validates, builds the tables
    const shading::LutSet ms = evaluator.ms_tables().set();
    for (int i = 0; i < shading::kLutCount; ++i)
        if (ms.images[i]) luts_[i] = make_lut_texture(*ms.images[i]);
    hair_ = hair;
    config_ = config;
    have_ms_ = true;
    return true;
}

void LightingTextures::bind(const Program& program, int first_unit) const {
    for (int i = 0; i < shading::kLutCount; ++i) {
        glBindTextureUnit(static_cast<GLuint>(first_unit + i), luts_[i].id());
        glUniform1i(program.uniform(kLutUniformNames[i]), first_unit + i);
    }
}

void set_lighting_uniforms(const Program& program, const shading::HairParams& hair, const shading::LightingConfig& config) {
    for (const shading::HairParamsField& f : shading::kHairParamsFields) {
        const GLint location = program.uniform(("u_hair." + std::string(f.name)).c_str());
        if (const auto* member = std::get_if<float shading::HairParams::*>(&f.member)) glUniform1f(location, hair.**member);
        else glUniform3fv(location, 1, &(hair.*std::get<glm::vec3 shading::HairParams::*>(f.member)).x);
    }
    for (const shading::LightingConfigField& f : shading::kLightingConfigFields) {
        const GLint location = program.uniform(("u_config." + std::string(f.name)).c_str());
        std::visit([&](auto member) { glUniform1i(location, static_cast<GLint>(config.*member)); }, f.member);
    }
}

std::vector<std::string> srbf_variant_defines(const shading::LightingConfig& config, int lobes, bool multiple) {
    std::string args;
    for (const shading::LightingConfigField& f : shading::kLightingConfigFields) {
        if (!args.empty()) args += ", ";
        std::visit(
            [&](auto member) {
                if constexpr (std::is_same_v<std::remove_cvref_t<decltype(config.*member)>, bool>)
                    args += config.*member ? "true" : "false";
                else
                    args += std::to_string(config.*member);
            },
            f.member);
    }
    return {"SRBF_CONFIG LightingConfig(" + args + ")", "SRBF_LOBES " + std::to_string(lobes),
            std::string("SRBF_MULTIPLE ") + (multiple ? "1" : "0")};
}

Buffer make_lights_buffer(std::span<const SrbfLight> lights) {
    struct GpuLight {  // std430 mirror of shaders/gl/srbf_light_buffer.glsl
        glm::vec4 direction_lambda, radiance;
    };
    std::vector<GpuLight> gpu;
    gpu.reserve(lights.size());
    for (const SrbfLight& l : lights) {
        shading::validate_light(l.lambda, l.omega, "SRBF light");
        gpu.push_back({glm::vec4(glm::normalize(l.omega), l.lambda), glm::vec4(l.L, 0.0f)});
    }
    return make_buffer(gpu.data(), gpu.size() * sizeof(GpuLight));
}

}  // namespace coif::gl
