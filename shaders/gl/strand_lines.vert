// The lit strand renderer (online/strand_renderer.h): lines with a per-vertex tangent root→tip and the
// lighting pass's L_o per vertex (unused in the per-fragment mode).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_tangent;
layout(location = 2) in vec3 a_radiance;
uniform mat4 u_view_projection;
uniform mat4 u_view;
out vec3 v_position;
out vec3 v_tangent;
out vec3 v_radiance;
out float v_depth;  // view-space depth z (> 0 in front of the camera)
void main() {
    v_position = a_position;
    v_tangent = a_tangent;
    v_radiance = a_radiance;
    v_depth = -(u_view * vec4(a_position, 1.0)).z;
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
