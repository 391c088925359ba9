// GL side of the table look-ups (GL only: never compiled as C++). Include it before any shared
// lighting file in a GL program. Each table is a GL_RGBA32F texture with GL_LINEAR filtering and
// GL_CLAMP_TO_EDGE wrapping, computed by coif::shading::LightingTables (shaders/lighting_tables.h)
// and bound to the sampler of the same name (the C++ back end is shaders/lut.h).
#ifndef COIF_SHADERS_LIGHTING_LUTS_GL_GLSL
#define COIF_SHADERS_LIGHTING_LUTS_GL_GLSL

#define COIF_FN
#define COIF_LUT(name, uv) textureLod(name, uv, 0.0)

uniform sampler2D lut_ck_lo;
uniform sampler2D lut_ck_hi;
uniform sampler2D lut_h_tt;
uniform sampler2D lut_h_trt;
uniform sampler2D lut_half_mass;
uniform sampler2D lut_fresnel_fit;
uniform sampler2D lut_own_cluster;
uniform sampler2D lut_ms_ab;
uniform sampler2D lut_ms_sat_delta;
uniform sampler2D lut_ms_sat_sigma;
uniform sampler2D lut_ms_af;

#endif
