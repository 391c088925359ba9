// Strand preview shading: Kajiya-Kay (1989) diffuse sin(T,L) and specular on the reflection cone
// (T.R = -T.L, so cos = -(T.L)(T.V) + sin(T,L) sin(T,V)),
// under one directional light. A preview only; coif's hair lighting is the SRBF Marschner model.
in vec3 v_position;
in vec3 v_tangent;
uniform vec3 u_light_direction;
uniform vec3 u_eye;
uniform vec3 u_hair_color;
uniform float u_specular_exponent;
layout(location = 0) out vec4 o_color;
void main() {
    vec3 t = normalize(v_tangent);
    vec3 l = normalize(u_light_direction);
    vec3 v = normalize(u_eye - v_position);
    float tl = dot(t, l);
    float tv = dot(t, v);
    float sin_tl = sqrt(max(0.0, 1.0 - tl * tl));
    float sin_tv = sqrt(max(0.0, 1.0 - tv * tv));
    float diffuse = sin_tl;
    float specular = pow(max(0.0, -tl * tv + sin_tl * sin_tv), u_specular_exponent);
    vec3 c = u_hair_color * (0.15 + 0.85 * diffuse) + vec3(0.35) * specular;
    o_color = vec4(c, 1.0);
}
