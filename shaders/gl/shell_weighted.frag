// The weighted blended compositing (online/weighted_blend.h; McGuire and Bavoil 2013): every shell fragment, shaded by
// shell_shade.glsl exactly as shell.frag shades it, adds its weighted premultiplied colour into the accumulation target
// and multiplies its transmittance into the revealage target, in any order.
#include "shaders/gl/shell_shade.glsl"
#include "shaders/gl/scene_depth.glsl"

in vec3 v_position;
in vec3 v_tangent;
in vec3 v_normal;
in vec3 v_axis_normal;
in vec2 v_texcoord;
flat in uvec2 v_info;

// The hair's eye distances in this view, in the shells' space: (nearest, 1 / (farthest − nearest)).
uniform vec2 u_depth_range;

layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec4 o_revealage;

// The weight of a fragment at z, its eye distance normalised to the hair's depth range in the view (0 nearest, 1
// farthest): α e^(−60 z). McGuire and Bavoil's eq. 9, α max(10⁻², 3·10³ (1 − z)³), falls too slowly across the few
// per cent of the range that one pixel's ~40 layers span, so the deep, shadowed layers weigh almost as much as the
// front ones (24.9 dB blurred PSNR against exact on the default scene, blue at 0.69 of exact's). Measured with
// e^(−kz) (docs/renderer.md "Decision 4"): k = 10, 30, 60, 100, 200 gave 25.6, 28.1, 30.2, 28.6, 27.1 dB; 60 is kept.
// The floor keeps the weight a normal float.
float blend_weight(float alpha, float z) {
    return alpha * max(exp(-60.0 * z), 1e-30);
}

void main() {
    if (behind_scene()) discard;
    vec4 color = shell_shade(v_position, v_tangent, v_normal, v_axis_normal, v_texcoord, v_info);
    float z = clamp((distance(v_position, u_eye) - u_depth_range.x) * u_depth_range.y, 0.0, 1.0);
    o_accum = color * blend_weight(color.a, z);
    o_revealage = vec4(color.a);
}
