// The weighted blended compositing's resolve (online/weighted_blend.h), with fullscreen.vert: the weighted mean colour
// of the pixel's fragments times their coverage 1 − Π(1 − α), over the background (opaque) or, with u_over, premultiplied
// for blending over a host's frame. u_origin: the viewport's origin in the framebuffer (the targets are the viewport's size).
uniform sampler2D u_accum;
uniform sampler2D u_revealage;
uniform ivec2 u_origin;
uniform vec3 u_background;
uniform int u_over;
layout(location = 0) out vec4 o_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy) - u_origin;
    vec4 accum = texelFetch(u_accum, texel, 0);
    float transmittance = texelFetch(u_revealage, texel, 0).r;
    vec3 mean = accum.a > 0.0 ? accum.rgb / accum.a : vec3(0.0);
    float coverage = 1.0 - transmittance;
    o_color = u_over != 0 ? vec4(mean * coverage, coverage) : vec4(mean * coverage + u_background * transmittance, 1.0);
}
