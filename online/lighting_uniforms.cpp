#include "online/lighting_uniforms.h"

#include <cstdio>
#include <vector>

namespace coif::gl {

bool same_lighting_tables(const shading::HairParams& a, const shading::LightingConfig& ca, const shading::HairParams& b,
                          const shading::LightingConfig& cb) {
    // σa is not compared: the dual-scattering tables span every σa (shaders/lighting/luts.glsl).
    return a.eta == b.eta && a.alpha_R == b.alpha_R && a.alpha_TT == b.alpha_TT &&
           a.alpha_TRT == b.alpha_TRT && a.beta_R == b.beta_R && a.beta_TT == b.beta_TT && a.beta_TRT == b.beta_TRT &&
           a.ecc_a == b.ecc_a && a.w_c == b.w_c && a.delta_eta_p == b.delta_eta_p && a.d_b == b.d_b &&
           ca.segments == cb.segments && ca.paper_schlick == cb.paper_schlick && ca.paper_norm == cb.paper_norm &&
           ca.paper_theta_gauss == cb.paper_theta_gauss && ca.paper_tt == cb.paper_tt;
}

LightingTextures::LightingTextures() {
    const shading::LutSet set = shading::global_lighting_tables().set();
    for (int i = 0; i < shading::kLutCount; ++i)
        if (set.images[i]) luts_[i] = make_lut_texture(*set.images[i]);
}

bool LightingTextures::update(const shading::HairParams& hair, const shading::LightingConfig& config) {
    if (have_ms_ && same_lighting_tables(hair_, config_, hair, config)) return false;
    std::fprintf(stderr, "coif: building the dual-scattering tables of these hair parameters\n");
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
    const auto f = [&](const char* name, float v) { glUniform1f(program.uniform(name), v); };
    const auto i1 = [&](const char* name, int v) { glUniform1i(program.uniform(name), v); };
    f("u_hair.eta", hair.eta);
    glUniform3fv(program.uniform("u_hair.sigma_a"), 1, &hair.sigma_a.x);
    f("u_hair.alpha_R", hair.alpha_R);
    f("u_hair.alpha_TT", hair.alpha_TT);
    f("u_hair.alpha_TRT", hair.alpha_TRT);
    f("u_hair.beta_R", hair.beta_R);
    f("u_hair.beta_TT", hair.beta_TT);
    f("u_hair.beta_TRT", hair.beta_TRT);
    f("u_hair.ecc_a", hair.ecc_a);
    f("u_hair.w_c", hair.w_c);
    f("u_hair.delta_eta_p", hair.delta_eta_p);
    f("u_hair.d_b", hair.d_b);
    i1("u_config.segments", config.segments);
    i1("u_config.paper_schlick", config.paper_schlick);
    i1("u_config.paper_norm", config.paper_norm);
    i1("u_config.paper_theta_gauss", config.paper_theta_gauss);
    i1("u_config.paper_tt", config.paper_tt);
}

Buffer make_lights_buffer(std::span<const SrbfLight> lights) {
    struct GpuLight {  // std430 mirror of shaders/gl/srbf_lights.glsl
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
