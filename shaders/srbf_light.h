#pragma once
// One SRBF light: a spherical Gaussian L_j G(ω; ω_j, λ_j) of an environment fitted as SRBF lights,
// G(ω; ω_j, λ_j) = exp(2(ω·ω_j − 1)/λ_j²) (000 eq. 1 and Table 1; shaders/envmap.glsl srbf_G). The one
// light type of coif: the fit and its file (offline/srbf_lights.h), the CPU lighting evaluator
// (shaders/lighting.h) and the GL renderers (online/lighting_uniforms.h) all take it.
#include <glm/glm.hpp>

namespace coif {

struct SrbfLight {
    glm::vec3 L{0.0f};                 // RGB coefficient L_j, linear radiance
    glm::vec3 omega{0.0f, 1.0f, 0.0f}; // centre ω_j: unit world direction towards the light (y up)
    float lambda = 1.0f;               // bandwidth λ_j (radians-like; NOT a standard deviation)

    bool operator==(const SrbfLight&) const = default;
};

}  // namespace coif
