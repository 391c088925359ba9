// One SRBF light's weight at one point of a cluster, w_j = L_j (T̃_j 𝓜_j + multiple scattering) of the
// SRBF Marschner lighting (shaders/lighting/srbf_shadowed.glsl: 000 eq. 2–5 in Zinke's split), and the
// damping d_k of its Fourier harmonics. Written once for the lighting pass (shell_lighting.comp, per
// lighting sample on the cluster axis) and the per-fragment reference of decision 3 (shell_shade.glsl
// with SHELL_LIGHTING == 2), so the two differ only in where they are evaluated.
#ifndef COIF_SHADERS_GL_SHELL_LIGHT_GLSL
#define COIF_SHADERS_GL_SHELL_LIGHT_GLSL

#include "shaders/lighting/luts_gl.glsl"
#include "shaders/lighting/srbf_shadowed.glsl"
#include "shaders/gl/sector_frame.glsl"

struct GpuLight {
    vec4 direction_lambda;  // xyz towards the light (unit), w = λ_j
    vec4 radiance;          // rgb = L_j
};
layout(std430, binding = 3) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = 4) readonly buffer Shadows { vec2 shadows[]; };  // (T̃, n) per sample × light

uniform int u_light_count;
uniform HairParams u_hair;
uniform LightingConfig u_config;
uniform int u_lobes;     // bit 0 R, bit 1 TT, bit 2 TRT
uniform int u_multiple;  // dual scattering on/off
uniform int u_shadows;   // shadows between clusters on/off
uniform int u_absorption_on;     // painted absorption (models/absorption_map.h) on/off
uniform sampler2D u_absorption;  // σa per lighting sample: texel (row, cluster), RGB32F
uniform float u_d_f;     // Zinke's forward density factor d_f

// The weight of light j at a point with hair angles (θo, φo) of the view in the frame (T, r0, w = T × r0),
// shadowed by sh = (T̃, n); `lum_visible` adds lum(L_j) T̃_j and `lum_total` lum(L_j) (the shadow AOV).
vec3 shell_light_weight(HairParams hp, vec4 f0123, vec4 f45, float theta_o, float phi_o, vec3 T, vec3 r0, vec3 w,
                        int j, vec2 sh, inout float lum_visible, inout float lum_total) {
    vec3 l = lights[j].direction_lambda.xyz;
    float lambda_j = lights[j].direction_lambda.w;
    float theta_j;
    float phi_j;
    hair_angles(l, T, r0, w, theta_j, phi_j);
    vec3 m = vec3(0.0);
    if (sh.x > MS_NEGLIGIBLE)
        m = sh.x * srbf_single_lobes(hp, u_config, f0123, f45, u_lobes, theta_o, phi_o, theta_j, phi_j, lambda_j);
    if (u_multiple != 0)
        m += srbf_shadowed_multiple(hp, u_config, f0123, f45, u_d_f, theta_o, phi_o, theta_j, phi_j, lambda_j, sh.x, sh.y);
    float lum = dot(lights[j].radiance.rgb, vec3(0.2126, 0.7152, 0.0722));
    lum_visible += lum * sh.x;
    lum_total += lum;
    return lights[j].radiance.rgb * m;
}

// λ' = λ_j over the length of the light direction projected on the normal plane of T: the light's
// spread as an in-plane angle; harmonic k of the light's azimuth is damped by d_k = exp(−k² λ'² / 4)
// (the Fourier coefficient of a circular Gaussian of bandwidth λ' for small λ').
float shell_light_spread(int j, vec3 T) {
    vec3 l = lights[j].direction_lambda.xyz;
    float proj = length(l - dot(l, T) * T);
    return lights[j].direction_lambda.w / max(proj, 1e-3);
}

#endif
