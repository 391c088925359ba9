// One fragment of a SATF layer mesh (004 §6.2–6.5) lit by the SRBF Marschner lighting (000), see
// online/shell_renderer.h for what each input holds and docs/renderer.md for the choices.
//
//   re/α     the HSV's two boundary sectors β⊤ (i) and β⊥ (i+1) each blend their nearest database
//            records (ids and weights from the FLANN look-up, once per hairstyle); each record is
//            read at (x, θv) with one bilinear fetch per 4 channels from the record atlas (x along the
//            HRIR, θv between the two nearest views; both periodic); the two sectors are mixed by
//            γ = the fragment's position along t across the HSV (004 eq. 7).
//   lighting Σ_j w_j re(x, θv, θl_j) in the Fourier form of DESIGN.md decision 1: the lighting pass
//            (shell_lighting.comp) stores C_k, S_k per lighting sample in a frame (r0, T × r0) fixed
//            to the cluster axis; here they are turned to the fragment's radial axis (angle ψr).
//   shadow   004 eq. 12: τ = exp(−κ_shadow Σ_{outer layers} ᾱ) with ᾱ each outer sector's mean α.
//   output   premultiplied: re already carries the coverage (planar tracer, 004 eq. 5), so the
//            colour is lighting · re / re_norm · τ and the blend is (ONE, ONE_MINUS_SRC_ALPHA).
#include "shaders/gl/sector_frame.glsl"

in vec3 v_position;
in vec3 v_tangent;
in vec3 v_normal;
in vec3 v_axis_normal;
in vec2 v_texcoord;
flat in uvec2 v_info;

struct ShellSector {
    uvec4 id;      // nearest records, best first
    vec4 weight;   // their weights (renormalised here over the first u_neighbours)
    vec4 shadow;   // x: Σ of the mean α of the outer sectors at the same (i, k)
};
layout(std430, binding = 1) readonly buffer Sectors { ShellSector sectors[]; };

uniform sampler2D u_records;       // record atlas (RGBA16F): per record 3 tiles of views × X texels + 1 border
uniform int u_tiles_per_row;
uniform vec2 u_atlas_inv_size;
uniform int u_views;
uniform int u_hrir_length;
uniform sampler2D u_lighting;      // C_k, S_k per lighting sample: x = row along t, y = cluster · 7 + texel
uniform int u_lighting_rows;
uniform int u_lighting_height;
uniform int u_s_t;
uniform int u_s_u;
uniform int u_layers;
uniform int u_layer;
uniform int u_neighbours;
uniform float u_kappa_shadow;
uniform float u_re_scale;          // 1 / re_norm
uniform vec3 u_eye;
uniform int u_debug;               // 0 shaded, 1 α only, 2 unlit re·τ, 3 lighting C_0·α·τ (no re)

layout(location = 0) out vec4 o_color;

const float TWO_PI = 6.28318530718;

vec4 atlas_fetch(uint tile, vec2 p) {
    uint tx = tile % uint(u_tiles_per_row);
    uint ty = tile / uint(u_tiles_per_row);
    vec2 origin = vec2(float(tx) * float(u_hrir_length + 2), float(ty) * float(u_views + 2)) + 1.0;
    return textureLod(u_records, (origin + p) * u_atlas_inv_size, 0.0);
}

// α and the 9 re coefficients (a0, a1, b1, …, a4, b4) of one sector at atlas position p.
void sector_values(uint sector, vec2 p, out float alpha, out float c[9]) {
    ShellSector s = sectors[sector];
    alpha = 0.0;
    for (int q = 0; q < 9; ++q) c[q] = 0.0;
    float wsum = 0.0;
    for (int n = 0; n < u_neighbours; ++n) {
        float w = s.weight[n];
        uint base = s.id[n] * 3u;
        vec4 t0 = atlas_fetch(base, p);
        vec4 t1 = atlas_fetch(base + 1u, p);
        vec4 t2 = atlas_fetch(base + 2u, p);
        alpha += w * t0.x;
        c[0] += w * t0.y; c[1] += w * t0.z; c[2] += w * t0.w;
        c[3] += w * t1.x; c[4] += w * t1.y; c[5] += w * t1.z; c[6] += w * t1.w;
        c[7] += w * t2.x; c[8] += w * t2.y;
        wsum += w;
    }
    float inv = wsum > 0.0 ? 1.0 / wsum : 0.0;
    alpha *= inv;
    for (int q = 0; q < 9; ++q) c[q] *= inv;
}

void main() {
    vec3 T = normalize(v_tangent);
    vec3 r = sector_radial(normalize(v_normal), T);
    vec3 V = normalize(u_eye - v_position);
    float theta_v = sector_azimuth(V, T, r);

    // HSV (i, j, k) and the position inside it.
    float tt = clamp(v_texcoord.y, 0.0, 1.0) * float(u_s_t);
    int i = min(int(tt), u_s_t - 1);
    float gamma = tt - float(i);
    float uu = fract(v_texcoord.x) * float(u_s_u);
    int k = min(int(uu), u_s_u - 1);
    float x = uu - float(k);
    uint base = v_info.x;
    uint top = base + uint((i * u_layers + u_layer) * u_s_u + k);
    uint bottom = top + uint(u_layers * u_s_u);

    float view = theta_v / TWO_PI * float(u_views);
    view = mod(view, float(u_views));
    vec2 p = vec2(x * float(u_hrir_length), view + 0.5);
    float a_top, a_bottom;
    float c_top[9];
    float c_bottom[9];
    sector_values(top, p, a_top, c_top);
    sector_values(bottom, p, a_bottom, c_bottom);
    float alpha = clamp(mix(a_top, a_bottom, gamma), 0.0, 1.0);
    float c[9];
    for (int q = 0; q < 9; ++q) c[q] = mix(c_top[q], c_bottom[q], gamma);
    float tau = exp(-u_kappa_shadow * mix(sectors[top].shadow.x, sectors[bottom].shadow.x, gamma));

    if (u_debug == 1) { o_color = vec4(vec3(alpha), alpha); return; }
    if (u_debug == 2) { o_color = vec4(vec3(max(c[0], 0.0) * u_re_scale * tau), alpha); return; }

    // Lighting coefficients at this t (linear between lighting rows), turned to this fragment's r.
    float lx = (clamp(v_texcoord.y, 0.0, 1.0) * float(u_lighting_rows - 1) + 0.5) / float(u_lighting_rows);
    float ly0 = float(v_info.y * 7u) + 0.5;
    float L[28];
    for (int m = 0; m < 7; ++m) {
        vec4 q = textureLod(u_lighting, vec2(lx, (ly0 + float(m)) / float(u_lighting_height)), 0.0);
        L[4 * m] = q.x; L[4 * m + 1] = q.y; L[4 * m + 2] = q.z; L[4 * m + 3] = q.w;
    }
    vec3 r0 = v_axis_normal - dot(v_axis_normal, T) * T;
    float psi_r = sector_azimuth(r, T, normalize(r0));
    if (u_debug == 3) { o_color = vec4(vec3(L[0], L[1], L[2]) * alpha * tau, alpha); return; }
    vec3 sum = c[0] * vec3(L[0], L[1], L[2]);
    for (int h = 1; h <= 4; ++h) {
        int o = 3 + 6 * (h - 1);
        vec3 C = vec3(L[o], L[o + 1], L[o + 2]);
        vec3 S = vec3(L[o + 3], L[o + 4], L[o + 5]);
        float ch = cos(float(h) * psi_r);
        float sh = sin(float(h) * psi_r);
        vec3 Cr = C * ch + S * sh;  // Σ w_j cos h(ψj − ψr)
        vec3 Sr = S * ch - C * sh;  // Σ w_j sin h(ψj − ψr)
        sum += c[2 * h - 1] * Cr + c[2 * h] * Sr;
    }
    o_color = vec4(max(sum, vec3(0.0)) * u_re_scale * tau, alpha);
}
