// A character's body (online/body_pass.h): an opaque Lambertian surface of albedo u_albedo under the SRBF lights,
// each taken as a directional light of its power L_j ∫G_j dω (srbf_integral): E = Σ_j L_j ∫G_j max(0, n·ω_j).
// A simple material, to place the hair on its character, not a skin model; the hair does not shadow it.
// Both sides are lit (the normal is turned to the eye): meshes with open or inconsistent faces still look solid.
#include "shaders/envmap.glsl"
#include "shaders/gl/srbf_light_buffer.glsl"
uniform vec3 u_albedo;
uniform vec3 u_eye;
in vec3 v_position;
in vec3 v_normal;
layout(location = 0) out vec4 o_color;
void main() {
    vec3 n = normalize(v_normal);
    if (dot(n, u_eye - v_position) < 0.0) n = -n;
    vec3 irradiance = vec3(0.0);
    for (int j = 0; j < u_light_count; ++j) {
        vec3 w = normalize(lights[j].direction_lambda.xyz);
        irradiance += lights[j].radiance.rgb * srbf_integral(lights[j].direction_lambda.w) * max(dot(n, w), 0.0);
    }
    o_color = vec4(u_albedo / ENVMAP_PI * irradiance, 1.0);
}
