#include "shaders/lighting.h"

#include <cmath>
#include <sstream>

#include "models/core/error.h"
#include "models/core/units.h"
#include "shaders/hair_parameters.h"

namespace coif::shading {

namespace {

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

void check_range(const std::string& place, const char* name, float v, float lo, float hi, bool lo_exclusive,
                 const char* unit) {
    const bool ok = std::isfinite(v) && (lo_exclusive ? v > lo : v >= lo) && v <= hi;
    if (!ok)
        throw Error::parameter(place, std::string(name) + " = " + fmt(v) + " is outside the accepted range " +
                                          (lo_exclusive ? "(" : "[") + fmt(lo) + ", " + fmt(hi) + "] " + unit);
}

}  // namespace

HairParams default_hair_params() {
    return linked_hair_params(1.55f, glm::vec3(0.432f, 0.612f, 0.98f), radians(-7.5f), radians(7.5f), 1.0f, 0.15f);
}

HairParams linked_hair_params(float eta, glm::vec3 sigma_a, float alpha_R, float beta_R, float ecc_a, float w_c) {
    HairParams p{};
    p.eta = eta;
    p.sigma_a = sigma_a;
    p.alpha_R = alpha_R;
    p.beta_R = beta_R;
    link_lobes_to_R(p);
    p.ecc_a = ecc_a;
    p.w_c = w_c;
    p.delta_eta_p = 0.3f;
    p.d_b = glsl::MS_DEFAULT_D_B;
    p.longitudinal = 0.0f;  // energy-conserving
    return p;
}

void link_lobes_to_R(HairParams& p) {
    p.alpha_TT = -0.5f * p.alpha_R;
    p.alpha_TRT = -1.5f * p.alpha_R;
    p.beta_TT = 0.5f * p.beta_R;
    p.beta_TRT = 2.0f * p.beta_R;
}

void validate(const HairParams& p, const std::string& place) {
    // Every field of the one list (shaders/hair_parameters.h kHairParamsFields), in its order.
    static constexpr const char* channel[3] = {".r", ".g", ".b"};
    for (const HairParamsField& f : kHairParamsFields) {
        if (const auto* m = std::get_if<float HairParams::*>(&f.member))
            check_range(place, f.label, p.*(*m), f.lo, f.hi, f.lo_exclusive, f.unit);
        else
            for (int c = 0; c < 3; ++c)
                check_range(place, (std::string(f.label) + channel[c]).c_str(), (p.*std::get<glm::vec3 HairParams::*>(f.member))[c],
                            f.lo, f.hi, f.lo_exclusive, f.unit);
    }
}

void validate(const LightingConfig& c, const std::string& place) {
    if (c.segments < 2 || c.segments > glsl::LIGHTING_MAX_SEGMENTS)
        throw Error::parameter(place, "segments m = " + std::to_string(c.segments) + " is outside [2, " +
                                          std::to_string(glsl::LIGHTING_MAX_SEGMENTS) + "]");
}

void validate_light(float lambda_j, glm::vec3 direction, const std::string& place) {
    check_range(place, "lambda (SRBF bandwidth)", lambda_j, kMinLambda, kMaxLambda, false, "rad");
    const float len = glm::length(direction);
    if (!std::isfinite(len) || len < 1e-6f)
        throw Error::parameter(place, "direction must be a finite non-zero vector");
}

LightingConfig default_config(int segments) {
    LightingConfig c{};
    c.segments = segments;
    c.paper_schlick = false;
    c.paper_norm = false;
    c.paper_theta_gauss = false;
    c.paper_tt = false;
    return c;
}

LightingConfig paper_config(int segments) {
    LightingConfig c = default_config(segments);
    c.paper_schlick = true;
    c.paper_norm = true;
    c.paper_theta_gauss = true;
    c.paper_tt = true;
    return c;
}

FibreFrame FibreFrame::from_tangent(glm::vec3 tangent, glm::vec3 normal_hint) {
    FibreFrame f;
    f.u = glm::normalize(tangent);
    glm::vec3 v = normal_hint - glm::dot(normal_hint, f.u) * f.u;
    if (glm::length(v) < 1e-6f) {
        const glm::vec3 axis = std::abs(f.u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        v = axis - glm::dot(axis, f.u) * f.u;
    }
    f.v = glm::normalize(v);
    f.w = glm::cross(f.u, f.v);
    return f;
}

LightingEvaluator::LightingEvaluator(const HairParams& params, const LightingConfig& config)
    : params_(params), config_(config) {
    validate(params_);
    validate(config_);
    ms_ = build_ms_tables(params_, config_);
    lut_set_ = global_lighting_tables().set();
    const LutSet ms = ms_.set();
    for (int i = 0; i < kLutCount; ++i)
        if (ms.images[i]) lut_set_.images[i] = ms.images[i];
    LutBinding b(lut_set_);
    glsl::srbf_point_setup(params_, config_, f0123_, f45_);
}

glm::vec3 LightingEvaluator::single(float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j) const {
    LutBinding b(lut_set_);
    return glsl::srbf_single(params_, config_, f0123_, f45_, theta_o, phi_o, theta_j, phi_j, lambda_j);
}

glm::vec3 LightingEvaluator::single_lobe(int lobe, float theta_o, float phi_o, float theta_j, float phi_j,
                                         float lambda_j) const {
    LutBinding b(lut_set_);
    return glsl::srbf_single_lobe(lobe, params_, config_, f0123_, f45_, theta_o, phi_o, theta_j, phi_j, lambda_j);
}

glm::vec3 LightingEvaluator::multiple(float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j,
                                      float sigma_f2) const {
    LutBinding b(lut_set_);
    return glsl::srbf_multiple(params_, config_, f0123_, f45_, theta_o, phi_o, theta_j, phi_j, lambda_j, sigma_f2);
}

glm::vec3 LightingEvaluator::ms_global(float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j,
                                       float sigma_f2) const {
    LutBinding b(lut_set_);
    const float lambda_f = glsl::ms_lambda_f(lambda_j, sigma_f2);
    glm::vec3 r(0.0f);
    for (int lobe = 0; lobe < kLobeCount; ++lobe)
        r += glsl::srbf_ms_global_lobe(lobe, params_, config_, f0123_, f45_, theta_o, phi_o, theta_j, phi_j, lambda_f);
    return r;
}

glm::vec3 LightingEvaluator::ms_local(float theta_o, float phi_o, float theta_j, float phi_j, float lambda_j,
                                      float sigma_f2) const {
    LutBinding b(lut_set_);
    return glsl::srbf_ms_local(params_, config_, theta_o, phi_o, theta_j, phi_j, glsl::ms_lambda_f(lambda_j, sigma_f2));
}

PointLighting LightingEvaluator::shade(const FibreFrame& frame, glm::vec3 view, std::span<const SrbfLight> lights,
                                       std::span<const LightShadow> shadows, bool multiple, float d_f) const {
    if (!shadows.empty() && shadows.size() != lights.size())
        throw Error::parameter("LightingEvaluator::shade", "shadows must be empty or have one entry per light");
    if (!(d_f >= 0.0f && d_f <= 1.0f)) throw Error::parameter("d_f", "must be in [0, 1]");
    for (const LightShadow& s : shadows)
        if (!(s.direct >= 0.0f && s.direct <= 1.0f) || !(s.fibres >= 0.0f && std::isfinite(s.fibres)))
            throw Error::parameter("LightingEvaluator::shade", "a shadow needs direct in [0, 1] and finite fibres >= 0");
    LutBinding b(lut_set_);
    float theta_o, phi_o;
    glsl::hair_angles(glm::normalize(view), frame.u, frame.v, frame.w, theta_o, phi_o);
    PointLighting out;
    for (size_t j = 0; j < lights.size(); ++j) {
        const SrbfLight& light = lights[j];
        const LightShadow shadow = shadows.empty() ? LightShadow{} : shadows[j];
        float theta_j, phi_j;
        glsl::hair_angles(glm::normalize(light.omega), frame.u, frame.v, frame.w, theta_j, phi_j);
        out.single += light.L * shadow.direct *
                      glsl::srbf_single(params_, config_, f0123_, f45_, theta_o, phi_o, theta_j, phi_j, light.lambda);
        if (multiple)
            out.multiple += light.L * glsl::srbf_shadowed_multiple(params_, config_, f0123_, f45_, d_f, theta_o,
                                                                          phi_o, theta_j, phi_j, light.lambda,
                                                                          shadow.direct, shadow.fibres);
    }
    return out;
}

}  // namespace coif::shading
