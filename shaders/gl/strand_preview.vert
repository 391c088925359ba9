// Strand preview (online/strand_preview.h): lines with a per-vertex hair tangent.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_tangent;
uniform mat4 u_view_projection;
out vec3 v_position;
out vec3 v_tangent;
void main() {
    v_position = a_position;
    v_tangent = a_tangent;
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
