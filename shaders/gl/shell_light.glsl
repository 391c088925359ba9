// One SRBF light's weight at one point of a cluster, w_j = L_j (T̃_j 𝓜_j + multiple scattering)
// (shaders/gl/srbf_lights.glsl) with the shell renderer's shadows and painted σa, and the damping d_k of
// its Fourier harmonics. Written once for the lighting pass (shell_lighting.comp, per
// lighting sample on the cluster axis) and the per-fragment reference of decision 3 (shell_shade.glsl
// with SHELL_LIGHTING == 2), so the two differ only in where they are evaluated.
#ifndef COIF_SHADERS_GL_SHELL_LIGHT_GLSL
#define COIF_SHADERS_GL_SHELL_LIGHT_GLSL

#include "shaders/lighting/common.glsl"  // luminance
#include "shaders/gl/srbf_lights.glsl"
#include "shaders/gl/sector_frame.glsl"
#include "shaders/lighting/fibre_tangents.glsl"

// (T̃, n) per sample × light, then the own cluster's depth toward the hair's inside per sample (shell_shadow.comp
// inner_depth, as two vec2)
layout(std430, binding = 4) readonly buffer Shadows { vec2 shadows[]; };
#include "shaders/gl/inner_depths.glsl"

uniform int u_shadows;   // shadows between clusters on/off
uniform int u_shadow_samples;  // the lighting samples: where the inner depths start in `shadows`
uniform float u_own_inner;     // ShellSettings::own_cluster_inner
uniform int u_absorption_on;     // painted absorption (models/absorption_map.h) on/off
uniform sampler2D u_absorption;  // σa per lighting sample: texel (row, cluster), RGB32F
uniform float u_d_f;     // Zinke's forward density factor d_f

// The luminance of light j's radiance L_j (Rec. 709 weights, as the shadow AOV's).
float light_luminance(int j) { return luminance(lights[j].radiance.rgb); }

// Light j's shadow (T̃, n) at lighting sample i: the shadow pass's, or unoccluded (1, 0) with shadows off.
vec2 sample_shadow(int i, int j) { return u_shadows != 0 ? shadows[i * u_light_count + j] : vec2(1.0, 0.0); }

// The own cluster's fibres per cluster radius toward the hair's outside at lighting sample i, as a vector along that
// direction (shell_shadow.comp inner_depth), times ShellSettings::own_cluster_inner; 0 with shadows off, which make no
// grid.
vec3 sample_inner(int i) {
    if (u_shadows == 0 || u_own_inner <= 0.0) return vec3(0.0);
    return u_own_inner * inner_depth_read(inner_depth_at(u_shadow_samples, u_light_count, i));
}

// Light j's radiance at point p, shadowed by sh = (T̃, n); `lum_visible` adds lum(L_j) T̃_j and
// `lum_total` lum(L_j) (the shadow AOV).
vec3 shell_light_weight(SrbfPoint p, int j, vec2 sh, inout float lum_visible, inout float lum_total) {
    float lum = light_luminance(j);
    lum_visible += lum * sh.x;
    lum_total += lum;
    return srbf_light_radiance(p, u_d_f, j, sh);
}

// Light j's forward-scattered light at point p per unit of its share max(T_f − T̃, 0), for `fibres` met on the way
// (srbf_shadowed_multiple's second term, d_f included), and the fibres' forward loss 1 − ā_f at the light's angle: a key
// light (ShellSettings::key_lights) is shadowed per fragment, where T̃ and T_f = exp(−n (1 − ā_f)) are known.
vec3 shell_light_forward(SrbfPoint p, float d_f, int j, float fibres, out vec3 loss) {
    float lambda_j = lights[j].direction_lambda.w;
    float theta_j;
    float phi_j;
    hair_angles(lights[j].direction_lambda.xyz, p.T, p.r0, p.w, theta_j, phi_j);
    vec4 fw = fetch_ms_forward(theta_j, p.hp.sigma_a);
    loss = vec3(1.0) - fw.xyz;
    if (SRBF_MULTIPLE == 0) return vec3(0.0);
    return lights[j].radiance.rgb * (d_f * srbf_integral(lambda_j)) *
           srbf_forward_multiple(p.hp, SRBF_CONFIG, p.f0123, p.f45, p.theta_o, p.phi_o, theta_j, phi_j, lambda_j, fibres, fw);
}

// The fibres' tangents about the cluster's (shaders/lighting/fibre_tangents.glsl): SHELL_TANGENTS 4, the mean
// over the tilts m ± a, m ± b; 1, T itself. u_tangent_spread ≥ 0 (ShellSettings::tangent_spread given) makes
// them a ring of that RMS angle; < 0 takes the lighting samples' measured tilts (m, a, b).
#ifndef SHELL_TANGENTS
#define SHELL_TANGENTS 1
#endif
uniform float u_tangent_spread;  // σ, radians; < 0: measured

void shell_fibre_tilts(vec3 T, vec3 r0, vec3 V, inout vec3 m, inout vec3 a, inout vec3 b) {
    if (u_tangent_spread >= 0.0) {
        m = vec3(0.0);
        fibre_ring_axes(T, r0, V, u_tangent_spread, a, b);
    }
}

// Light j's weight at a fibre point (T, r0) seen along V, the mean over its fibres' tangents (tilts m, a, b).
vec3 shell_light_weight_fibres(HairParams hp, vec3 V, vec3 T, vec3 r0, vec3 m, vec3 a, vec3 b, int j, vec2 sh,
                               inout float lum_visible, inout float lum_total) {
    vec3 w = vec3(0.0);
    for (int q = 0; q < SHELL_TANGENTS; ++q) {
        vec3 Tq;
        vec3 rq;
        fibre_tangent_of(T, r0, m, a, b, q, SHELL_TANGENTS, Tq, rq);
        w += shell_light_weight(srbf_point(hp, V, Tq, rq), j, sh, lum_visible, lum_total);
    }
    return w * (1.0 / float(SHELL_TANGENTS));
}

// Light j's share in the lights' hot spot, max(0, l_j · v)^p (ShellSettings::hot_spot; v toward the camera): the part
// of it that the lighting pass and the per-fragment path light past the own cluster's factor.
float shell_hot_spot_share(int j, vec3 v, int p) {
    return pow(max(dot(normalize(lights[j].direction_lambda.xyz), v), 0.0), float(p));
}

// Light j's spread as an in-plane angle λ' (sector_frame.glsl light_spread).
float shell_light_spread(int j, vec3 T) { return light_spread(lights[j].direction_lambda.xyz, lights[j].direction_lambda.w, T); }

#endif
