// The weighted blended compositing's resolve (online/weighted_blend.h), with fullscreen.vert: the weighted mean colour
// of the pixel's fragments times their coverage 1 − Π(1 − α), over the background (opaque) or, with u_over, premultiplied
// for blending over a host's frame. With KBUFFER_SLOTS, the k-buffer's: its slots exactly in front of that tail. u_origin: the viewport's origin in the framebuffer (the targets are the viewport's size).
uniform sampler2D u_accum;
uniform sampler2D u_revealage;
uniform ivec2 u_origin;
uniform vec3 u_background;
uniform int u_over;
layout(location = 0) out vec4 o_color;
#ifdef KBUFFER_SLOTS
// The k-buffer compositing: the pixel's nearest fragments, premultiplied, nearest first (empty slots are 0), in front of
// the weighted tail.
layout(binding = 2, rgba16f) uniform readonly image2DArray u_slot_color;
#endif

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy) - u_origin;
    vec3 front = vec3(0.0);  // the slots' "over", front to back, and the transmittance through them
    float through = 1.0;
#ifdef KBUFFER_SLOTS
    for (int i = 0; i < KBUFFER_SLOTS; ++i) {
        vec4 c = imageLoad(u_slot_color, ivec3(texel, i));
        front += through * c.rgb;
        through *= 1.0 - c.a;
    }
#endif
    vec4 accum = texelFetch(u_accum, texel, 0);
    float transmittance = texelFetch(u_revealage, texel, 0).r;
    vec3 mean = accum.a > 0.0 ? accum.rgb / accum.a : vec3(0.0);
    vec3 color = front + through * mean * (1.0 - transmittance);
    transmittance *= through;
    o_color = u_over != 0 ? vec4(color, 1.0 - transmittance) : vec4(color + u_background * transmittance, 1.0);
}
