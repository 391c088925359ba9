// Copies a texture of the framebuffer's size into it, texel for pixel (with fullscreen.vert).
uniform sampler2D u_image;
layout(location = 0) out vec4 o_color;
void main() { o_color = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0); }
