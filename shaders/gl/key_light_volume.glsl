// The key lights' shadow volumes (ShellSettings::key_lights; made by shell_key_light.comp, bound by
// online/shell_passes.cpp) and the light each key light gives a point: read per vertex by shell.vert where the lighting
// sums are read there (SHELL_LIGHTING 1), per fragment by shell_shade.glsl otherwise.
#ifndef COIF_SHADERS_GL_KEY_LIGHT_VOLUME_GLSL
#define COIF_SHADERS_GL_KEY_LIGHT_VOLUME_GLSL

uniform sampler3D u_key_volume[SHELL_KEY_LIGHTS];  // the fibres met toward each key light (KeyLightPass)
uniform mat4 u_key_frame[SHELL_KEY_LIGHTS];        // shells' space → the volume's texture coordinates

// The fibres met from p toward key light m.
float key_fibres(int m, vec3 p) { return textureLod(u_key_volume[m], (u_key_frame[m] * vec4(p, 1.0)).xyz, 0.0).r; }

// Key light m's weight at p from its texels of the lighting sums (shell_lighting.comp: the unshadowed light `direct`,
// the forward-scattered light per unit share `forward`, the forward loss `loss`): the light that crosses the n fibres
// unscattered, and what they scatter forward beyond it, D e^{-n} + max(T_f - e^{-n}, 0) F with T_f = e^{-n loss}.
vec3 key_light_weight(int m, vec3 p, vec3 direct, vec3 forward, vec3 loss) {
    float n = key_fibres(m, p);
    float T_direct = exp(-n);
    return direct * T_direct + max(exp(-n * loss) - vec3(T_direct), vec3(0.0)) * forward;
}

#endif
