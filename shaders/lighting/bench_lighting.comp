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
uniform HairParams u_hair;       // online/lighting_uniforms.h set_lighting_uniforms
uniform LightingConfig u_config;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_num_points) return;
    HairParams hp = u_hair;
    LightingConfig cfg = u_config;
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
