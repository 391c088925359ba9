// Copies a texture of the viewport's size into it, texel for pixel (with fullscreen.vert); u_origin: the viewport's
// origin in the framebuffer.
uniform sampler2D u_image;
uniform ivec2 u_origin;
layout(location = 0) out vec4 o_color;
void main() { o_color = texelFetch(u_image, ivec2(gl_FragCoord.xy) - u_origin, 0); }
