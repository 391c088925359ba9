// `coif bench lighting`: the shared SRBF lighting GLSL run as a compute shader, one invocation per
// shading point, looping over all lights (single + optionally multiple scattering).
#include "shaders/lighting/luts_gl.glsl"
#include "shaders/lighting/srbf_multiple.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };   // (θo, φo, 0, 0)
layout(std430, binding = 1) readonly buffer Lights { vec4 lights[]; };   // (θj, φj, λj, σ̄_f²)
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };

uniform int u_num_points;
uniform int u_num_lights;
uniform int u_multiple;
uniform vec4 u_hair0;   // η, σa.r, σa.g, σa.b
uniform vec4 u_hair1;   // α_R, α_TT, α_TRT, β_R
uniform vec4 u_hair2;   // β_TT, β_TRT, a, w_c
uniform vec4 u_hair3;   // Δη', d_b, m, flags (bit 0 schlick, 1 norm, 2 θ gauss, 3 tt)

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_num_points) return;
    HairParams hp;
    hp.eta = u_hair0.x;
    hp.sigma_a = vec3(u_hair0.y, u_hair0.z, u_hair0.w);
    hp.alpha_R = u_hair1.x;
    hp.alpha_TT = u_hair1.y;
    hp.alpha_TRT = u_hair1.z;
    hp.beta_R = u_hair1.w;
    hp.beta_TT = u_hair2.x;
    hp.beta_TRT = u_hair2.y;
    hp.ecc_a = u_hair2.z;
    hp.w_c = u_hair2.w;
    hp.delta_eta_p = u_hair3.x;
    hp.d_b = u_hair3.y;
    LightingConfig cfg;
    cfg.segments = int(u_hair3.z);
    int flags = int(u_hair3.w);
    cfg.paper_schlick = (flags & 1) != 0;
    cfg.paper_norm = (flags & 2) != 0;
    cfg.paper_theta_gauss = (flags & 4) != 0;
    cfg.paper_tt = (flags & 8) != 0;
    vec4 f0123;
    vec4 f45;
    srbf_point_setup(hp, cfg, f0123, f45);
    vec4 p = points[i];
    vec3 single_sum = vec3(0.0);
    vec3 multiple_sum = vec3(0.0);
    for (int j = 0; j < u_num_lights; ++j) {
        vec4 l = lights[j];
        single_sum += srbf_single(hp, cfg, f0123, f45, p.x, p.y, l.x, l.y, l.z);
        if (u_multiple != 0) multiple_sum += srbf_multiple(hp, cfg, f0123, f45, p.x, p.y, l.x, l.y, l.z, l.w);
    }
    results[2 * i] = vec4(single_sum, 0.0);
    results[2 * i + 1] = vec4(multiple_sum, 0.0);
}
