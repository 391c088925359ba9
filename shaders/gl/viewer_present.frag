// The viewer's display pass (with fullscreen.vert): the linear frame, scaled to the window, tone-mapped to sRGB as
// coif render writes a PNG (shaders/display.glsl).
#include "shaders/display.glsl"

uniform sampler2D u_image;  // linear RGBA, bilinear (a frame drawn smaller while the camera moves is scaled up)
uniform vec2 u_size;        // the window's framebuffer size
uniform float u_exposure_scale;
layout(location = 0) out vec4 o_color;

void main() {
    vec3 c = texture(u_image, gl_FragCoord.xy / u_size).rgb;
    o_color = vec4(tone_map_srgb(c.r, u_exposure_scale), tone_map_srgb(c.g, u_exposure_scale),
                   tone_map_srgb(c.b, u_exposure_scale), 1.0);
}
