// The lighting pass's sums (shell_lighting.comp) read back at a point of a cluster: LIGHTING_TEXELS RGBA32F texels
// per lighting sample (a define from online/shell_passes.h kLightingTexels), linear between the lighting rows along
// t. Used per vertex (SHELL_LIGHTING == 1: the rows are the mesh rows, so the interpolated varyings equal the
// per-fragment fetch) or per fragment (SHELL_LIGHTING == 0: any number of rows).
#ifndef COIF_SHADERS_GL_SHELL_LIGHTING_FETCH_GLSL
#define COIF_SHADERS_GL_SHELL_LIGHTING_FETCH_GLSL
#ifndef LIGHTING_TEXELS
#error "LIGHTING_TEXELS: the programs reading the lighting sums define it (online/shell_passes.cpp)"
#endif

uniform sampler2D u_lighting;      // C_k, S_k per lighting sample: x = row along t, y = cluster · LIGHTING_TEXELS + texel
uniform int u_lighting_rows;       // the texture's width: the lighting samples per cluster
uniform int u_lighting_used;       // the rows the pass wrote, evenly along t from x = 0 (ShellSettings::lighting_step)
uniform int u_lighting_height;

// Texel m (0..LIGHTING_TEXELS − 1) of the sums at t ∈ [0, 1] of lighting cluster `cluster`.
vec4 lighting_fetch(float t, uint cluster, int m) {
    float lx = (clamp(t, 0.0, 1.0) * float(u_lighting_used - 1) + 0.5) / float(u_lighting_rows);
    float ly = (float(cluster * uint(LIGHTING_TEXELS) + uint(m)) + 0.5) / float(u_lighting_height);
    return textureLod(u_lighting, vec2(lx, ly), 0.0);
}

#endif
