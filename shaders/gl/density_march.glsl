// The shadow grid as the GLSL marches read it (online/shells/shadow_grid.h DensityGrid): the fibres' projected length
// density along a direction, and the span of a ray inside the grid's box. Written once for the shadow pass
// (shell_shadow.comp) and the key lights' volumes (shell_key_light.comp).
#ifndef COIF_SHADERS_GL_DENSITY_MARCH_GLSL
#define COIF_SHADERS_GL_DENSITY_MARCH_GLSL

// dᵀMd = m·(dx², dy², dz², 2 dx dy) + o·(2 dx dz, 2 dy dz) for the unit direction d (shadow_grid.cpp
// projected_length_density): its two factors, once per ray.
struct MarchDirection {
    vec4 dd;
    vec2 doff;
};
MarchDirection march_direction(vec3 d) {
    MarchDirection m;
    m.dd = vec4(d * d, 2.0 * d.x * d.y);
    m.doff = vec2(2.0 * d.x * d.z, 2.0 * d.y * d.z);
    return m;
}

// √(tr M (tr M − dᵀMd)) of the grid (M's (xx, yy, zz, xy) in `density`, (xz, yz) in `density_off`) at texture
// coordinates uvw: the fibres' length per unit volume projected across d.
float projected_density(sampler3D density, sampler3D density_off, vec3 uvw, MarchDirection d) {
    vec4 m = textureLod(density, uvw, 0.0);
    float trace = m.x + m.y + m.z;
    float along = dot(m, d.dd) + dot(textureLod(density_off, uvw, 0.0).rg, d.doff);
    return sqrt(max(trace * (trace - along), 0.0));
}

// The span [a, b] of the ray p + s d, s ≥ 0, inside the box [lo, lo + extent]; b ≤ a where the ray misses it.
void ray_box_span(vec3 p, vec3 d, vec3 lo, vec3 extent, out float a, out float b) {
    vec3 inv = 1.0 / vec3(abs(d.x) > 1e-8 ? d.x : 1e-8, abs(d.y) > 1e-8 ? d.y : 1e-8, abs(d.z) > 1e-8 ? d.z : 1e-8);
    vec3 t0 = (lo - p) * inv;
    vec3 t1 = (lo + extent - p) * inv;
    vec3 tn = min(t0, t1);
    vec3 tf = max(t0, t1);
    a = max(max(max(tn.x, tn.y), tn.z), 0.0);
    b = min(min(tf.x, tf.y), tf.z);
}

#endif
