// Layer meshes of the SATF shells (online/shell_renderer.h). One draw per (cluster, layer, facing);
// the cluster is the instance (attribute 5, divisor 1, selected by the draw's base instance).
// SHELL_LIGHTING == 1: the lighting pass's sums are read here, per vertex, and interpolated (the
// lighting rows are the mesh rows, so this equals reading them per fragment; docs/renderer.md).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_tangent;
layout(location = 2) in vec3 a_normal;
layout(location = 3) in vec2 a_texcoord;     // (u / 2π, t)
layout(location = 4) in vec3 a_axis_normal;  // the cylinder's frame normal n(t): reference axis of azimuths
layout(location = 5) in uint a_cluster;

struct ShellInstance {
    mat4 model;   // world = model · prototype coordinates (similarity, then the scene orientation)
    uvec4 info;   // x: first sector of the prototype, y: cluster index (lighting rows)
};
layout(std430, binding = 0) readonly buffer Instances { ShellInstance instances[]; };

uniform mat4 u_view_projection;

out vec3 v_position;
out vec3 v_tangent;
out vec3 v_normal;
out vec3 v_axis_normal;
out vec2 v_texcoord;
flat out uvec2 v_info;

#if defined(SHELL_LIGHTING) && SHELL_LIGHTING == 1
#include "shaders/gl/shell_lighting_fetch.glsl"
out vec4 v_L0;
out vec4 v_L1;
out vec4 v_L2;
out vec4 v_L3;
out vec4 v_L4;
out vec4 v_L5;
out vec4 v_L6;
out vec3 v_L7;  // texel 7's x, z, w: the lights' mean own_cluster_stretch, the own cluster's inner depth (shell_lighting.comp)
#if defined(SHELL_TILT_PICK) && SHELL_TILT_PICK == 1
out vec4 v_L8;   // texel 8: each fibre tangent's lum(C_0)
out vec4 v_L10;  // texels 10..13: each tangent's lum(C_1), lum(S_1), lum(C_2), lum(S_2)
out vec4 v_L11;
out vec4 v_L12;
out vec4 v_L13;
#endif
#if defined(SHELL_OWN) && SHELL_OWN == 2
out vec3 v_L9;   // texel 9: the fibres' forward loss 1 − ā_f
#endif
#if defined(SHELL_HOT_SPOT) && SHELL_HOT_SPOT > 0
out vec3 v_hot;  // texel LIGHTING_HOT_TEXEL: the lights' hot spot
#if defined(SHELL_TILT_PICK) && SHELL_TILT_PICK == 1
out vec4 v_hot_tangent;  // the next texel: each fibre tangent's share of it in luminance
#endif
#endif
#if defined(SHELL_KEY_LIGHTS) && SHELL_KEY_LIGHTS > 0
#include "shaders/gl/key_light_volume.glsl"
#include "shaders/gl/lighting_samples.glsl"  // the clusters' axes (key_slab)
uniform float u_layer_rho;  // this layer's slab, in cluster radii: the mesh's surface and the next layer in's
uniform float u_inner_rho;
uniform vec3 u_eye;
out vec3 v_key_weight[SHELL_KEY_LIGHTS];  // each key light's weight over the vertex's slab (key_light_weight)
#if defined(SHELL_FOLD) && SHELL_FOLD == 1
out vec3 v_key_weight_inner[SHELL_KEY_LIGHTS];  // the folded inner layer's, over its own slab on the same line
#endif
#endif
#endif

#if defined(SHELL_FOLD) && SHELL_FOLD == 1
// The folded inner layer is found where the view ray meets it (shell_shade.glsl): the vertex's offset from its cluster's
// axis and the cross-section's ellipse (axis e1, half-axes A, B), from the lighting samples around its t.
#include "shaders/gl/lighting_samples.glsl"
#if !defined(SHELL_LIGHTING) || SHELL_LIGHTING != 1
uniform int u_lighting_rows;
#endif
out vec3 v_axis_offset;
out vec3 v_ellipse_e1;
out vec2 v_ellipse_ab;
#endif

void main() {
    ShellInstance inst = instances[a_cluster];
    vec4 world = inst.model * vec4(a_position, 1.0);
    mat3 rot = mat3(inst.model);  // uniform scale: directions only need normalising
    v_position = world.xyz;
    v_tangent = rot * a_tangent;
    v_normal = rot * a_normal;
    v_axis_normal = rot * a_axis_normal;
    v_texcoord = a_texcoord;
    v_info = inst.info.xy;
#if defined(SHELL_LIGHTING) && SHELL_LIGHTING == 1
    v_L0 = lighting_fetch(a_texcoord.y, inst.info.y, 0);
    v_L1 = lighting_fetch(a_texcoord.y, inst.info.y, 1);
    v_L2 = lighting_fetch(a_texcoord.y, inst.info.y, 2);
    v_L3 = lighting_fetch(a_texcoord.y, inst.info.y, 3);
    v_L4 = lighting_fetch(a_texcoord.y, inst.info.y, 4);
    v_L5 = lighting_fetch(a_texcoord.y, inst.info.y, 5);
    v_L6 = lighting_fetch(a_texcoord.y, inst.info.y, 6);
    v_L7 = lighting_fetch(a_texcoord.y, inst.info.y, 7).xzw;
#if defined(SHELL_TILT_PICK) && SHELL_TILT_PICK == 1
    v_L8 = lighting_fetch(a_texcoord.y, inst.info.y, 8);
    v_L10 = lighting_fetch(a_texcoord.y, inst.info.y, 10);
    v_L11 = lighting_fetch(a_texcoord.y, inst.info.y, 11);
    v_L12 = lighting_fetch(a_texcoord.y, inst.info.y, 12);
    v_L13 = lighting_fetch(a_texcoord.y, inst.info.y, 13);
#endif
#if defined(SHELL_OWN) && SHELL_OWN == 2
    v_L9 = lighting_fetch(a_texcoord.y, inst.info.y, 9).xyz;
#endif
#if defined(SHELL_HOT_SPOT) && SHELL_HOT_SPOT > 0
    v_hot = lighting_fetch(a_texcoord.y, inst.info.y, LIGHTING_HOT_TEXEL).xyz;
#if defined(SHELL_TILT_PICK) && SHELL_TILT_PICK == 1
    v_hot_tangent = lighting_fetch(a_texcoord.y, inst.info.y, LIGHTING_HOT_TEXEL + 1);
#endif
#endif
#if defined(SHELL_KEY_LIGHTS) && SHELL_KEY_LIGHTS > 0
    {
        vec3 axis = sample_axis_point(a_texcoord.y, inst.info.y, u_lighting_rows);
        float spacing = u_layer_rho - u_inner_rho;
        vec3 to_eye = normalize(u_eye - world.xyz);
        KeySlab slab = key_slab(world.xyz, axis, u_layer_rho, spacing, u_layer_rho, to_eye);
#if defined(SHELL_FOLD) && SHELL_FOLD == 1
        KeySlab inner = key_slab(world.xyz, axis, u_layer_rho, spacing, u_inner_rho, to_eye);
#endif
        for (int m = 0; m < SHELL_KEY_LIGHTS; ++m) {
            vec3 direct = lighting_fetch(a_texcoord.y, inst.info.y, 14 + 3 * m).rgb;
            vec3 forward = lighting_fetch(a_texcoord.y, inst.info.y, 15 + 3 * m).rgb;
            vec3 loss = lighting_fetch(a_texcoord.y, inst.info.y, 16 + 3 * m).rgb;
            v_key_weight[m] = key_light_weight(m, slab, direct, forward, loss);
#if defined(SHELL_FOLD) && SHELL_FOLD == 1
            v_key_weight_inner[m] = key_light_weight(m, inner, direct, forward, loss);
#endif
        }
    }
#endif
#endif
#if defined(SHELL_FOLD) && SHELL_FOLD == 1
    {
        float tr = clamp(a_texcoord.y, 0.0, 1.0) * float(u_lighting_rows - 1);
        int row = min(int(tr), u_lighting_rows - 2);
        float f = tr - float(row);
        int first = int(inst.info.y) * u_lighting_rows + row;
        LightingSample s0 = samples[first], s1 = samples[first + 1];
        vec3 t0 = normalize(s0.tangent.xyz), t1 = normalize(s1.tangent.xyz);
        v_axis_offset = world.xyz - mix(s0.position.xyz, s1.position.xyz, f);
        v_ellipse_e1 = mix(sample_ellipse_axis(s0, t0), sample_ellipse_axis(s1, t1), f);
        v_ellipse_ab = mix(vec2(s0.position.w, s0.tangent.w), vec2(s1.position.w, s1.tangent.w), f);
    }
#endif
    gl_Position = u_view_projection * world;
}
