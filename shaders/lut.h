#pragma once
// CPU back end of the table look-ups used by the shared GLSL (COIF_LUT in shaders/glsl_prelude.h).
//
// A look-up table is an RGBA float image sampled exactly as OpenGL samples a GL_RGBA32F texture with
// GL_LINEAR filtering and GL_CLAMP_TO_EDGE wrapping: texel (i, j) has its centre at
// uv = ((i + 0.5) / width, (j + 0.5) / height), row j = 0 first. The shared GLSL names a table by
// the name of its GL sampler uniform (enum Lut below); C++ code binds a LutSet to the calling thread
// with LutBinding before calling the shared functions, which keeps the GLSL free of C++ plumbing
// and lets several threads shade with different tables at once.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace coif::shading {

// One entry per `uniform sampler2D` of shaders/lighting/luts_gl.glsl, same names.
enum class Lut : int {
    lut_ck_lo,         // 000 eq. 14 C_k for k = 0..3, normalised by ∫g^c (x: φ difference, y: log λ')
    lut_ck_hi,         // C_k for k = 4..6
    lut_h_tt,          // 000 eq. 19 H_k^TT, k = 0, 2, 4 (x: θd, y: log η)
    lut_h_trt,         // 000 eq. 23 H_k^TRT
    lut_half_mass,     // share of a circular Gaussian inside a half circle (000 eq. 28)
    lut_fresnel_fit,   // polynomial fit of the exact Fresnel term in cos(incidence), per η
    lut_own_cluster,   // the own cluster's transmittance O(Δ) as cosine harmonics over (τ, ρ) (own_cluster.glsl)
    lut_ms_ab,         // Zinke's Ā_b(θd, σa) for one parameter set (000 eq. 29), one channel
    lut_ms_sat_delta,  // summed-area table of Δ̄_b(θd, σa) over θd (000 eq. 31)
    lut_ms_sat_sigma,  // summed-area table of σ̄_b(θd, σa)
    lut_ms_af,         // forward scattering through one fibre: ā_f(θd, σa) in x, β̄_f² in y (shadow paths)
    count
};
inline constexpr int kLutCount = static_cast<int>(Lut::count);

struct LutImage {
    int width = 0, height = 0;
    std::vector<glm::vec4> texels;  // row-major, width * height

    LutImage() = default;
    LutImage(int w, int h) : width(w), height(h), texels(static_cast<size_t>(w) * h, glm::vec4(0.0f)) {}
    glm::vec4& at(int x, int y) { return texels[static_cast<size_t>(y) * width + x]; }
    const glm::vec4& at(int x, int y) const { return texels[static_cast<size_t>(y) * width + x]; }
    // GL_LINEAR + GL_CLAMP_TO_EDGE.
    glm::vec4 sample(glm::vec2 uv) const;
};

// Which image backs each name; null entries are unbound (a fetch from one returns 0 and counts a miss).
struct LutSet {
    std::array<const LutImage*, kLutCount> images{};
};

// Binds `set` (merged over the currently bound set: its non-null entries win) to this thread for
// the lifetime of the object.
class LutBinding {
public:
    explicit LutBinding(const LutSet& set);
    ~LutBinding();
    LutBinding(const LutBinding&) = delete;
    LutBinding& operator=(const LutBinding&) = delete;

private:
    LutSet merged_;
    const LutSet* previous_;
};

glm::vec4 lut_fetch(Lut id, glm::vec2 uv);

// Number of lut_fetch calls made by this thread so far (the cost count of `coif bench lighting`).
std::uint64_t lut_fetch_count();

}  // namespace coif::shading
