// The lit strand renderer (online/strand_renderer.h): a fragment of a strand line is L_o — interpolated
// from the lighting pass's vertices, or with COIF_STRAND_PER_FRAGMENT evaluated here
// (strand_lighting.glsl) — with the fibre's pixel coverage 2r/p as alpha, premultiplied.
#ifdef COIF_STRAND_PER_FRAGMENT
#include "shaders/gl/strand_lighting.glsl"
#endif

in vec3 v_position;
in vec3 v_tangent;
in vec3 v_radiance;
in float v_depth;
uniform float u_coverage_scale;  // r · height / tan(fov/2): 2r/p = u_coverage_scale / z
layout(location = 0) out vec4 o_color;

void main() {
#ifdef COIF_STRAND_PER_FRAGMENT
    vec3 L = strand_radiance(v_position, v_tangent);
#else
    vec3 L = v_radiance;
#endif
    float alpha = min(1.0, u_coverage_scale / max(v_depth, 1e-6));
    o_color = vec4(L * alpha, alpha);
}
