// Each lighting sample's own cluster's depth toward the hair's inside (shell_shadow.comp inner_depth) in the Shadows
// buffer (online/shell_passes.h ShellGpu::shadows): after the (T̃, n) of every sample and light, two vec2 per sample,
// (x, y) then (z, 0). The includer declares the buffer as `shadows`; ShellRenderer::read_inner_depths reads the same
// layout on the CPU.
#ifndef COIF_SHADERS_GL_INNER_DEPTHS_GLSL
#define COIF_SHADERS_GL_INNER_DEPTHS_GLSL

// Where sample i's inner depth starts, with `samples` lighting samples and `lights` lights.
int inner_depth_at(int samples, int lights, int i) { return samples * lights + 2 * i; }

vec3 inner_depth_read(int at) { return vec3(shadows[at], shadows[at + 1].x); }

#endif
