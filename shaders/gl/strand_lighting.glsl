// The lit strand renderer's shading (online/strand_renderer.h), for its per-vertex lighting pass
// (strand_lighting.comp) and its per-fragment mode (strand_lines.frag with COIF_STRAND_PER_FRAGMENT):
// the SRBF Marschner lighting of an unoccluded round fibre (shaders/lighting/srbf_shadowed.glsl with
// T̃ = 1, n = 0),
//   L_o = Σ_j L_j (𝓜_j + ∫G_j d_b 𝓜^L_j)   (000 eq. 2 without D; the multiple term when u_multiple)
// in the frame u = tangent, v = the view direction projected orthogonal to u (φo = 0), w = u × v.
#ifndef COIF_SHADERS_GL_STRAND_LIGHTING_GLSL
#define COIF_SHADERS_GL_STRAND_LIGHTING_GLSL

#include "shaders/gl/srbf_lights.glsl"

uniform vec3 u_eye;

vec3 strand_radiance(vec3 position, vec3 tangent) {
    vec3 u = normalize(tangent);
    vec3 V = normalize(u_eye - position);
    vec3 vp = V - dot(V, u) * u;
    if (dot(vp, vp) < 1e-12) vp = abs(u.x) < 0.9 ? vec3(1.0, 0.0, 0.0) - u.x * u : vec3(0.0, 1.0, 0.0) - u.y * u;
    SrbfPoint p = srbf_point(u_hair, V, u, normalize(vp));
    vec3 L = vec3(0.0);
    for (int j = 0; j < u_light_count; ++j) L += srbf_light_radiance(p, MS_DEFAULT_D_F, j, vec2(1.0, 0.0));
    return L;
}

#endif
