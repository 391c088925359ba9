// The k-buffer compositing's first pass (online/weighted_blend.h): the eye distances of each pixel's KBUFFER_SLOTS
// nearest fragments, kept in increasing order in the pixel's slots by an atomic-minimum cascade (each slot keeps the
// smaller of what it held and what arrives, and the larger goes on to the next slot; the slots start at the largest
// uint, "empty"). No shading, no colour output.
#include "shaders/gl/scene_depth.glsl"
#include "shaders/gl/fragment_distance.glsl"

in vec3 v_position;

layout(binding = 1, r32ui) uniform coherent uimage2DArray u_slot_depth;
uniform vec3 u_eye;

void main() {
    if (behind_scene()) discard;
    uint d = eye_distance_bits(v_position, u_eye);
    ivec2 p = ivec2(gl_FragCoord.xy);
    for (int i = 0; i < KBUFFER_SLOTS; ++i) {
        uint held = imageAtomicMin(u_slot_depth, ivec3(p, i), d);
        if (held == 0xffffffffu) break;  // the slot was empty: d is placed
        d = max(held, d);
    }
}
