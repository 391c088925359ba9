// The shading of one fragment of a SATF layer mesh (004 §6.2–6.5) lit by the SRBF Marschner lighting
// (000), see online/shell_renderer.h for what each input holds and docs/renderer.md for the choices.
//
//   re/α     the HSV's two boundary sectors β⊤ (i) and β⊥ (i+1) each blend their nearest database
//            records (ids and weights from the FLANN look-up, once per hairstyle); each record is
//            read at (x, θv) with one bilinear fetch per 4 channels from the RGBA8 record atlas (x along the
//            HRIR, θv between the two nearest views; both periodic); the two sectors are mixed by
//            γ = the fragment's position along t across the HSV (004 eq. 7).
//   lighting Σ_j w_j re(x, θv, θl_j) in the Fourier form of DESIGN.md decision 1: the lighting pass
//            (shell_lighting.comp) stores C_k, S_k per lighting sample in a frame (r0, T × r0) fixed
//            to the cluster axis; here they are turned to the fragment's radial axis (angle ψr).
//   shadow   004 eq. 12: τ = exp(−κ_shadow Σ_{outer layers} ᾱ) with ᾱ each outer sector's mean α; and with
//            SHELL_OWN, the own cluster's shadow by the fragment's side toward each light
//            (shaders/lighting/own_cluster.glsl): re(θl) becomes re(θl) · exp(−τ s(ρ, θl)), ρ this layer
//            mesh's surface, τ = κ_shadow Σ ᾱ of every layer at (i, k) lengthened by the lights' angles to the
//            axis (texel 7 of the lighting sums; per light in SHELL_LIGHTING 2); eq. 12 is then off.
//   output   premultiplied: re already carries the coverage (planar tracer, 004 eq. 5), so the
//            colour is lighting · re / re_norm · τ and the blend is (ONE, ONE_MINUS_SRC_ALPHA).
//
// Compile-time variants (online/shell_passes.cpp ShellsPass builds one program per set; llvmpipe runs every
// branch of a shader under masks, so a uniform switch costs its whole code in every fragment):
//   SHELL_NEIGHBOURS  records blended per sector, 1..4
//   SHELL_LIGHTING    0: the lighting sums fetched per fragment (any number of lighting rows);
//                     1: fetched per vertex by shell.vert and interpolated (rows = mesh rows; the same values);
//                     2: the per-fragment, per-light reference of decision 3: every light's weight evaluated
//                        at this fragment (its own T, V and radial axis; T̃, n interpolated between the
//                        lighting samples along t) times re at that light's own azimuth
//   SHELL_DEBUG       0 shaded, 1 α only, 2 unlit re·τ, 3 lighting C_0·α·τ (no re), 4 the shadow AOV, 5 key light 0's
//                     transmittance over the slab · α, 6 shaded with the key lights unshadowed (key_light_volume.glsl)
//   SHELL_FOURIER     harmonics of re in θl used, 0..4 (the database stores 4): 0 and 1 read one atlas tile per
//                     record, 2 and 3 two, 4 all three; the dropped ones are zero (0: re = a0, the same for every
//                     light azimuth)
//   SHELL_OWN         1: the own cluster's shadow per fragment (ShellSettings::own_cluster_shadow), 0: none;
//                     2: as 1 with the light its fibres scatter forward (ShellSettings::own_cluster_forward)
//   SHELL_TANGENTS    with SHELL_LIGHTING 2: the fibres' tangents each light is evaluated at (shell_light.glsl)
//   SHELL_FOLD        1: two layers from the outer one's mesh (ShellSettings::fold_level, shell_shade_pair below)
//   SHELL_TILT_PICK   1: each strip of a sector lit as one fibre at one of the four fibre tangents (ShellSettings::
//                     tilt_per_strip, fibre_strip_tangent below); 0: every fibre at the four tangents' mean
//   SHELL_SECTOR_PICK 1: each strip takes the records of one of its HSV's two sectors, drawn against γ
//                     (ShellSettings::sector_per_strip); 0: both sectors' records mixed by γ (004 eq. 7)
//   SHELL_KEY_LIGHTS  K > 0: the key lights (ShellSettings::key_lights), left out of the lighting sums, each lit here
//                     with the fibres met toward it (its shadow volume, shell_key_light.comp) and without the own
//                     cluster's factor (the volume counts the own cluster's fibres): its weight from the lighting
//                     pass's texels 14 + 3m .. 16 + 3m, w = D T̃ + max(T_f − T̃, 0) F with T̃ = exp(−n),
//                     T_f = exp(−n (1 − ā_f)) (key_light_volume.glsl), times re at its own azimuth. With
//                     SHELL_LIGHTING 1 w is taken at the vertices (shell.vert) and interpolated, as the sums are;
//                     otherwise at the fragment. (Without the own cluster's shadow, eq. 12's factor still takes all
//                     the light.)
//
// shell_shade() returns the fragment's premultiplied RGBA; shell.frag blends it, shell_abuffer.frag
// appends it to the per-pixel fragment lists (exact compositing, docs/renderer.md decision 4).
#ifndef COIF_SHADERS_GL_SHELL_SHADE_GLSL
#define COIF_SHADERS_GL_SHELL_SHADE_GLSL

#include "shaders/lighting/common.glsl"  // luminance
#include "shaders/gl/sector_frame.glsl"
#include "shaders/gl/record_atlas.glsl"

#ifndef SHELL_NEIGHBOURS
#define SHELL_NEIGHBOURS 1
#endif
#ifndef SHELL_LIGHTING
#define SHELL_LIGHTING 1
#endif
#ifndef SHELL_DEBUG
#define SHELL_DEBUG 0
#endif
#ifndef SHELL_FOURIER
#define SHELL_FOURIER 4
#endif
#ifndef SHELL_OWN
#define SHELL_OWN 1
#endif
#ifndef SHELL_FOLD
#define SHELL_FOLD 0
#endif
#ifndef SHELL_TILT_PICK
#define SHELL_TILT_PICK 0
#endif
#ifndef SHELL_SECTOR_PICK
#define SHELL_SECTOR_PICK 0
#endif
#ifndef SHELL_KEY_LIGHTS
#define SHELL_KEY_LIGHTS 0
#endif
#ifndef SHELL_HOT_SPOT
#define SHELL_HOT_SPOT 0
#endif
#ifndef SHELL_KEY_MEAN
#define SHELL_KEY_MEAN 0
#endif
#if SHELL_KEY_LIGHTS > 0
#include "shaders/gl/key_light_volume.glsl"  // u_key_light
uniform int u_key_index[SHELL_KEY_LIGHTS];         // in the lights buffer
#endif
#if SHELL_OWN != 0
#include "shaders/lighting/luts_gl.glsl"  // lut_own_cluster (bound by LightingPass::bind_tables)
#include "shaders/lighting/own_cluster.glsl"
#endif
#if SHELL_OWN == 2 && SHELL_LIGHTING != 2
uniform float u_d_f;  // Zinke's d_f for the own cluster's forward-scattered light (shell_light.glsl's, per fragment)
#endif

#if SHELL_LIGHTING == 2
#include "shaders/gl/shell_light.glsl"
#include "shaders/gl/lighting_samples.glsl"
#elif SHELL_KEY_LIGHTS > 0 && (SHELL_LIGHTING != 1 || SHELL_DEBUG == 5)
// The clusters' axes, for the key lights' slab where a fragment reads it (key_slab below, under the same condition).
#include "shaders/gl/lighting_samples.glsl"
#endif
#include "shaders/gl/shell_lighting_fetch.glsl"
#if SHELL_LIGHTING == 1
centroid in vec4 v_L0;
centroid in vec4 v_L1;
centroid in vec4 v_L2;
centroid in vec4 v_L3;
centroid in vec4 v_L4;
centroid in vec4 v_L5;
centroid in vec4 v_L6;
centroid in vec3 v_L7;
#if SHELL_TILT_PICK == 1
centroid in vec4 v_L8;
centroid in vec4 v_L10;
centroid in vec4 v_L11;
centroid in vec4 v_L12;
centroid in vec4 v_L13;
#endif
#if SHELL_OWN == 2
centroid in vec3 v_L9;
#endif
#if SHELL_HOT_SPOT > 0
centroid in vec3 v_hot;  // the lights' hot spot (shell_lighting.comp, texel LIGHTING_HOT_TEXEL)
#if SHELL_TILT_PICK == 1
centroid in vec4 v_hot_tangent;  // each fibre tangent's share of it in luminance (the next texel)
#endif
#endif
#if SHELL_KEY_LIGHTS > 0
centroid in vec3 v_key_weight[SHELL_KEY_LIGHTS];
#if SHELL_FOLD == 1
centroid in vec3 v_key_weight_inner[SHELL_KEY_LIGHTS];  // the folded inner layer's (shell.vert)
#endif
#endif
#endif

struct ShellSector {
    uvec4 id;      // nearest records, best first
    vec4 weight;   // their weights (renormalised here over the first u_neighbours)
    vec4 shadow;   // x: Σ of the mean α of the outer sectors at the same (i, k); y: of every layer there; z: the
                   // records' thinning c (record_atlas.glsl thinned_alpha)
};
layout(std430, binding = 1) readonly buffer Sectors { ShellSector sectors[]; };

uniform sampler2D u_records;       // record atlas (layout: shaders/gl/record_atlas.glsl)
uniform vec4 u_atlas_lo[ATLAS_PARTS];     // per tile part and channel: value = lo + scale · texel (the RGBA8
uniform vec4 u_atlas_scale[ATLAS_PARTS];  // atlas's ranges, online/shells/record_atlas.h)
uniform int u_tiles_per_row;
uniform vec2 u_atlas_inv_size;
uniform int u_views;
uniform int u_hrir_length;
uniform int u_s_t;
uniform int u_s_u;
uniform int u_layers;
uniform int u_layer;
uniform float u_kappa_shadow;
uniform float u_layer_rho;         // this layer mesh's surface v_{j+1}, in cluster radii (SHELL_OWN, key_slab)
uniform float u_inner_rho;         // the surface v_j of the layer inside it (key_slab; the folded inner layer's)
#if SHELL_FOLD == 1
centroid in vec3 v_axis_offset;    // from the cluster's axis (shell.vert)
centroid in vec3 v_ellipse_e1;     // the cross-section's axis of A
centroid in vec2 v_ellipse_ab;     // its half-axes A, B
uniform float u_fold_inner;        // 1: the layer inside u_layer is folded into this draw; 0: none (an odd count's last)
#endif
uniform float u_re_scale;          // 1 / re_norm
uniform vec3 u_eye;

const float TWO_PI = 6.28318530718;

// Strips across a sector (SHELL_TILT_PICK, SHELL_SECTOR_PICK). A record stands for the fibres of a sector; the two
// choices below light and draw each of FIBRE_STRIPS strips across it as one fibre would be, where the sums and the
// mix of 004 eq. 7 made every fibre the mean of its neighbours. Both draw by a stable hash, stratified: every 4
// neighbouring strips form a group whose draws are a permutation, so that every group, and so every sector, keeps the
// mean (independent draws per strip left the image's mean hair radiance 1-2 % to the draw at 240 x 160).
// docs/quality.md ("One tangent per strip", "One sector's records per strip") chose them and the strips' count by
// the detail ratio and the blurred PSNR against the path tracer.
const int FIBRE_STRIPS = 16;

int fibre_strip(float x) { return int(clamp(x, 0.0, 0.999999) * float(FIBRE_STRIPS)); }

// Position (0..3) of `strip` in a permutation of its group of 4, drawn from the sector, the group and `salt`.
int strip_rank(uint sector, int strip, uint salt) {
    uint h = (sector * 2654435761u) ^ (uint(strip / 4) * 2246822519u) ^ (salt * 3266489917u);
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    // A permutation of (0, 1, 2, 3) from h (Fisher–Yates: 4 · 3 · 2 choices).
    ivec4 order = ivec4(0, 1, 2, 3);
    int k = int(h % 4u);
    int swap = order[k];
    order[k] = order[3];
    order[3] = swap;
    h /= 4u;
    k = int(h % 3u);
    swap = order[k];
    order[k] = order[2];
    order[2] = swap;
    h /= 3u;
    k = int(h % 2u);
    swap = order[k];
    order[k] = order[1];
    order[1] = swap;
    return order[strip & 3];
}

#if SHELL_TILT_PICK == 1
// The fibres a record stands for tilt about the cluster's axis: by 35° RMS for the default style, each fibre its own
// way. The lighting pass lights four tangents with the strands' measured tilts (shaders/lighting/fibre_tangents.glsl);
// their mean lights every fibre alike and smooths away the fibre-to-fibre contrast of the highlights. So each strip is
// lit as one fibre at one of the four, every group of 4 strips taking each once.
int fibre_strip_tangent(uint sector, float x) { return strip_rank(sector, fibre_strip(x), 0u); }

// Tangent q's share of a light whose luminance each of the four tangents carries in `per_tangent` (texels 8 and
// LIGHTING_HOT_TEXEL + 1, on the light's scale): over their mean, not below 0; 1 where they carry none.
float tangent_share(vec4 per_tangent, int q) {
    float mean = 0.25 * (per_tangent.x + per_tangent.y + per_tangent.z + per_tangent.w);
    return mean > 1e-20 ? max(per_tangent[q], 0.0) / mean : 1.0;
}
#endif

vec4 atlas_fetch(uint tile, vec2 p) {
    vec2 origin = atlas_tile_origin(tile, u_tiles_per_row, u_hrir_length, u_views);
    return textureLod(u_records, (origin + p) * u_atlas_inv_size, 0.0);
}

// α and the 9 re coefficients of one sector at atlas position p (its SHELL_NEIGHBOURS best records, thinned to the
// sector's density), as three vec4: t0 = (α, a0, a1, b1), t1 = (a2, b2, a3, b3), t2 = (a4, b4, 0, 0). No arrays:
// llvmpipe spills them.
void sector_values(uint sector, vec2 p, out vec4 t0, out vec4 t1, out vec4 t2) {
    ShellSector s = sectors[sector];
    t0 = vec4(0.0);
    t1 = vec4(0.0);
    t2 = vec4(0.0);
    float wsum = 0.0;
    for (int n = 0; n < SHELL_NEIGHBOURS; ++n) {
        float w = s.weight[n];
        uint base = s.id[n] * uint(ATLAS_PARTS);
        t0 += w * atlas_fetch(base, p);
#if SHELL_FOURIER >= 2
        t1 += w * atlas_fetch(base + 1u, p);
#endif
#if SHELL_FOURIER >= 4
        t2 += w * atlas_fetch(base + 2u, p);
#endif
        wsum += w;
    }
    float inv = wsum > 0.0 ? 1.0 / wsum : 0.0;
    t0 = u_atlas_lo[0] + u_atlas_scale[0] * (t0 * inv);
#if SHELL_FOURIER >= 2
    t1 = u_atlas_lo[1] + u_atlas_scale[1] * (t1 * inv);
#endif
#if SHELL_FOURIER == 0
    t0.zw = vec2(0.0);
#endif
#if SHELL_FOURIER == 2
    t1.zw = vec2(0.0);
#endif
#if SHELL_FOURIER >= 4
    t2 = u_atlas_lo[2] + u_atlas_scale[2] * (t2 * inv);
#endif
    // Thinned to the sector's own density: α′ = 1 − (1 − α)^c, and re, the light per unit of α, with it.
    float a = clamp(t0.x, 0.0, 1.0);
    float thinned = thinned_alpha(a, s.shadow.z);
    float k = a > 1e-6 ? thinned / a : s.shadow.z;
    t0 = vec4(thinned, k * t0.yzw);
    t1 *= k;
    t2 *= k;
}

// re at a light's in-plane azimuth θl from its harmonics (c01 = (a0, a1, b1), c23 = (a2, b2, a3, b3), c4 = (a4, b4)),
// harmonic k damped by d_k for the light's spread.
float re_at(vec3 c01, vec4 c23, vec2 c4, float th, float d1, float d2, float d3, float d4) {
    return c01.x + d1 * (c01.y * cos(th) + c01.z * sin(th)) + d2 * (c23.x * cos(2.0 * th) + c23.y * sin(2.0 * th)) +
           d3 * (c23.z * cos(3.0 * th) + c23.w * sin(3.0 * th)) + d4 * (c4.x * cos(4.0 * th) + c4.y * sin(4.0 * th));
}

// The dampings d_k = exp(−k² λ'² / 4), k = 1..4, of re's harmonics for a light of bandwidth λ along l (unit) at a fibre
// of tangent T (sector_frame.glsl light_spread).
void light_dampings(vec3 l, float lambda, vec3 T, out float d1, out float d2, out float d3, out float d4) {
    float lp = light_spread(l, lambda, T);
    d1 = exp(-0.25 * lp * lp);
    d2 = d1 * d1 * d1 * d1;
    d3 = d2 * d2 * d1;
    d4 = d2 * d2 * d2 * d2;
}

#if SHELL_LIGHTING != 2
// Σ_j w_j re(θl_j) from the lighting sums turned to the fragment's radial axis: re's harmonics per channel (h[0] = a0,
// h[2k − 1] = a_k, h[2k] = b_k) against C_k, S_k, with e_k = (cos kψr, sin kψr):
//   Σ_j w_j cos k(ψj − ψr) = C_k cos kψr + S_k sin kψr;  Σ_j w_j sin k(ψj − ψr) = S_k cos kψr − C_k sin kψr.
vec3 fourier_sum(vec3 h[9], vec3 C0, vec3 C1, vec3 S1, vec3 C2, vec3 S2, vec3 C3, vec3 S3, vec3 C4, vec3 S4, vec2 e1,
                 vec2 e2, vec2 e3, vec2 e4) {
    vec3 sum = h[0] * C0;
    sum += h[1] * (C1 * e1.x + S1 * e1.y) + h[2] * (S1 * e1.x - C1 * e1.y);
    sum += h[3] * (C2 * e2.x + S2 * e2.y) + h[4] * (S2 * e2.x - C2 * e2.y);
    sum += h[5] * (C3 * e3.x + S3 * e3.y) + h[6] * (S3 * e3.x - C3 * e3.y);
    sum += h[7] * (C4 * e4.x + S4 * e4.y) + h[8] * (S4 * e4.x - C4 * e4.y);
    return sum;
}
#endif

// One layer `layer` (its mesh's surface at `rho` cluster radii) of the HSV at this fragment.
vec4 shell_shade_layer(vec3 position, vec3 tangent, vec3 normal, vec3 axis_normal, vec2 texcoord, uvec2 info, int layer,
                      float rho) {
    vec3 T = normalize(tangent);
    vec3 r = sector_radial(normalize(normal), T);
    vec3 V = normalize(u_eye - position);
    float theta_v = sector_azimuth(V, T, r);

    // HSV (i, j, k) and the position inside it.
    float tt = clamp(texcoord.y, 0.0, 1.0) * float(u_s_t);
    int i = min(int(tt), u_s_t - 1);
    float gamma = tt - float(i);
    float uu = fract(texcoord.x) * float(u_s_u);
    int k = min(int(uu), u_s_u - 1);
    float x = uu - float(k);
    uint base = info.x;
    uint top = base + uint((i * u_layers + layer) * u_s_u + k);
    uint bottom = top + uint(u_layers * u_s_u);

    float view = theta_v / TWO_PI * float(u_views);
    view = mod(view, float(u_views));
    vec2 p = vec2(x * float(u_hrir_length), view + 0.5);
#if SHELL_SECTOR_PICK == 1
    // The strip takes the records of one of the HSV's two sectors: the bottom one where γ passes the strip's threshold,
    // (rank + a hash's offset) / 4 within its group, so that a share γ of every group's strips takes the bottom one,
    // as 004 eq. 7 mixes them. Each strip keeps one record's contrast, and one sector's records are read instead of two.
    vec4 t0, t1, t2;
    {
        int strip = fibre_strip(x);
        uint h = (top * 747796405u) ^ (uint(strip / 4) * 2891336453u);
        h ^= h >> 16;
        h *= 2246822519u;
        h ^= h >> 13;
        float threshold = (float(strip_rank(top, strip, 1u)) + (float(h & 65535u) + 0.5) / 65536.0) * 0.25;
        sector_values(gamma > threshold ? bottom : top, p, t0, t1, t2);
    }
#else
    vec4 top0, top1, top2, bot0, bot1, bot2;
    sector_values(top, p, top0, top1, top2);
    sector_values(bottom, p, bot0, bot1, bot2);
    vec4 t0 = mix(top0, bot0, gamma);
    vec4 t1 = mix(top1, bot1, gamma);
    vec2 t2 = mix(top2.xy, bot2.xy, gamma);
#endif
    float alpha = clamp(t0.x, 0.0, 1.0);
#if SHELL_OWN != 0
    // The own cluster's fibres along one radius at this (i, k), in eq. 12's units: κ_shadow Σ ᾱ of every layer;
    // the light's side and the fragment's depth decide how much of it lies toward the light (own_cluster.glsl).
    float tau_r = u_kappa_shadow * mix(sectors[top].shadow.y, sectors[bottom].shadow.y, gamma);
    float tau = 1.0;
#else
    float tau = exp(-u_kappa_shadow * mix(sectors[top].shadow.x, sectors[bottom].shadow.x, gamma));
#endif

#if SHELL_DEBUG == 1
    return vec4(vec3(alpha), alpha);
#elif SHELL_DEBUG == 2
    return vec4(vec3(max(t0.y, 0.0) * u_re_scale * tau), alpha);
#endif

#if SHELL_KEY_LIGHTS > 0 && (SHELL_LIGHTING != 1 || SHELL_DEBUG == 5)
    // The key lights' points of this layer's slab (key_slab), on the line through the fragment, which lies on u_layer_rho.
    KeySlab slab = key_slab(position, sample_axis_point(texcoord.y, info.y, u_lighting_rows), u_layer_rho,
                            u_layer_rho - u_inner_rho, rho, V);
#endif
#if SHELL_DEBUG == 5 && SHELL_KEY_LIGHTS > 0
    return vec4(vec3(key_transmittance(0, slab) * alpha), alpha);
#elif SHELL_DEBUG == 5
    return vec4(vec3(alpha), alpha);
#endif

#if SHELL_LIGHTING == 2
    // Every light at this fragment: its weight in the fragment's own frame (T, r, T × r), shadowed by
    // (T̃, n) interpolated between the two lighting samples around t, times re at the light's own
    // in-plane azimuth θl = the light's azimuth from r: re(θl) = a0 + Σ_k d_k (a_k cos kθl + b_k sin kθl).
    float tr = clamp(texcoord.y, 0.0, 1.0) * float(u_lighting_rows - 1);
    int row = min(int(tr), u_lighting_rows - 2);
    float f = tr - float(row);
    int first = int(info.y) * u_lighting_rows + row;
    HairParams hp = u_hair;
    if (u_absorption_on != 0)
        hp.sigma_a = mix(texelFetch(u_absorption, ivec2(row, int(info.y)), 0).rgb,
                         texelFetch(u_absorption, ivec2(row + 1, int(info.y)), 0).rgb, f);
    // The fibres' tilts between the two lighting samples around t (or the ring of u_tangent_spread).
    vec3 tm = mix(samples[first].tilt_mean.xyz, samples[first + 1].tilt_mean.xyz, f);
    vec3 ta = mix(samples[first].tilt_a.xyz, samples[first + 1].tilt_a.xyz, f);
    vec3 tb = mix(samples[first].tilt_b.xyz, samples[first + 1].tilt_b.xyz, f);
    shell_fibre_tilts(T, r, V, tm, ta, tb);
#if SHELL_TILT_PICK == 1
    // The strip's fibre at its one tangent, for every light (the Fourier path scales the mean by this tangent's share).
    vec3 Tq;
    vec3 rq;
    fibre_tangent_of(T, r, tm, ta, tb, fibre_strip_tangent(top, x), SHELL_TANGENTS, Tq, rq);
    SrbfPoint strip_point = srbf_point(hp, V, Tq, rq);
#endif
#if SHELL_OWN != 0
    // The own cluster's depth per radius (own_cluster_tau), the inner depth between the two samples around t.
    float own_tau = own_cluster_tau(tau_r, mix(sample_inner(first), sample_inner(first + 1), f), r);
#endif
    vec3 lit = vec3(0.0);
    vec3 C0 = vec3(0.0);
    float visible = 0.0;
    float total = 0.0;
#if SHELL_TILT_PICK == 1
#define SHELL_LIGHT_WEIGHT(sh, lum_visible, lum_total) shell_light_weight(strip_point, j, sh, lum_visible, lum_total)
#else
    // The mean over the fibres' tangents about T, as in the lighting pass.
#define SHELL_LIGHT_WEIGHT(sh, lum_visible, lum_total) \
    shell_light_weight_fibres(hp, V, T, r, tm, ta, tb, j, sh, lum_visible, lum_total)
#endif
    for (int j = 0; j < u_light_count; ++j) {
        vec2 sh = vec2(1.0, 0.0);
        if (u_shadows != 0)
            sh = mix(shadows[first * u_light_count + j], shadows[(first + 1) * u_light_count + j], f);
        float own_on = 1.0;  // 0 for a key light: its volume counts the own cluster's fibres
        vec3 wj;
#if SHELL_KEY_LIGHTS > 0
        int key = -1;
        for (int m = 0; m < SHELL_KEY_LIGHTS; ++m)
            if (u_key_index[m] == j) key = m;
        if (key >= 0) {  // over the layer's slab (key_slab), as key_light_weight
            float n0 = key_fibres(key, slab.p0), n1 = key_fibres(key, slab.p1);
            float visible0 = 0.0, total0 = 0.0, visible1 = 0.0, total1 = 0.0;
            wj = mix(SHELL_LIGHT_WEIGHT(vec2(exp(-n0), n0), visible0, total0),
                     SHELL_LIGHT_WEIGHT(vec2(exp(-n1), n1), visible1, total1), slab.w1);
            visible += mix(visible0, visible1, slab.w1);
            total += mix(total0, total1, slab.w1);
            own_on = 0.0;
        } else
#endif
        {
            wj = SHELL_LIGHT_WEIGHT(sh, visible, total);
        }
        float th = sector_azimuth(lights[j].direction_lambda.xyz, T, r);
        float d1, d2, d3, d4;
        light_dampings(lights[j].direction_lambda.xyz, lights[j].direction_lambda.w, T, d1, d2, d3, d4);
#if SHELL_OWN == 1
        // re times this light's own-cluster transmittance (its own angle to the axis), as harmonics, so that the
        // light's spread blurs the product as it does in the Fourier path.
        vec3 h01;
        vec4 h23;
        vec2 h4;
        own_cluster_harmonics(own_on * own_tau * own_cluster_stretch(normalize(lights[j].direction_lambda.xyz), T), rho,
                              t0.yzw, t1, t2.xy, h01, h23, h4);
        float re = re_at(h01, h23, h4, th, d1, d2, d3, d4);
#elif SHELL_OWN == 2
        // As SHELL_OWN 1 with the forward-scattered light (own_cluster_forward_series), per channel, at this light's
        // own angle to the axis: ā_f at θd = its longitudinal angle, as the lighting pass takes it.
        vec3 lj = normalize(lights[j].direction_lambda.xyz);
        float tau_j = own_on * own_tau * own_cluster_stretch(lj, T);
        vec3 loss = vec3(1.0) - fetch_ms_forward(safe_asin(dot(lj, T)), hp.sigma_a).rgb;
        float p0;
        vec4 p1234;
        vec4 p5678;
        own_cluster_series(tau_j, rho, p0, p1234, p5678);
        vec3 re;
        for (int c = 0; c < 3; ++c) {
            float q0;
            vec4 q1234;
            vec4 q5678;
            own_cluster_forward_series(tau_j, rho, loss[c], u_d_f, p0, p1234, p5678, q0, q1234, q5678);
            vec3 h01;
            vec4 h23;
            vec2 h4;
            own_cluster_product(q0, q1234, q5678, t0.yzw, t1, t2.xy, h01, h23, h4);
            re[c] = re_at(h01, h23, h4, th, d1, d2, d3, d4);
        }
#else
        float re = re_at(t0.yzw, t1, t2.xy, th, d1, d2, d3, d4);
#endif
        // The share of this light lit with re's mean past the own cluster's factor: the hot spot's (ShellSettings::hot_spot;
        // the lighting pass splits each light but the key lights alike), a key light's whole with key_re_mean.
        float mean_share = 0.0;
#if SHELL_HOT_SPOT > 0
        mean_share = shell_hot_spot_share(j, V, SHELL_HOT_SPOT);
#endif
#if SHELL_KEY_LIGHTS > 0
        if (key >= 0) mean_share = float(SHELL_KEY_MEAN);
#endif
        lit += wj * (re * (1.0 - mean_share) + t0.y * mean_share);
        C0 += wj;
    }
#undef SHELL_LIGHT_WEIGHT
#if SHELL_DEBUG == 3
    return vec4(C0 * alpha * tau, alpha);
#elif SHELL_DEBUG == 4
    return vec4(vec3((total > 0.0 ? visible / total : 1.0) * tau * alpha), alpha);
#endif
    return vec4(max(lit, vec3(0.0)) * u_re_scale * tau, alpha);
#else
    // Lighting coefficients at this t (linear between lighting rows), turned to this fragment's r.
    // Texels: L0 = (C0.rgb, C1.r), L1 = (C1.gb, S1.rg), L2 = (S1.b, C2.rgb), L3 = (S2.rgb, C3.r),
    //         L4 = (C3.gb, S3.rg), L5 = (S3.b, C4.rgb), L6 = (S4.rgb, V) with V the sample's unoccluded
    //         fraction of the light (Σ_j lum L_j T̃_j / Σ_j lum L_j).
#if SHELL_LIGHTING == 1
    vec4 L0 = v_L0, L1 = v_L1, L2 = v_L2, L3 = v_L3, L4 = v_L4, L5 = v_L5, L6 = v_L6;
    vec3 L7 = v_L7;
#else
    vec4 L0 = lighting_fetch(texcoord.y, info.y, 0);
    vec4 L1 = lighting_fetch(texcoord.y, info.y, 1);
    vec4 L2 = lighting_fetch(texcoord.y, info.y, 2);
    vec4 L3 = lighting_fetch(texcoord.y, info.y, 3);
    vec4 L4 = lighting_fetch(texcoord.y, info.y, 4);
    vec4 L5 = lighting_fetch(texcoord.y, info.y, 5);
    vec4 L6 = lighting_fetch(texcoord.y, info.y, 6);
    vec3 L7 = lighting_fetch(texcoord.y, info.y, 7).xzw;
#endif
    vec3 C0 = L0.xyz;
#if SHELL_HOT_SPOT > 0
    // The lights' hot spot (ShellSettings::hot_spot), which C0 and the harmonics leave out.
#if SHELL_LIGHTING == 1
    vec3 hot = v_hot;
#else
    vec3 hot = lighting_fetch(texcoord.y, info.y, LIGHTING_HOT_TEXEL).xyz;
#endif
#endif
#if SHELL_DEBUG == 3 && SHELL_HOT_SPOT > 0
    return vec4((C0 + hot) * alpha * tau, alpha);
#elif SHELL_DEBUG == 3
    return vec4(C0 * alpha * tau, alpha);
#elif SHELL_DEBUG == 4
    return vec4(vec3(L6.w * tau * alpha), alpha);
#endif
    vec3 C1 = vec3(L0.w, L1.xy), S1 = vec3(L1.zw, L2.x);
    vec3 C2 = L2.yzw, S2 = L3.xyz;
    vec3 C3 = vec3(L3.w, L4.xy), S3 = vec3(L4.zw, L5.x);
    vec3 C4 = L5.yzw, S4 = L6.xyz;
    vec3 r0 = axis_normal - dot(axis_normal, T) * T;
    // ψr = sector_azimuth(r, T, r0) without the angle: (cos ψr, sin ψr) = (r · r0, r · (T × r0)), both unit ⟂ T; the
    // sums turn to it in fourier_sum.
    r0 = normalize(r0);
    vec2 e1 = vec2(dot(r, r0), dot(r, cross(T, r0)));
    float e1_len = length(e1);
    e1 = e1_len > 1e-6 ? e1 / e1_len : vec2(1.0, 0.0);
    vec2 e2 = vec2(e1.x * e1.x - e1.y * e1.y, 2.0 * e1.x * e1.y);
    vec2 e3 = vec2(e2.x * e1.x - e2.y * e1.y, e2.x * e1.y + e2.y * e1.x);
    vec2 e4 = vec2(e2.x * e2.x - e2.y * e2.y, 2.0 * e2.x * e2.y);
#if SHELL_KEY_LIGHTS > 0
    vec3 raw01 = t0.yzw;  // re's own harmonics, for the key lights (no own cluster's factor)
    vec4 raw23 = t1;
    vec2 raw4 = t2.xy;
#endif
#if SHELL_HOT_SPOT > 0
    float re_mean = t0.y;  // re's mean, for the lights' hot spot (no own cluster's factor)
#endif
#if SHELL_OWN != 0
    // The own cluster's depth per radius at this fragment, stretched by the lights' mean angle to the axis: at least the
    // grid's count across the cluster on its side toward the hair's inside (own_cluster_tau).
    float own_tau = own_cluster_tau(tau_r, L7.yz, e1) * L7.x;
#endif
#if SHELL_OWN == 1
    {  // re(θl) times the own cluster's transmittance at θl, as harmonics (shaders/lighting/own_cluster.glsl)
        vec3 h01;
        vec4 h23;
        vec2 h4;
        own_cluster_harmonics(own_tau, rho, t0.yzw, t1, t2.xy, h01, h23, h4);
        t0.yzw = h01;
        t1 = h23;
        t2.xy = h4;
    }
#endif
#if SHELL_OWN == 2
    // re(θl) times the own cluster's transmittance with its forward-scattered light, which differs per channel
    // (own_cluster_forward_series): one product of the series per channel, each channel's harmonics in h[·][c].
#if SHELL_LIGHTING == 1
    vec3 loss = v_L9;
#else
    vec3 loss = lighting_fetch(texcoord.y, info.y, 9).xyz;
#endif
    vec3 h[9];
    {
        float p0;
        vec4 p1234;
        vec4 p5678;
        own_cluster_series(own_tau, rho, p0, p1234, p5678);
        for (int c = 0; c < 3; ++c) {
            float q0;
            vec4 q1234;
            vec4 q5678;
            own_cluster_forward_series(own_tau, rho, loss[c], u_d_f, p0, p1234, p5678, q0, q1234, q5678);
            vec3 h01;
            vec4 h23;
            vec2 h4;
            own_cluster_product(q0, q1234, q5678, t0.yzw, t1, t2.xy, h01, h23, h4);
            h[0][c] = h01.x;
            h[1][c] = h01.y;
            h[2][c] = h01.z;
            h[3][c] = h23.x;
            h[4][c] = h23.y;
            h[5][c] = h23.z;
            h[6][c] = h23.w;
            h[7][c] = h4.x;
            h[8][c] = h4.y;
        }
    }
#else
    vec3 h[9] = vec3[9](vec3(t0.y), vec3(t0.z), vec3(t0.w), vec3(t1.x), vec3(t1.y), vec3(t1.z), vec3(t1.w), vec3(t2.x),
                        vec3(t2.y));
#endif
    vec3 sum = fourier_sum(h, C0, C1, S1, C2, S2, C3, S3, C4, S4, e1, e2, e3, e4);
#if SHELL_KEY_LIGHTS > 0
    for (int m = 0; m < SHELL_KEY_LIGHTS; ++m) {
#if SHELL_LIGHTING == 1
        // Per vertex, as the sums are, and interpolated as light: a coarser mesh's vertices are the full mesh's and read
        // only the samples the lighting pass lit (docs/renderer.md, "Key lights").
#if SHELL_FOLD == 1
        vec3 w = layer == u_layer ? v_key_weight[m] : v_key_weight_inner[m];
#else
        vec3 w = v_key_weight[m];
#endif
#else
        vec3 w = key_light_weight(m, slab, lighting_fetch(texcoord.y, info.y, 14 + 3 * m).rgb,
                                  lighting_fetch(texcoord.y, info.y, 15 + 3 * m).rgb,
                                  lighting_fetch(texcoord.y, info.y, 16 + 3 * m).rgb);
#endif
#if SHELL_KEY_MEAN == 1
        sum += w * raw01.x;  // re's mean (ShellSettings::key_re_mean)
#else
        vec3 l = u_key_light[m].xyz;
        float d1, d2, d3, d4;
        light_dampings(l, u_key_light[m].w, T, d1, d2, d3, d4);
        sum += w * re_at(raw01, raw23, raw4, sector_azimuth(l, T, r), d1, d2, d3, d4);
#endif
    }
#endif
#if SHELL_TILT_PICK == 1
    {
        // The strip's fibre at its one tangent q: the sums scaled by that tangent's share of the light where re takes
        // it. Each tangent's sums to the second harmonic in luminance (texels 8, 10..13), turned to r as above, against
        // re's harmonics in luminance, give what reaches each tangent through this fragment's records; the strip takes
        // tangent q's share of the four's mean. The colour stays the mean's (scaling each channel sprinkled red and blue
        // where a channel's light is near 0: docs/quality.md "One tangent per strip"); a share below 0 leaves the strip
        // unlit. Where the four's mean is not well above 0 (re's harmonics cancel the light), the share of C_0 alone
        // (texel 8).
#if SHELL_LIGHTING == 1
        vec4 L8 = v_L8, L10 = v_L10, L11 = v_L11, L12 = v_L12, L13 = v_L13;
#else
        vec4 L8 = lighting_fetch(texcoord.y, info.y, 8);
        vec4 L10 = lighting_fetch(texcoord.y, info.y, 10);
        vec4 L11 = lighting_fetch(texcoord.y, info.y, 11);
        vec4 L12 = lighting_fetch(texcoord.y, info.y, 12);
        vec4 L13 = lighting_fetch(texcoord.y, info.y, 13);
#endif
        vec4 reach = luminance(h[0]) * L8 + luminance(h[1]) * (L10 * e1.x + L11 * e1.y) +
                     luminance(h[2]) * (L11 * e1.x - L10 * e1.y) + luminance(h[3]) * (L12 * e2.x + L13 * e2.y) +
                     luminance(h[4]) * (L13 * e2.x - L12 * e2.y);
        float reach_mean = 0.25 * (reach.x + reach.y + reach.z + reach.w);
        float reach_abs = 0.25 * (abs(reach.x) + abs(reach.y) + abs(reach.z) + abs(reach.w));
        int q = fibre_strip_tangent(top, x);
        sum *= reach_mean > 0.5 * reach_abs && reach_mean > 0.0 ? reach[q] / reach_mean : tangent_share(L8, q);
#if SHELL_HOT_SPOT > 0
        // The hot spot's own share of the strip's tangent: its light is re's mean's alone, so C_0's share.
#if SHELL_LIGHTING == 1
        vec4 hot_tangent = v_hot_tangent;
#else
        vec4 hot_tangent = lighting_fetch(texcoord.y, info.y, LIGHTING_HOT_TEXEL + 1);
#endif
        hot *= tangent_share(hot_tangent, q);
#endif
    }
#endif
#if SHELL_HOT_SPOT > 0
    // The hot spot: lit with re's mean past the own cluster's factor.
    sum += re_mean * hot;
#endif
    return vec4(max(sum, vec3(0.0)) * u_re_scale * tau, alpha);
#endif
}

#if SHELL_FOLD == 1
// Two layers from the outer one's mesh (ShellSettings::fold_level): `outer`, layer u_layer shaded here, and `inner`, the
// layer inside it (u_layer − 1, surface u_inner_rho; none when u_fold_inner is 0) shaded where this fragment's view ray
// meets it.
//
// In the cross-section's coordinates scaled by its half-axes (x along e1 over A, y along e2 = T × e1 over B) the layers
// are circles of radii u_layer_rho and u_inner_rho, and the ray's projection is a line: p the fragment, D the ray's
// direction, c its point nearest the axis. The ray meets the inner layer at c ∓ √(ρ_i² − |c|²) D (entering on the near
// side, leaving on the far side), at the angle u_i, where the ellipse's normal is ∝ (x / A, y / B); where |c| ≥ ρ_i it
// passes beside the inner layer, which then adds nothing (weighed across 10 % of ρ_i against aliasing).
void shell_shade_pair(vec3 position, vec3 tangent, vec3 normal, vec3 axis_normal, vec2 texcoord, uvec2 info, out vec4 outer,
                      out vec4 inner) {
    outer = shell_shade_layer(position, tangent, normal, axis_normal, texcoord, info, u_layer, u_layer_rho);
    vec3 T = normalize(tangent);
    vec3 e1 = normalize(v_ellipse_e1 - dot(v_ellipse_e1, T) * T);
    vec3 e2 = cross(T, e1);
    vec2 ab = max(v_ellipse_ab, vec2(1e-6));
    vec2 p = vec2(dot(v_axis_offset, e1), dot(v_axis_offset, e2)) / ab;
    // On the surface at the fragment's angle: a coarse mesh's chords lie inside it (8 columns: by up to 8 %).
    float p_len = length(p);
    p = p_len > 1e-6 ? p * (u_layer_rho / p_len) : vec2(u_layer_rho, 0.0);
    vec3 ray = normalize(position - u_eye);
    vec2 D = vec2(dot(ray, e1), dot(ray, e2)) / ab;
    float D_len = length(D);
    bool across = D_len > 1e-6 * u_layer_rho / max(ab.x, ab.y);
    D = across ? D / D_len : vec2(0.0);
    vec2 c = p - dot(p, D) * D;
    float h = sqrt(max(u_inner_rho * u_inner_rho - dot(c, c), 0.0));
    // Seen along the axis, the ray meets the inner layer far along it: the same side of the cluster, beside the outer.
    vec2 pi = across ? c + (gl_FrontFacing ? -h : h) * D : p * (u_inner_rho / u_layer_rho);
    vec3 ni = (pi.x / ab.x) * e1 + (pi.y / ab.y) * e2;
    float ni_len = length(ni);
    ni = ni_len > 1e-12 ? ni / ni_len : normal;
    vec2 tc_inner = vec2(atan(pi.y, pi.x) * (1.0 / TWO_PI), texcoord.y);
    float hit = across ? clamp((u_inner_rho - length(c)) / (0.1 * u_inner_rho) + 0.5, 0.0, 1.0) : 1.0;
    inner = (u_fold_inner * hit) * shell_shade_layer(position, tangent, ni, axis_normal, tc_inner, info, max(u_layer - 1, 0),
                                                     u_inner_rho);
}
#endif

vec4 shell_shade(vec3 position, vec3 tangent, vec3 normal, vec3 axis_normal, vec2 texcoord, uvec2 info) {
#if SHELL_FOLD == 1
    // The pair as one fragment at the outer layer's depth (the weighted blend and the k-buffer; not the exact lists,
    // docs/renderer.md): composited "over" in the order the eye meets them, the outer first on the near side (front
    // faces), the inner first on the far side (back faces, seen through the core).
    vec4 outer, inner;
    shell_shade_pair(position, tangent, normal, axis_normal, texcoord, info, outer, inner);
    return gl_FrontFacing ? outer + (1.0 - outer.a) * inner : inner + (1.0 - inner.a) * outer;
#else
    return shell_shade_layer(position, tangent, normal, axis_normal, texcoord, info, u_layer, u_layer_rho);
#endif
}

#endif  // COIF_SHADERS_GL_SHELL_SHADE_GLSL
