// The lit strand renderer's lighting pass (online/strand_renderer.h): L_o (strand_lighting.glsl) at
// every strand point, read by strand_lines.vert as a vertex attribute and interpolated along the lines.
#include "shaders/gl/strand_lighting.glsl"

layout(local_size_x = 64) in;

// Vertex k: position (floats 6k..6k+2), tangent root→tip (6k+3..6k+5), as the vertex buffer holds them.
layout(std430, binding = 1) readonly buffer Vertices { float vertices[]; };
layout(std430, binding = 2) writeonly buffer Radiance { vec4 radiance[]; };
uniform int u_vertex_count;

void main() {
    int k = int(gl_GlobalInvocationID.x);
    if (k >= u_vertex_count) return;
    vec3 p = vec3(vertices[6 * k], vertices[6 * k + 1], vertices[6 * k + 2]);
    vec3 t = vec3(vertices[6 * k + 3], vertices[6 * k + 4], vertices[6 * k + 5]);
    radiance[k] = vec4(strand_radiance(p, t), 0.0);
}
