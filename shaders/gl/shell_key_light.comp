// The key lights' shadow volumes (ShellSettings::key_lights, online/shell_passes.h KeyLightPass): for one light, the
// fibres met on the way from every point of the hair toward the light, n = 2r ∫ √(tr M (tr M − lᵀMl)) ds (the shadow
// pass's count, shell_shadow.comp, along the light's centre direction l only), on a grid aligned with the light. Each
// invocation is one column of that grid along l: it walks from the end nearest the light toward the far end and adds
// each voxel's fibres as it goes (Simpson's rule on half-voxel samples of the fine grid, online/shells/shadow_grid.h
// kKeyLightGridSize), so the whole volume costs two samples per voxel where a march from each point would cost a
// column each. The shells read it once per fragment (shell_shade.glsl SHELL_KEY_LIGHTS): every fibre of a cluster
// gets its own side's shadow, where the shadow pass marches from the cluster's axis and the own cluster's factor
// (shaders/lighting/own_cluster.glsl) models the side. docs/quality.md ("Key lights") measures it.
//
// With SHADOW_BODY the body's optical depth is added as the shadow pass adds it (at most u_body_max_depth per ray),
// read on the shadow grid that holds it, the stretch beyond the column's end toward the light included (the body can
// reach beyond the hair's box).
layout(local_size_x = 8, local_size_y = 8) in;
#ifndef SHADOW_BODY
#define SHADOW_BODY 0
#endif

#include "shaders/gl/density_march.glsl"

layout(r16f, binding = 0) writeonly uniform image3D u_out;

uniform sampler3D u_density;      // the fine grid's M per unit volume: (xx, yy, zz, xy)
uniform sampler3D u_density_off;  // (xz, yz)
uniform vec3 u_grid_min;          // the fine grid's corner and extent
uniform vec3 u_grid_extent;
uniform vec3 u_origin;            // the volume's corner: voxel (i, j, k)'s centre is u_origin + (i + ½, j + ½, k + ½) u_h in (e1, e2, l)
uniform vec3 u_e1;
uniform vec3 u_e2;
uniform vec3 u_l;                 // toward the light
uniform float u_h;                // voxel edge, world units
uniform ivec3 u_dims;
uniform float u_width;            // the fibres' diameter 2r
#if SHADOW_BODY
uniform sampler3D u_body;         // on the shadow grid
uniform vec3 u_body_min;
uniform vec3 u_body_extent;
uniform float u_body_step;        // the shadow grid's voxel
uniform float u_body_opacity;     // optical depth per world unit through a body voxel
uniform float u_body_max_depth;
#endif

float projected(vec3 p, MarchDirection d) {
    return projected_density(u_density, u_density_off, (p - u_grid_min) / u_grid_extent, d);
}

void main() {
    ivec2 column = ivec2(gl_GlobalInvocationID.xy);
    if (column.x >= u_dims.x || column.y >= u_dims.y) return;
    vec3 l = u_l;
    MarchDirection md = march_direction(l);
    vec3 base = u_origin + (float(column.x) + 0.5) * u_h * u_e1 + (float(column.y) + 0.5) * u_h * u_e2;
    float h = u_h;
    float fibres = 0.0;  // ∫ projected length density from the column's end to the current voxel's centre
    float body = 0.0;    // ∫ body occupancy, world units
#if SHADOW_BODY
    {   // The body beyond the column's end toward the light, to where the ray leaves the shadow grid.
        vec3 p = base + float(u_dims.z) * h * l;
        float a;
        float b;
        ray_box_span(p, l, u_body_min, u_body_extent, a, b);
        if (b > a) {
            int n = int(ceil((b - a) / u_body_step));
            float s = (b - a) / float(n);
            for (int k = 0; k < n; ++k)
                body += s * textureLod(u_body, (p + l * (a + (float(k) + 0.5) * s) - u_body_min) / u_body_extent, 0.0).r;
        }
    }
#endif
    // The column's end: half a voxel beyond the last centre, where the volume (which holds the fine grid, whose border
    // voxels are empty) holds no fibres.
    float above = projected(base + (float(u_dims.z) - 0.5) * h * l, md);  // at the last centre
    for (int k = u_dims.z - 1; k >= 0; --k) {
        vec3 p = base + (float(k) + 0.5) * h * l;
        float here = projected(p, md);
        if (k < u_dims.z - 1) {
            // Simpson's rule over the voxel between this centre and the one above.
            float middle = projected(p + 0.5 * h * l, md);
            fibres += h / 6.0 * (here + 4.0 * middle + above);
#if SHADOW_BODY
            body += h * 0.5 * (textureLod(u_body, (p - u_body_min) / u_body_extent, 0.0).r +
                               textureLod(u_body, (p + h * l - u_body_min) / u_body_extent, 0.0).r);
#endif
        }
        above = here;
        float n = u_width * fibres;
#if SHADOW_BODY
        n += min(u_body_opacity * body, u_body_max_depth);
#endif
        imageStore(u_out, ivec3(column, k), vec4(n, 0.0, 0.0, 0.0));
    }
}
