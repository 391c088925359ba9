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


layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec4 o_revealage;

#include "shaders/gl/weighted_weight.glsl"

void main() {
    if (behind_scene()) discard;
    vec4 color = shell_shade(v_position, v_tangent, v_normal, v_axis_normal, v_texcoord, v_info);
    o_accum = color * blend_weight(color.a, weighted_depth(v_position));
    o_revealage = vec4(color.a);
}
