// The SRBF lights of a GL program and one light's radiance at a fibre point, written once for the shell
// renderer's lighting pass and per-fragment reference (shell_light.glsl) and the lit strand renderer
// (strand_lighting.glsl): L_j (T̃_j 𝓜_j + multiple scattering) of shaders/lighting/srbf_shadowed.glsl
// (000 eq. 2–5 in Zinke's split). The program binds its lights at storage binding 3.
#ifndef COIF_SHADERS_GL_SRBF_LIGHTS_GLSL
#define COIF_SHADERS_GL_SRBF_LIGHTS_GLSL

#include "shaders/lighting/luts_gl.glsl"
#include "shaders/lighting/srbf_shadowed.glsl"
#include "shaders/gl/srbf_light_buffer.glsl"
uniform HairParams u_hair;
// The lighting configuration, the lobes drawn (bit 0 R, bit 1 TT, bit 2 TRT) and dual scattering on/off: compile-time
// constants when the program is built with online/lighting_uniforms.h srbf_variant_defines (the compiler then drops
// what they switch off and unrolls the quadrature: the default scene's lighting pass took 453 ms with uniforms, 425
// as constants), else uniforms set by set_lighting_uniforms (the strand renderer).
#ifndef SRBF_CONFIG
uniform LightingConfig u_config;
uniform int u_lobes;
uniform int u_multiple;
#define SRBF_CONFIG u_config
#define SRBF_LOBES u_lobes
#define SRBF_MULTIPLE u_multiple
#endif

// A fibre point seen along V: its frame (T, r0, w = T × r0), the view's hair angles in it and the
// parameter setup of the SRBF lobes, made once per point by srbf_point().
struct SrbfPoint {
    HairParams hp;
    vec3 T, r0, w;
    float theta_o, phi_o;
    vec4 f0123, f45;
};
SrbfPoint srbf_point(HairParams hp, vec3 V, vec3 T, vec3 r0) {
    SrbfPoint p;
    p.hp = hp;
    p.T = T;
    p.r0 = r0;
    p.w = cross(T, r0);
    hair_angles(V, T, r0, p.w, p.theta_o, p.phi_o);
    srbf_point_setup(hp, SRBF_CONFIG, p.f0123, p.f45);
    return p;
}

// Light j's radiance at point p, shadowed by sh = (T̃, n) (unoccluded: (1, 0)), with Zinke's forward
// density factor d_f.
vec3 srbf_light_radiance(SrbfPoint p, float d_f, int j, vec2 sh) {
    float lambda_j = lights[j].direction_lambda.w;
    float theta_j;
    float phi_j;
    hair_angles(lights[j].direction_lambda.xyz, p.T, p.r0, p.w, theta_j, phi_j);
    vec3 m = vec3(0.0);
    if (sh.x > MS_NEGLIGIBLE)
        m = sh.x * srbf_single_lobes(p.hp, SRBF_CONFIG, p.f0123, p.f45, SRBF_LOBES, p.theta_o, p.phi_o, theta_j, phi_j, lambda_j);
    if (SRBF_MULTIPLE != 0)
        m += srbf_shadowed_multiple(p.hp, SRBF_CONFIG, p.f0123, p.f45, d_f, p.theta_o, p.phi_o, theta_j, phi_j, lambda_j,
                                    sh.x, sh.y);
    return lights[j].radiance.rgb * m;
}

#endif
