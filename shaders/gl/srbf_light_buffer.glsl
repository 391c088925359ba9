// The SRBF lights as a GL program reads them: storage binding 3, written by online/lighting_uniforms.cpp
// make_lights_buffer (its std430 mirror), with u_light_count of them.
#ifndef COIF_SHADERS_GL_SRBF_LIGHT_BUFFER_GLSL
#define COIF_SHADERS_GL_SRBF_LIGHT_BUFFER_GLSL

struct GpuLight {
    vec4 direction_lambda;  // xyz towards the light (unit), w = λ_j
    vec4 radiance;          // rgb = L_j
};
layout(std430, binding = 3) readonly buffer Lights { GpuLight lights[]; };

uniform int u_light_count;

#endif  // COIF_SHADERS_GL_SRBF_LIGHT_BUFFER_GLSL
