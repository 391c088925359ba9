// The lighting pass of the shell renderer (DESIGN.md decisions 1 and 3): per lighting sample along
// each cluster's axis (position, tangent T, frame normal r0) and per SRBF light j, the weight
// w_j = L_j (T̃_j 𝓜_j + multiple scattering) of the SRBF Marschner lighting (shaders/lighting/
// srbf_shadowed.glsl: 000 eq. 2–5 in Zinke's split) with T̃_j and the fibres met n_j from the shadow
// pass (shell_shadow.comp; T̃ = 1, n = 0 when shadows between clusters are off), and the light's in-plane
// azimuth ψ_j in the fixed frame (r0, T × r0) (shaders/gl/sector_frame.glsl). w_j is the mean over the
// fibres' tangents about T (shaders/lighting/fibre_tangents.glsl: the sample's measured tilts, or a ring of
// u_tangent_spread; SHELL_TANGENTS of them). Stored:
//   C_0 = Σ w_j,  C_k = Σ w_j d_k cos kψ_j,  S_k = Σ w_j d_k sin kψ_j   (k = 1..4, RGB each)
// with d_k = exp(−k² λ'²/4) the damping of harmonic k by the light's spread (the Fourier coefficient
// of a circular Gaussian of bandwidth λ' for small λ'), λ' = λ_j / |l projected on the normal plane|.
// 27 floats in the first 8 RGBA32F texels per sample: texel (k, cluster · LIGHTING_TEXELS + m) for the k-th sample
// lit along the cluster; the 28th float is the sample's unoccluded fraction of the light, Σ_j lum(L_j) T̃_j /
// Σ_j lum(L_j) (the shadow AOV); the 29th is the factor by which the lights' angles to the axis lengthen their
// paths across the own cluster in the Fourier path: own_cluster_stretch (shaders/lighting/own_cluster.glsl) of each
// light, averaged with the weights lum(w_j); the 30th the number of lights lit (all of them unless culled, below);
// the 31st and 32nd the own cluster's fibres per radius toward the hair's outside (sample_inner) in the frame (r0, T × r0),
// by which the shells shade the cluster's side toward the hair's inside (own_cluster.glsl own_cluster_tau).
// Texel 8 holds lum(C_0) of each fibre tangent q alone, (Σ_j w_jq over the four), on C_0's scale (all four lum(C_0)
// with one tangent), and texels 10..13 that tangent's first two harmonics in luminance, lum(C_1), lum(S_1), lum(C_2),
// lum(S_2) (each texel one harmonic, component q the tangent): the shells light each strip of a sector as one fibre at
// one tangent (shell_shade.glsl SHELL_TILT_PICK), with the share of the light that reaches that tangent at the
// records' light azimuths. Texel 9 holds the fibres' forward loss 1 − ā_f per channel (ā_f: zinke_forward, at the θd whose
// 1 / cos is the 29th float, the lights' mean stretch), for the own cluster's forward-scattered light (shell_shade.glsl
// SHELL_OWN 2). LIGHTING_TEXELS (online/shell_passes.h kLightingTexels) texels per sample in all, the last two of them
// the hot spot's (LIGHTING_HOT_TEXEL, below).
//
// With SHELL_KEY_LIGHTS K (ShellSettings::key_lights) the K lights u_key_index are left out of every sum but texels 8,
// 10..13 (and the shadow AOV), and texels 14 + 3m .. 16 + 3m hold key light m's weight for the shells to shadow per
// fragment (shell_shade.glsl): its light unshadowed (single scattering and the local multiple scattering, T̃ = 1), its
// forward-scattered light per unit of its share max(T_f − T̃, 0) (shell_light_forward, at the axis's n), and the fibres'
// forward loss 1 − ā_f at its angle, each the mean over the fibre tangents.
//
// With SHELL_HOT_SPOT p > 0 (ShellSettings::hot_spot, with the own cluster's shadow) each light j but the key lights is
// split by h_j = max(0, l_j · v)^p, v toward the camera: h_j w_j is summed apart into texel LIGHTING_HOT_TEXEL (and
// each fibre tangent's in luminance, on its scale as texel 8, into the next texel) and left out of every other sum (the
// own cluster's mean stretch, 29th float, and texels 8, 10..13 included). The shells light that share with re's
// mean past the own cluster's factor (shell_shade.glsl): where a light stands behind the camera, the fibres the camera
// sees through the cluster's gaps are lit through the same gaps (docs/quality.md, "The records thinned to their
// sectors' density, and the lights' hot spot").
//
// With SHELL_CULL_LIGHTS N (the light count, up to kMaxCulledLights; ShellSettings::light_cull > 0) each sample lights only the lights that
// carry its light: light j's share is estimated as b_j = |lum(L_j)| ∫G_j (T̃_j + d_f max_c(T_f − T̃_j)), its power times
// what reaches the sample unscattered and forward-scattered (srbf_shadowed.glsl, at the axis tangent), and the
// dimmest lights whose estimates sum to at most u_light_cull Σ b are skipped. The shadow AOV still counts every light.
#include "shaders/gl/shell_light.glsl"
#include "shaders/lighting/own_cluster.glsl"

layout(local_size_x = 32) in;
#ifndef SHELL_KEY_LIGHTS
#define SHELL_KEY_LIGHTS 0
#endif
#if SHELL_KEY_LIGHTS > 0
uniform int u_key_index[SHELL_KEY_LIGHTS];  // the key lights in the lights buffer
bool is_key(int j) {
    for (int m = 0; m < SHELL_KEY_LIGHTS; ++m)
        if (u_key_index[m] == j) return true;
    return false;
}
#else
bool is_key(int j) { return false; }
#endif

#ifndef SHELL_HOT_SPOT
#define SHELL_HOT_SPOT 0
#endif

#include "shaders/gl/lighting_samples.glsl"
layout(rgba32f, binding = 0) writeonly uniform image2D u_out;

uniform int u_invocations;  // the samples lit
uniform int u_rows;         // lighting samples per cluster
uniform int u_step;         // every u_step-th of them is lit (ShellSettings::lighting_step), the k-th written to texel k
// The samples lit, as (cluster, k): with a level of detail only those its meshes read (online/shell_passes.h lit_samples).
layout(std430, binding = 5) readonly buffer LitSamples { ivec2 lit_samples[]; };
uniform vec3 u_eye;
#ifdef SHELL_CULL_LIGHTS
uniform float u_light_cull;  // ShellSettings::light_cull
#endif

void main() {
    int invocation = int(gl_GlobalInvocationID.x);
    if (invocation >= u_invocations) return;
    int cluster = lit_samples[invocation].x;
    int used = lit_samples[invocation].y;
    int row = used * u_step;
    int i = cluster * u_rows + row;  // the lighting sample
    LightingSample s = samples[i];
    HairParams hp = u_hair;
    if (u_absorption_on != 0) hp.sigma_a = texelFetch(u_absorption, ivec2(row, cluster), 0).rgb;
    vec3 T = normalize(s.tangent.xyz);
    vec3 r0 = sample_frame_normal(s, T);
    vec3 V = normalize(u_eye - s.position.xyz);
    vec3 C[5];
    vec3 S[5];
    for (int k = 0; k < 5; ++k) { C[k] = vec3(0.0); S[k] = vec3(0.0); }
    float visible = 0.0;  // Σ_j lum(L_j) T̃_j and Σ_j lum(L_j): the sample's unoccluded fraction (shadow AOV)
    float total = 0.0;
    float own_weight = 0.0;  // Σ_j lum(w_j) own_cluster_stretch(l_j) and Σ_j lum(w_j)
    float own_norm = 0.0;
    // The fibres' tangents about T (shell_light.glsl): each is lit with its own angles; the light's azimuth ψ_j
    // stays in the axis frame, where re meets it. The lum-weighted sums below are ratios, so summing them over the
    // tangents leaves them means.
    vec3 tm = s.tilt_mean.xyz;
    vec3 ta = s.tilt_a.xyz;
    vec3 tb = s.tilt_b.xyz;
    shell_fibre_tilts(T, r0, V, tm, ta, tb);
#ifdef SHELL_CULL_LIGHTS
    float estimate[SHELL_CULL_LIGHTS];
    float estimated = 0.0;
    for (int j = 0; j < SHELL_CULL_LIGHTS; ++j) {
        vec2 sh = sample_shadow(i, j);
        vec4 dl = lights[j].direction_lambda;
        float lum = light_luminance(j);
        visible += lum * sh.x;
        total += lum;
        float reach = sh.x;
        if (SRBF_MULTIPLE != 0 && sh.y > 0.0) {
            vec3 a_f = fetch_ms_forward(safe_asin(dot(normalize(dl.xyz), T)), hp.sigma_a).rgb;
            vec3 T_f = exp(-sh.y * (vec3(1.0) - a_f));
            reach += u_d_f * max(max(max(T_f.x, T_f.y), T_f.z) - sh.x, 0.0);
        }
        estimate[j] = is_key(j) ? 0.0 : abs(lum) * srbf_integral(dl.w) * reach;  // a key light is lit apart
        estimated += estimate[j];
    }
    // The lights below a threshold are skipped: the highest threshold under which the estimates sum to at most
    // u_light_cull of the whole, found by bisection (20 halvings of [0, the brightest]; the sum below `low` always
    // stays within the bound). A light whose estimate is 0 adds nothing (no power, or no light reaches the sample).
    float low = 0.0;
    float high = 0.0;
    for (int j = 0; j < SHELL_CULL_LIGHTS; ++j) high = max(high, estimate[j]);
    for (int it = 0; it < 20; ++it) {
        float mid = 0.5 * (low + high);
        float below = 0.0;
        for (int j = 0; j < SHELL_CULL_LIGHTS; ++j) below += estimate[j] < mid ? estimate[j] : 0.0;
        if (below <= u_light_cull * estimated)
            low = mid;
        else
            high = mid;
    }
    int kept[SHELL_CULL_LIGHTS];
    int kept_count = 0;
    float kept_estimate = 0.0;
    for (int j = 0; j < SHELL_CULL_LIGHTS; ++j) {
        if (estimate[j] >= low && estimate[j] > 0.0) {
            kept[kept_count] = j;
            ++kept_count;
            kept_estimate += estimate[j];
        }
    }
    // The kept lights stand for the skipped ones too: scaled by Σ b over Σ b kept (at most 1 / (1 − u_light_cull)).
    float stand_in = kept_estimate > 0.0 ? estimated / kept_estimate : 1.0;
#endif
#if SHELL_KEY_LIGHTS > 0
    vec3 key_direct[SHELL_KEY_LIGHTS];
    vec3 key_forward[SHELL_KEY_LIGHTS];
    vec3 key_loss[SHELL_KEY_LIGHTS];
    for (int m = 0; m < SHELL_KEY_LIGHTS; ++m) {
        key_direct[m] = vec3(0.0);
        key_forward[m] = vec3(0.0);
        key_loss[m] = vec3(0.0);
    }
#endif
    vec3 hot = vec3(0.0);          // Σ h_j w_j (texel LIGHTING_HOT_TEXEL)
    vec4 hot_tangent = vec4(0.0);  // lum of each tangent's alone (the texel after it)
    vec4 tangent_lum = vec4(0.0);  // lum(C_0) of each tangent alone (texel 8)
    vec4 tangent_c1 = vec4(0.0);   // lum(C_1), lum(S_1), lum(C_2), lum(S_2) of each tangent alone (texels 10..13)
    vec4 tangent_s1 = vec4(0.0);
    vec4 tangent_c2 = vec4(0.0);
    vec4 tangent_s2 = vec4(0.0);
    for (int q = 0; q < SHELL_TANGENTS; ++q) {
        vec3 C0_before = C[0];
        vec3 hot_before = hot;
        vec3 Tq;
        vec3 rq;
        fibre_tangent_of(T, r0, tm, ta, tb, q, SHELL_TANGENTS, Tq, rq);
        SrbfPoint p = srbf_point(hp, V, Tq, rq);
#ifdef SHELL_CULL_LIGHTS
        for (int m = 0; m < kept_count; ++m) {  // (the shadow AOV counted every light above)
            int j = kept[m];
            vec3 wj = srbf_light_radiance(p, u_d_f, j, sample_shadow(i, j)) * (stand_in / float(SHELL_TANGENTS));
#else
        for (int j = 0; j < u_light_count; ++j) {
            if (is_key(j)) continue;  // lit apart, below
            vec3 wj = shell_light_weight(p, j, sample_shadow(i, j), visible, total) * (1.0 / float(SHELL_TANGENTS));
#endif
            vec3 l = lights[j].direction_lambda.xyz;
#if SHELL_HOT_SPOT > 0
            {
                float h = shell_hot_spot_share(j, V, SHELL_HOT_SPOT);
                hot += h * wj;
                wj *= 1.0 - h;
            }
#endif
            float psi = sector_azimuth(l, T, r0);
            float lp = shell_light_spread(j, T);
            C[0] += wj;
            float lum = max(luminance(wj), 0.0);
            own_weight += lum * own_cluster_stretch(normalize(l), T);
            own_norm += lum;
            // This tangent's own harmonics 1 and 2 in luminance too, on C_0's scale as texel 8.
            float lw = float(SHELL_TANGENTS) * luminance(wj);
            for (int k = 1; k <= 4; ++k) {
                float d = exp(-float(k * k) * lp * lp * 0.25);
                float ck = d * cos(float(k) * psi);
                float sk = d * sin(float(k) * psi);
                C[k] += wj * ck;
                S[k] += wj * sk;
                if (k == 1) {
                    tangent_c1[q] += lw * ck;
                    tangent_s1[q] += lw * sk;
                } else if (k == 2) {
                    tangent_c2[q] += lw * ck;
                    tangent_s2[q] += lw * sk;
                }
            }
        }
        tangent_lum[q] = float(SHELL_TANGENTS) * luminance(C[0] - C0_before);
        hot_tangent[q] = float(SHELL_TANGENTS) * luminance(hot - hot_before);
#if SHELL_KEY_LIGHTS > 0
        for (int m = 0; m < SHELL_KEY_LIGHTS; ++m) {
            int j = u_key_index[m];
            vec2 sh = sample_shadow(i, j);
            vec3 direct = srbf_light_radiance(p, u_d_f, j, vec2(1.0, 0.0));
            vec3 loss;
            vec3 forward = shell_light_forward(p, u_d_f, j, sh.y, loss);
            key_direct[m] += direct * (1.0 / float(SHELL_TANGENTS));
            key_forward[m] += forward * (1.0 / float(SHELL_TANGENTS));
            key_loss[m] += loss * (1.0 / float(SHELL_TANGENTS));
            // This tangent's weight at the axis's shadow: for texels 8, 10..13 and the shadow AOV only.
            vec3 wj = direct * sh.x + max(exp(-sh.y * loss) - vec3(sh.x), vec3(0.0)) * forward;
            float lum = light_luminance(j);
            visible += lum * sh.x;
            total += lum;
            float lw = luminance(wj);
            tangent_lum[q] += lw;
            vec3 l = lights[j].direction_lambda.xyz;
            float psi = sector_azimuth(l, T, r0);
            float lp = shell_light_spread(j, T);
            float d1 = exp(-0.25 * lp * lp);
            float d2 = d1 * d1 * d1 * d1;
            tangent_c1[q] += lw * d1 * cos(psi);
            tangent_s1[q] += lw * d1 * sin(psi);
            tangent_c2[q] += lw * d2 * cos(2.0 * psi);
            tangent_s2[q] += lw * d2 * sin(2.0 * psi);
        }
#endif
    }
    if (SHELL_TANGENTS == 1) {
        tangent_lum = vec4(tangent_lum.x);
        tangent_c1 = vec4(tangent_c1.x);
        tangent_s1 = vec4(tangent_s1.x);
        tangent_c2 = vec4(tangent_c2.x);
        tangent_s2 = vec4(tangent_s2.x);
        hot_tangent = vec4(hot_tangent.x);
    }
    float v[32];
    v[0] = C[0].x; v[1] = C[0].y; v[2] = C[0].z;
    for (int k = 1; k <= 4; ++k) {
        int o = 3 + 6 * (k - 1);
        v[o] = C[k].x; v[o + 1] = C[k].y; v[o + 2] = C[k].z;
        v[o + 3] = S[k].x; v[o + 4] = S[k].y; v[o + 5] = S[k].z;
    }
    v[27] = total > 0.0 ? visible / total : 1.0;
    v[28] = own_norm > 0.0 ? own_weight / own_norm : 1.0;
#ifdef SHELL_CULL_LIGHTS
    v[29] = float(kept_count);
#else
    v[29] = float(u_light_count);
#endif
    // The own cluster's depth toward the hair's inside, in the sample's frame (r0, T × r0) as the sums' azimuths are.
    vec3 inner = sample_inner(i);
    v[30] = dot(inner, r0);
    v[31] = dot(inner, cross(T, r0));
    for (int m = 0; m < 8; ++m)
        imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + m), vec4(v[4 * m], v[4 * m + 1], v[4 * m + 2], v[4 * m + 3]));
    imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 8), tangent_lum);
    imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 10), tangent_c1);
    imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 11), tangent_s1);
    imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 12), tangent_c2);
    imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 13), tangent_s2);
#if SHELL_KEY_LIGHTS > 0
    for (int m = 0; m < SHELL_KEY_LIGHTS; ++m) {
        imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 14 + 3 * m), vec4(key_direct[m], 0.0));
        imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 15 + 3 * m), vec4(key_forward[m], 0.0));
        imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 16 + 3 * m), vec4(key_loss[m], 0.0));
    }
#endif
    vec3 a_f = fetch_ms_forward(acos(clamp(1.0 / v[28], 0.0, 1.0)), hp.sigma_a).rgb;
    imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + 9), vec4(vec3(1.0) - a_f, 0.0));
    imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + LIGHTING_HOT_TEXEL), vec4(hot, 0.0));
    imageStore(u_out, ivec2(used, cluster * LIGHTING_TEXELS + LIGHTING_HOT_TEXEL + 1), hot_tangent);
}
