// The viewer's background (with fullscreen.vert): the environment as the renderer is lit by it, the sum of its SRBF
// lights (000 eq. 1, shaders/envmap.glsl) along each pixel's view ray: what the fitted lights keep of the map.
#include "shaders/envmap.glsl"
#include "shaders/gl/srbf_light_buffer.glsl"

uniform mat4 u_inverse_view_projection;
uniform vec3 u_eye;
uniform vec4 u_viewport;  // x, y, width, height
layout(location = 0) out vec4 o_color;

void main() {
    vec2 ndc = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0;
    vec4 far = u_inverse_view_projection * vec4(ndc, 1.0, 1.0);
    vec3 omega = normalize(far.xyz / far.w - u_eye);
    vec3 radiance = vec3(0.0);
    for (int j = 0; j < u_light_count; ++j)
        radiance += lights[j].radiance.rgb * srbf_G(omega, lights[j].direction_lambda.xyz, lights[j].direction_lambda.w);
    o_color = vec4(radiance, 1.0);
}
