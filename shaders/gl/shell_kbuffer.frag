// The k-buffer compositing's second pass (online/weighted_blend.h): every shell fragment, shaded by shell_shade.glsl
// exactly as shell.frag shades it, goes into the slot that the first pass (shell_kbuffer_depth.frag) kept for its eye
// distance, if it is among the pixel's KBUFFER_SLOTS nearest; else it adds into the weighted blended tail (as
// shell_weighted.frag does).
#include "shaders/gl/shell_shade.glsl"
#include "shaders/gl/scene_depth.glsl"
#include "shaders/gl/weighted_weight.glsl"
#include "shaders/gl/fragment_distance.glsl"

in vec3 v_position;
in vec3 v_tangent;
in vec3 v_normal;
in vec3 v_axis_normal;
in vec2 v_texcoord;
flat in uvec2 v_info;

layout(binding = 1, r32ui) uniform readonly uimage2DArray u_slot_depth;
layout(binding = 2, rgba16f) uniform writeonly image2DArray u_slot_color;

layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec4 o_revealage;

void main() {
    if (behind_scene()) discard;
    vec4 color = shell_shade(v_position, v_tangent, v_normal, v_axis_normal, v_texcoord, v_info);
    uint key = eye_distance_bits(v_position, u_eye);
    ivec2 p = ivec2(gl_FragCoord.xy);
    int slot = -1;
    for (int i = 0; i < KBUFFER_SLOTS; ++i)
        if (slot < 0 && imageLoad(u_slot_depth, ivec3(p, i)).r == key) slot = i;
    if (slot >= 0) {
        imageStore(u_slot_color, ivec3(p, slot), color);
        o_accum = vec4(0.0);      // adds nothing to the tail
        o_revealage = vec4(0.0);  // multiplies its transmittance by 1
    } else {
        o_accum = color * blend_weight(color.a, weighted_depth(v_position));
        o_revealage = vec4(color.a);
    }
}
