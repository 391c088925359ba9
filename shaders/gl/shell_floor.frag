// The trivial-shader floor of `coif bench render`: the same shells, the same blending, a constant colour.
layout(location = 0) out vec4 o_color;
in vec2 v_texcoord;
void main() { o_color = vec4(0.05 * v_texcoord.x, 0.05, 0.05, 0.1); }
