#pragma once
// Compiles GLSL sources of shaders/ as C++ (the one source of truth for shared math, DESIGN.md).
//
// Usage in C++:   namespace coif::glsl {
//                 #include "shaders/envmap.glsl"
//                 }
// after including this header. GLM mirrors GLSL's types and built-ins (vec3, dot, normalize, mix,
// clamp, exp, inversesqrt, ...). Rules for GLSL that must also compile as C++:
//   - include-guard every file with #ifndef/#define/#endif (both preprocessors accept it);
//   - write float literals with a digit after the point (1.0, not 1.) and no 'f' suffix;
//   - no swizzles beyond single components (.x .y .z .w); build vectors with constructors;
//   - out/inout parameters are written OUT(type) / INOUT(type) (a reference in C++);
//   - constants as `const float NAME = ...;` at file scope;
//   - functions that a C++ caller uses must not rely on GLSL-only built-ins (texture(), dFdx, ...):
//     keep those in GL-only files under shaders/gl/.
// In GLSL the same macros come from shaders/gl/prelude.glsl, which online/ prepends to every program.
#include <cmath>
#include <glm/glm.hpp>

#define OUT(type) type&
#define INOUT(type) type&

namespace coif::glsl {
using namespace glm;
using uint = unsigned int;
}  // namespace coif::glsl

// ---- Extensions for the SRBF lighting (shaders/lighting/, issue 6) ----
//
// COIF_FN: put before every function of a shared .glsl file. In C++ the functions live in headers
// included by several translation units, so they must be `inline`; GLSL has no `inline`, and there
// the macro is empty (shaders/lighting/common.glsl defines it when the C++ prelude has not).
#define COIF_FN inline

// Table look-ups. Shared GLSL fetches a precomputed table with COIF_LUT(name, uv) (bilinear,
// clamp-to-edge, uv in [0,1]², texel centres at (i + 0.5)/n, exactly as GL_LINEAR does). In GL the
// name is a `uniform sampler2D` (shaders/lighting/luts_gl.glsl); in C++ it is a CPU table bound to the
// calling thread (shaders/lut.h, coif::shading::LutBinding). Same GLSL, two back ends.
#include "shaders/lut.h"
#define COIF_LUT(name, uv) ::coif::shading::lut_fetch(::coif::shading::Lut::name, uv)

// GLSL writes float literals without a suffix (1.0), which C++ reads as double. GLM's templates do
// not mix float and double, so `max(x, 0.0)` or `v * 2.0` would not compile; these overloads make
// the mixed forms mean what GLSL means (float arithmetic).
namespace coif::glsl {
// The using-declarations keep GLM's own overloads visible beside the mixed ones declared here.
using glm::atan;
using glm::clamp;
using glm::max;
using glm::min;
using glm::mix;
using glm::mod;
using glm::pow;
using glm::smoothstep;
using glm::step;
#define COIF_GLSL_MIXED2(fn)                                                          \
    inline float fn(float a, double b) { return glm::fn(a, float(b)); }              \
    inline float fn(double a, float b) { return glm::fn(float(a), b); }              \
    inline vec2 fn(const vec2& a, double b) { return glm::fn(a, float(b)); }         \
    inline vec3 fn(const vec3& a, double b) { return glm::fn(a, float(b)); }         \
    inline vec4 fn(const vec4& a, double b) { return glm::fn(a, float(b)); }
COIF_GLSL_MIXED2(max)
COIF_GLSL_MIXED2(min)
COIF_GLSL_MIXED2(mod)
#undef COIF_GLSL_MIXED2
inline float pow(float a, double b) { return std::pow(a, float(b)); }
inline float atan(float y, double x) { return std::atan2(y, float(x)); }
inline float atan(double y, float x) { return std::atan2(float(y), x); }
inline float clamp(float x, double lo, double hi) { return glm::clamp(x, float(lo), float(hi)); }
inline vec3 clamp(const vec3& x, double lo, double hi) { return glm::clamp(x, float(lo), float(hi)); }
inline float mix(float a, double b, float t) { return glm::mix(a, float(b), t); }
inline float mix(double a, float b, float t) { return glm::mix(float(a), b, t); }
inline float mix(float a, float b, double t) { return glm::mix(a, b, float(t)); }
inline float smoothstep(double e0, double e1, float x) { return glm::smoothstep(float(e0), float(e1), x); }
inline float smoothstep(float e0, double e1, float x) { return glm::smoothstep(e0, float(e1), x); }
inline float step(double edge, float x) { return glm::step(float(edge), x); }
#define COIF_GLSL_MIXED_OP(op)                                                                          \
    inline vec2 operator op(const vec2& a, double b) { return a op float(b); }                          \
    inline vec3 operator op(const vec3& a, double b) { return a op float(b); }                          \
    inline vec4 operator op(const vec4& a, double b) { return a op float(b); }                          \
    inline vec2 operator op(double a, const vec2& b) { return float(a) op b; }                          \
    inline vec3 operator op(double a, const vec3& b) { return float(a) op b; }                          \
    inline vec4 operator op(double a, const vec4& b) { return float(a) op b; }
COIF_GLSL_MIXED_OP(+)
COIF_GLSL_MIXED_OP(-)
COIF_GLSL_MIXED_OP(*)
COIF_GLSL_MIXED_OP(/)
#undef COIF_GLSL_MIXED_OP
}  // namespace coif::glsl
