// Exact-compositing capture (docs/renderer.md decision 4): every shell fragment, shaded by
// shell_shade.glsl exactly as shell.frag shades it, is appended to its pixel's linked list instead of
// being blended. online/fragment_lists.h reads the lists back (CPU reference) or resolves them on the
// GPU (shell_abuffer_resolve.comp).
//
//   u_heads   r32ui, one per pixel: index of the pixel's last appended node, kFragmentListEnd if none
//   counter   atomic counter: fragments seen; nodes at or beyond u_capacity are counted, not stored
//   colors    node → premultiplied RGBA as two packHalf2x16 (the precision of the RGBA16F target the
//             blended modes write; 8 bytes, so llvmpipe's 128 MiB storage blocks hold 16 M fragments)
//   links     node → (eye distance as float bits, index of the next node of the same pixel)
#include "shaders/gl/shell_shade.glsl"
#include "shaders/gl/scene_depth.glsl"
#include "shaders/gl/fragment_distance.glsl"

in vec3 v_position;
in vec3 v_tangent;
in vec3 v_normal;
in vec3 v_axis_normal;
in vec2 v_texcoord;
flat in uvec2 v_info;

layout(binding = 0, r32ui) uniform coherent uimage2D u_heads;
layout(binding = 0, offset = 0) uniform atomic_uint u_fragment_count;
layout(std430, binding = 6) writeonly buffer FragmentColors { uvec2 fragment_colors[]; };
layout(std430, binding = 7) writeonly buffer FragmentLinks { uvec2 fragment_links[]; };
uniform uint u_capacity;

void main() {
    if (behind_scene()) discard;
    vec4 color = shell_shade(v_position, v_tangent, v_normal, v_axis_normal, v_texcoord, v_info);
    uint node = atomicCounterIncrement(u_fragment_count);
    if (node >= u_capacity) return;  // overflow: counted by the counter, reported by the host
    uint next = imageAtomicExchange(u_heads, ivec2(gl_FragCoord.xy), node);
    fragment_colors[node] = uvec2(packHalf2x16(color.rg), packHalf2x16(color.ba));
    fragment_links[node] = uvec2(eye_distance_bits(v_position, u_eye), next);
}
