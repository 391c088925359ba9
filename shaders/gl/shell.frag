// One fragment of a SATF layer mesh, blended premultiplied "over" (ONE, ONE_MINUS_SRC_ALPHA) in the
// draw order of online/shell_passes.cpp (ShellsPass); the shading itself is shell_shade.glsl.
#include "shaders/gl/shell_shade.glsl"
#include "shaders/gl/scene_depth.glsl"

centroid in vec3 v_position;
centroid in vec3 v_tangent;
centroid in vec3 v_normal;
centroid in vec3 v_axis_normal;
centroid in vec2 v_texcoord;
flat in uvec2 v_info;

layout(location = 0) out vec4 o_color;

void main() {
    if (behind_scene()) discard;
    o_color = shell_shade(v_position, v_tangent, v_normal, v_axis_normal, v_texcoord, v_info);
}
