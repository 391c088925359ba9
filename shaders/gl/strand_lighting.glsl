// The lit strand renderer's shading (online/strand_renderer.h), for its per-vertex lighting pass
// (strand_lighting.comp) and its per-fragment mode (strand_lines.frag with COIF_STRAND_PER_FRAGMENT):
// the SRBF Marschner lighting of an unoccluded round fibre (shaders/lighting/srbf_shadowed.glsl with
// T̃ = 1, n = 0),
//   L_o = Σ_j L_j (𝓜_j + d_b 𝓜^L_j)        (000 eq. 2 without D; the multiple term when u_multiple)
// in the frame u = tangent, v = the view direction projected orthogonal to u (φo = 0), w = u × v.
#ifndef COIF_SHADERS_GL_STRAND_LIGHTING_GLSL
#define COIF_SHADERS_GL_STRAND_LIGHTING_GLSL

#include "shaders/lighting/luts_gl.glsl"
#include "shaders/lighting/srbf_shadowed.glsl"

struct GpuLight {
    vec4 direction_lambda;  // xyz towards the light (unit), w = λ_j
    vec4 radiance;          // rgb = L_j
};
layout(std430, binding = 0) readonly buffer Lights { GpuLight lights[]; };

uniform int u_light_count;
uniform vec3 u_eye;
uniform HairParams u_hair;
uniform LightingConfig u_config;
uniform int u_lobes;     // bit 0 R, bit 1 TT, bit 2 TRT
uniform int u_multiple;  // the unoccluded fibre's multiple scattering on/off

vec3 strand_radiance(vec3 position, vec3 tangent) {
    vec3 u = normalize(tangent);
    vec3 V = normalize(u_eye - position);
    vec3 vp = V - dot(V, u) * u;
    if (dot(vp, vp) < 1e-12) vp = abs(u.x) < 0.9 ? vec3(1.0, 0.0, 0.0) - u.x * u : vec3(0.0, 1.0, 0.0) - u.y * u;
    vec3 v = normalize(vp);
    vec3 w = cross(u, v);
    float theta_o;
    float phi_o;
    hair_angles(V, u, v, w, theta_o, phi_o);
    vec4 f0123;
    vec4 f45;
    srbf_point_setup(u_hair, u_config, f0123, f45);
    vec3 L = vec3(0.0);
    for (int j = 0; j < u_light_count; ++j) {
        float lambda_j = lights[j].direction_lambda.w;
        float theta_j;
        float phi_j;
        hair_angles(lights[j].direction_lambda.xyz, u, v, w, theta_j, phi_j);
        vec3 m = srbf_single_lobes(u_hair, u_config, f0123, f45, u_lobes, theta_o, phi_o, theta_j, phi_j, lambda_j);
        if (u_multiple != 0)
            m += srbf_shadowed_multiple(u_hair, u_config, f0123, f45, MS_DEFAULT_D_F, theta_o, phi_o, theta_j, phi_j,
                                        lambda_j, 1.0, 0.0);
        L += lights[j].radiance.rgb * m;
    }
    return L;
}

#endif
