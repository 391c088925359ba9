// GPU resolve of the per-pixel fragment lists of shell_abuffer.frag (the "exact" compositing mode,
// docs/renderer.md decision 4): one invocation per pixel keeps the kResolveFragments nearest fragments
// sorted in a local array (insertion sort on (eye distance, node index)) and composites them "over"
// back to front onto the background (004 eq. 14), into an RGBA32F image. Fragments beyond the nearest
// kResolveFragments lie behind all kept ones: their product of (1 − α) is exact whatever the order,
// their colour is approximated by the α-weighted mean (weighted-average OIT), and the pixel is counted.
// The same order as the CPU reference (online/fragment_lists.cpp): farther first; at equal distance
// the lower node index first.
// A compute pass, not a full-screen fragment pass: as a fragment shader, Mesa 22.3's llvmpipe left the
// final loop after one iteration in some lanes (pixels beside empty ones); the compute path does not.
#ifndef kResolveFragments
#define kResolveFragments 32
#endif
const uint kFragmentListEnd = 0xffffffffu;

layout(binding = 0, r32ui) uniform readonly uimage2D u_heads;
layout(binding = 1, offset = 0) uniform atomic_uint u_pixels_over_limit;
layout(std430, binding = 6) readonly buffer FragmentColors { uvec2 fragment_colors[]; };
layout(std430, binding = 7) readonly buffer FragmentLinks { uvec2 fragment_links[]; };
uniform uint u_capacity;
uniform vec3 u_background;
// 0: the pixel composited over u_background, opaque (alpha 1). 1: over nothing, premultiplied, alpha = 1 − the
// fragments' transmittance, for blending (ONE, ONE_MINUS_SRC_ALPHA) over a host's frame (online/hair_renderer.h).
uniform int u_over;

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1, rgba32f) uniform writeonly image2D u_resolved;

vec4 fragment_color(uint node) {
    uvec2 halves = fragment_colors[node];
    return vec4(unpackHalf2x16(halves.x), unpackHalf2x16(halves.y));
}

// a lies in front of b (composited after it).
bool in_front(float da, uint ia, float db, uint ib) { return da < db || (da == db && ia > ib); }

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(u_heads)))) return;
    float depth[kResolveFragments];
    uint ids[kResolveFragments];
    int kept = 0;  // depth/ids[0 .. kept) sorted nearest first
    vec3 tail_sum = vec3(0.0);
    float tail_alpha = 0.0, tail_transmittance = 1.0;
    bool over_limit = false;
    uint node = imageLoad(u_heads, pixel).x;
    for (uint guard = 0u; guard < u_capacity; ++guard) {
        if (node == kFragmentListEnd || node >= u_capacity) break;
        uvec2 link = fragment_links[node];
        float d = uintBitsToFloat(link.x);
        uint candidate = node;
        node = link.y;
        bool insert = true;
        if (kept == kResolveFragments) {
            // Full: the farther of the candidate and the farthest kept fragment goes to the tail.
            over_limit = true;
            uint far = ids[kept - 1];
            if (in_front(d, candidate, depth[kept - 1], far)) {
                --kept;
            } else {
                far = candidate;
                insert = false;
            }
            vec4 c = fragment_color(far);
            tail_sum += c.rgb;
            tail_alpha += c.a;
            tail_transmittance *= 1.0 - c.a;
        }
        if (insert) {
            int j = kept;
            while (j > 0 && in_front(d, candidate, depth[j - 1], ids[j - 1])) {
                depth[j] = depth[j - 1];
                ids[j] = ids[j - 1];
                --j;
            }
            depth[j] = d;
            ids[j] = candidate;
            ++kept;
        }
    }
    if (over_limit) atomicCounterIncrement(u_pixels_over_limit);
    vec3 background = u_over != 0 ? vec3(0.0) : u_background;
    vec3 color = background * tail_transmittance;
    float transmittance = tail_transmittance;
    if (tail_alpha > 0.0) color += tail_sum / tail_alpha * (1.0 - tail_transmittance);
    for (int n = kept - 1; n >= 0; --n) {
        vec4 c = fragment_color(ids[n]);
        color = c.rgb + (1.0 - c.a) * color;
        transmittance *= 1.0 - c.a;
    }
    imageStore(u_resolved, pixel, vec4(color, u_over != 0 ? 1.0 - transmittance : 1.0));
}
