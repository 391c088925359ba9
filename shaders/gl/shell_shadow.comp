// Shadows between clusters (DESIGN.md decision 5) for the shell renderer's lighting pass: per
// lighting sample and SRBF light, the light's unoccluded fraction T̃ and the fibres met n on the way
// (shaders/lighting/srbf_shadowed.glsl), marched through the hair's optical-density grid
// (online/shells/shadow_grid.h). They depend on the hair, the lights and κ only — not on the view or the
// scattering parameters — so the renderer runs this pass when those change, not every frame.
//
// The light's lobe is sampled by `u_rays` rays: its centre and a ring of u_rays − 1 directions at
// min(λ_j, 1) rad from it (a circular Gaussian exp(2(cos θ − 1)/λ²) ≈ exp(−θ²/λ²) puts its mean
// angle near λ); T̃ = mean exp(−τ), n = mean τ over the rays, τ = κ ∫ density. Each ray starts at
// two voxels from the lighting sample on the cluster's axis (u_own = 1; two voxels measured closer to
// the reference than none: 12.2 against 11.9 dB), so the half of its own cluster that faces
// the light shades it — what the cluster's far side gets from its own fibres, which 004 eq. 12 (one
// shadow per layer, whatever the light) cannot give; or (u_own = 0) where the ray leaves the own
// cluster (its outer radius over the sine of the ray's angle to the axis, at most 4 radii, plus two
// voxels for the grid's blur), leaving the own cluster to eq. 12 alone. docs/renderer.md compares the
// two against the reference: from the axis is much closer.
layout(local_size_x = 64) in;

#include "shaders/gl/lighting_samples.glsl"
struct GpuLight {
    vec4 direction_lambda;
    vec4 radiance;
};
layout(std430, binding = 3) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = 4) writeonly buffer Shadows { vec2 shadows[]; };  // (T̃, n) per sample × light

uniform sampler3D u_density;  // optical depth per unit length at κ = 1
uniform vec3 u_grid_min;
uniform vec3 u_grid_extent;
uniform float u_step;         // world units per march step (one voxel)
uniform float u_kappa;
uniform int u_sample_count;
uniform int u_light_count;
uniform int u_rays;
uniform int u_own;             // 1: rays start on the axis (through the own cluster); 0: outside it

const float TWO_PI = 6.28318530718;

float optical_depth(vec3 p, vec3 d) {
    vec3 inv = 1.0 / vec3(abs(d.x) > 1e-8 ? d.x : 1e-8, abs(d.y) > 1e-8 ? d.y : 1e-8, abs(d.z) > 1e-8 ? d.z : 1e-8);
    vec3 t0 = (u_grid_min - p) * inv;
    vec3 t1 = (u_grid_min + u_grid_extent - p) * inv;
    vec3 tn = min(t0, t1);
    vec3 tf = max(t0, t1);
    float a = max(max(max(tn.x, tn.y), tn.z), 0.0);
    float b = min(min(tf.x, tf.y), tf.z);
    if (b <= a) return 0.0;
    int n = int(ceil((b - a) / u_step));
    float h = (b - a) / float(n);
    float sum = 0.0;
    for (int k = 0; k < n; ++k) {
        vec3 q = p + d * (a + (float(k) + 0.5) * h);
        sum += textureLod(u_density, (q - u_grid_min) / u_grid_extent, 0.0).r;
    }
    return sum * h;
}

void main() {
    int id = int(gl_GlobalInvocationID.x);
    if (id >= u_sample_count * u_light_count) return;
    int i = id / u_light_count;
    int j = id - i * u_light_count;
    LightingSample s = samples[i];
    vec3 T = normalize(s.tangent.xyz);
    vec3 l = normalize(lights[j].direction_lambda.xyz);
    float spread = min(lights[j].direction_lambda.w, 1.0);
    vec3 e1 = normalize(abs(l.x) < 0.9 ? cross(l, vec3(1.0, 0.0, 0.0)) : cross(l, vec3(0.0, 1.0, 0.0)));
    vec3 e2 = cross(l, e1);
    float direct = 0.0;
    float fibres = 0.0;
    for (int r = 0; r < u_rays; ++r) {
        vec3 d = l;
        if (r > 0) {
            float phi = TWO_PI * float(r - 1) / float(u_rays - 1);
            d = normalize(cos(spread) * l + sin(spread) * (cos(phi) * e1 + sin(phi) * e2));
        }
        float across = length(d - dot(d, T) * T);
        float start = (u_own != 0 ? 0.0 : s.position.w / max(across, 0.25)) + 2.0 * u_step;
        float tau = u_kappa * optical_depth(s.position.xyz + start * d, d);
        direct += exp(-tau);
        fibres += tau;
    }
    shadows[id] = vec2(direct, fibres) / float(u_rays);
}
