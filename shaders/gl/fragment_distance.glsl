// A shell fragment's eye distance in world units, as bits that order as the distances do (positive floats do), for
// the compositings that order fragments per pixel: the exact lists (shell_abuffer.frag) and the k-buffer, whose depth
// pass (shell_kbuffer_depth.frag) and shading pass (shell_kbuffer.frag) must compute the very same bits.
#ifndef COIF_SHADERS_GL_FRAGMENT_DISTANCE_GLSL
#define COIF_SHADERS_GL_FRAGMENT_DISTANCE_GLSL

// World units per unit of the shells' space: an instance of the hair drawn in its own space (online/shell_renderer.h
// draw_frame) under a transform of uniform scale s has eye distances s times those of its space, and the fragments of
// every instance share the lists or slots.
uniform float u_distance_scale;

uint eye_distance_bits(vec3 position, vec3 eye) {
    return floatBitsToUint(u_distance_scale * distance(position, eye));
}

#endif
