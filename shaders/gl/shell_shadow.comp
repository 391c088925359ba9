// Shadows between clusters (DESIGN.md decision 5) for the shell renderer's lighting pass: per
// lighting sample and SRBF light, the light's unoccluded fraction T̃ and the fibres met n on the way
// (shaders/lighting/srbf_shadowed.glsl), marched through the grid of the strands' length by direction
// (online/shells/shadow_grid.h): τ = 2r ∫ √(tr M (tr M − dᵀMd)) ds is the number of fibres of radius r a ray
// along d is expected to meet, as the reference's fibres meet it. They depend on the hair, the lights and r
// only — not on the view or the scattering parameters — so the renderer runs this pass when those change.
//
// The light's lobe is sampled by `u_rays` rays, each the direction of one of u_rays equal shares of the light's energy
// (stratified by the lobe's own distribution, shaders/envmap.glsl srbf_lobe_cos: for a narrow light at 0.27 to 1.6 λ
// from its centre; a wide one, λ = 2, sends 38 % of its light from the far hemisphere and three of 7 rays there);
// T̃ = mean exp(−τ), n = mean τ over the rays. (A centre and a ring at min(λ, 1) rad, the earlier rule, missed the
// far side of a wide light's lobe; docs/quality.md, "Each light's shadow rays by its own energy".) Each ray starts
// where it leaves the own cluster (own_cluster_exit: its elliptic cross-section's radius in the ray's direction over the
// sine of the ray's angle to the axis, at most 4 such radii), with u_narrow_start at most its narrow half-axis out, so
// that the neighbours overlapping the ellipse count (own_cluster_shadow_start), plus two voxels for the grid's blur: the
// own cluster shades each of its fibres by the fibre's side toward the light, in the shells pass
// (shaders/lighting/own_cluster.glsl). Rays from the axis through the own cluster, the
// earlier rule, gave every fibre of a cluster its axis's light: docs/quality.md measures both.
//
// The rays are the shadows of the fibres the camera sees, on the cluster's outer side: they leave from the point
// u_outward of the cluster's radius out from the axis toward the hair's outside (outward_shift), not from the axis. A
// light that grazes the hair, as most of a sky does at the crown, crosses the neighbours lying beside the axis but
// passes above the outermost fibres' (docs/quality.md, "The shadows on the cluster's outer side").
//
// With u_inner, each sample also gets the own cluster's depth toward the hair's inside (inner_depth), after the (T̃, n) of
// every sample and light: the fragments on that side take it as their own cluster's depth (ShellSettings::
// own_cluster_inner; docs/quality.md, "The cluster's side toward the hair's inside").
//
// Only the lit samples are marched: every u_lit_step-th of each cluster's u_rows (ShellSettings::lighting_step, as the
// lighting pass lights them), u_used per cluster. SHADOW_FILL 1 is the second dispatch when u_lit_step > 1: each sample
// between two lit ones gets their linear interpolation, so that every sample holds its shadows (for the per-fragment
// lighting, which the renderer marches at step 1 anyway, and for read_shadows), and its inner depth.
layout(local_size_x = 64) in;
#ifndef SHADOW_BODY
#define SHADOW_BODY 0
#endif
#ifndef SHADOW_FILL
#define SHADOW_FILL 0
#endif

#include "shaders/envmap.glsl"
#include "shaders/gl/density_march.glsl"
#include "shaders/gl/lighting_samples.glsl"
#include "shaders/lighting/luts_gl.glsl"
#include "shaders/lighting/own_cluster.glsl"
struct GpuLight {
    vec4 direction_lambda;
    vec4 radiance;
};
layout(std430, binding = 3) readonly buffer Lights { GpuLight lights[]; };
// (T̃, n) per sample × light, then inner_depth per sample as two vec2 (online/shell_passes.h ShellGpu::shadows)
layout(std430, binding = 4) buffer Shadows { vec2 shadows[]; };

uniform sampler3D u_density;      // M per unit volume: (xx, yy, zz, xy)
uniform sampler3D u_density_off;  // (xz, yz)
uniform vec3 u_grid_min;
uniform vec3 u_grid_extent;
uniform float u_step;         // world units per march step (one voxel)
uniform float u_width;        // the fibres' diameter 2r
uniform int u_sample_count;
uniform int u_light_count;
uniform int u_rays;
uniform int u_narrow_start;  // 1: rays start at most the own cluster's narrow half-axis out (ShellSettings::shadow_neighbours)
uniform float u_outward;     // the share of the cluster's radius the rays start toward the hair's outside (shadow_outward)
uniform int u_inner;         // 1: write inner_depth per sample (ShellSettings::own_cluster_inner > 0), else zeros
uniform int u_rows;   // lighting samples per cluster
uniform int u_lit_step;  // every u_lit_step-th is lit (the last is)
uniform int u_used;   // lit samples per cluster
#if SHADOW_BODY
uniform sampler3D u_body;
uniform float u_body_opacity;    // optical depth per world unit through a body voxel
uniform float u_body_max_depth;  // per ray
#endif

#include "shaders/gl/inner_depths.glsl"

void write_inner(int i, vec3 v) {
    int at = inner_depth_at(u_sample_count, u_light_count, i);
    shadows[at] = v.xy;
    shadows[at + 1] = vec2(v.z, 0.0);
}
vec3 read_inner(int i) { return inner_depth_read(inner_depth_at(u_sample_count, u_light_count, i)); }

const float GOLDEN_ANGLE = 2.39996322973;  // π (3 − √5): successive rays' turn about the light's axis

// (the fibres' projected length along the ray, the body's optical depth along it)
vec2 optical_depth(vec3 p, vec3 d) {
    float a;
    float b;
    ray_box_span(p, d, u_grid_min, u_grid_extent, a, b);
    if (b <= a) return vec2(0.0);
    int n = int(ceil((b - a) / u_step));
    float h = (b - a) / float(n);
    float sum = 0.0;
    float body = 0.0;
    MarchDirection md = march_direction(d);
    for (int k = 0; k < n; ++k) {
        vec3 uvw = (p + d * (a + (float(k) + 0.5) * h) - u_grid_min) / u_grid_extent;
        sum += projected_density(u_density, u_density_off, uvw, md);
#if SHADOW_BODY
        body += textureLod(u_body, uvw, 0.0).r;
#endif
    }
    return vec2(sum, body) * h;
}

// The hair's outside at a sample, across its axis: the unit direction, how clearly the density falls that way (0 where
// it does not: no outside), and the own cluster's ellipse radius that way.
struct Outside {
    vec3 dir;
    float weight;
    float radius;
};

// The hair's outside at sample s, across its axis T: down the gradient of the strands' length per volume (tr M), by
// central differences just outside the own cluster: along each world axis, the ellipse's radius that way across T plus
// two voxels either side (two voxels alone for an axis within 17° of T), so that the hair around the cluster sets it and
// not its own fibres. The weight is |∇ tr M| times four voxels against the mean tr M of the six points (at most 1): 0 in
// hair of even density, which has no outer side to speak of, and where there is no gradient. Measured against the rule
// with two voxels alone: docs/quality.md.
Outside hair_outside(LightingSample s, vec3 T, vec3 e1_own) {
    Outside o = Outside(vec3(0.0), 0.0, 0.0);
    vec3 p = s.position.xyz;
    vec3 g = vec3(0.0);
    float mean = 0.0;
    for (int a = 0; a < 3; ++a) {
        vec3 e = vec3(0.0);
        e[a] = 1.0;
        vec3 across = e - dot(e, T) * T;
        float len = length(across);
        // The ellipse's radius that way: own_cluster_exit of a direction across the axis (its stretch is 1).
        float h = 2.0 * u_step + (len > 0.3 ? own_cluster_exit(across / len, T, e1_own, s.position.w, s.tangent.w) : 0.0);
        e[a] = h;
        vec4 up = textureLod(u_density, (p + e - u_grid_min) / u_grid_extent, 0.0);
        vec4 down = textureLod(u_density, (p - e - u_grid_min) / u_grid_extent, 0.0);
        float m_up = up.x + up.y + up.z, m_down = down.x + down.y + down.z;
        g[a] = (m_up - m_down) / (2.0 * h);
        mean += (m_up + m_down) / 6.0;
    }
    g -= dot(g, T) * T;
    float slope = length(g);
    if (!(slope > 0.0) || !(mean > 0.0)) return o;
    o.dir = -g / slope;
    o.weight = min(slope * 4.0 * u_step / mean, 1.0);
    o.radius = own_cluster_exit(o.dir, T, e1_own, s.position.w, s.tangent.w);  // across the axis: the ellipse's radius
    return o;
}

// Where sample s's rays leave from, relative to its axis point: u_outward of the cluster's radius toward the hair's
// outside, weighed by how clearly the hair has an outside there.
vec3 outward_shift(Outside o) { return (u_outward * o.weight * o.radius) * o.dir; }

// The own cluster's fibres met across it toward the hair's outside, per cluster radius, as a vector: weight · τ_out ·
// the outside's direction, with τ_out half the grid's count along the ellipse's diameter that way. The shells shade the
// cluster's side toward the hair's inside by it (shaders/lighting/own_cluster.glsl own_cluster_tau): there the light
// from outside crosses the whole cluster, whose fibres the records' coverage undercounts.
vec3 inner_depth(LightingSample s, Outside o) {
    if (!(o.weight > 0.0)) return vec3(0.0);
    vec3 from = s.position.xyz - o.radius * o.dir;
    int n = max(int(ceil(4.0 * o.radius / u_step)), 2);  // half-voxel steps over the diameter
    float h = 2.0 * o.radius / float(n);
    MarchDirection md = march_direction(o.dir);
    float sum = 0.0;
    for (int k = 0; k < n; ++k)
        sum += projected_density(u_density, u_density_off, (from + o.dir * ((float(k) + 0.5) * h) - u_grid_min) / u_grid_extent, md);
    return (o.weight * 0.5 * u_width * sum * h) * o.dir;
}

#if SHADOW_FILL
void main() {
    int id = int(gl_GlobalInvocationID.x);
    if (id >= u_sample_count * u_light_count) return;
    int i = id / u_light_count;
    int j = id - i * u_light_count;
    int row = i - (i / u_rows) * u_rows;
    int lower = (row / u_lit_step) * u_lit_step;
    if (lower == row) return;  // lit
    int first = i - row + lower;
    float f = float(row - lower) / float(u_lit_step);
    shadows[id] = mix(shadows[first * u_light_count + j], shadows[(first + u_lit_step) * u_light_count + j], f);
    if (j == 0) write_inner(i, mix(read_inner(first), read_inner(first + u_lit_step), f));
}
#else
void main() {
    int id = int(gl_GlobalInvocationID.x);
    int per_cluster = u_used * u_light_count;
    int cluster = id / per_cluster;
    if (cluster * u_rows >= u_sample_count) return;
    int rest = id - cluster * per_cluster;
    int used = rest / u_light_count;
    int j = rest - used * u_light_count;
    int i = cluster * u_rows + used * u_lit_step;  // the lit sample
    LightingSample s = samples[i];
    vec3 T = normalize(s.tangent.xyz);
    vec3 e1_own = sample_ellipse_axis(s, T);
    vec3 l = normalize(lights[j].direction_lambda.xyz);
    float lambda = lights[j].direction_lambda.w;
    vec3 e1 = normalize(abs(l.x) < 0.9 ? cross(l, vec3(1.0, 0.0, 0.0)) : cross(l, vec3(0.0, 1.0, 0.0)));
    vec3 e2 = cross(l, e1);
    float direct = 0.0;
    float fibres = 0.0;
    // The hair's outside, once for the rays' start and the sample's inner depth (the first light's invocation writes it).
    bool inner = j == 0 && u_inner != 0;
    Outside outside = u_outward > 0.0 || inner ? hair_outside(s, T, e1_own) : Outside(vec3(0.0), 0.0, 0.0);
    vec3 origin = s.position.xyz + outward_shift(outside);
    if (j == 0) write_inner(i, inner ? inner_depth(s, outside) : vec3(0.0));
    for (int r = 0; r < u_rays; ++r) {
        // Ray r carries the r-th of u_rays equal shares of the light's energy, from the centre out (srbf_lobe_cos),
        // turned by the golden angle from the one before.
        float c = srbf_lobe_cos(lambda, 1.0 - (float(r) + 0.5) / float(u_rays));
        float phi = GOLDEN_ANGLE * float(r);
        vec3 d = normalize(c * l + sqrt(max(1.0 - c * c, 0.0)) * (cos(phi) * e1 + sin(phi) * e2));
        float start = own_cluster_shadow_start(d, T, e1_own, s.position.w, s.tangent.w, u_narrow_start != 0) + 2.0 * u_step;
        vec2 depth = optical_depth(origin + start * d, d);
        float tau = u_width * depth.x;
#if SHADOW_BODY
        tau += min(u_body_opacity * depth.y, u_body_max_depth);
#endif
        direct += exp(-tau);
        fibres += tau;
    }
    shadows[i * u_light_count + j] = vec2(direct, fibres) / float(u_rays);
}
#endif
