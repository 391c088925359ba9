// The key lights' shadow volumes (ShellSettings::key_lights; made by shell_key_light.comp, bound by
// online/shell_passes.cpp) and the light each key light gives a point: read per vertex by shell.vert where the lighting
// sums are read there (SHELL_LIGHTING 1), per fragment by shell_shade.glsl otherwise.
#ifndef COIF_SHADERS_GL_KEY_LIGHT_VOLUME_GLSL
#define COIF_SHADERS_GL_KEY_LIGHT_VOLUME_GLSL

uniform sampler3D u_key_volume[SHELL_KEY_LIGHTS];  // the fibres met toward each key light (KeyLightPass)
// Shells' space → the volume's texture coordinates, each point first moved ShellSettings::key_toward_light voxels toward
// the light (online/shell_passes.cpp, ShellsPass::draw).
uniform mat4 u_key_frame[SHELL_KEY_LIGHTS];
uniform vec4 u_key_light[SHELL_KEY_LIGHTS];        // unit direction toward the light, λ
uniform float u_key_toward_camera;                 // ShellSettings::key_toward_camera, in shells' units

// The fibres met from p toward key light m; none with ShellSettings::debug 6, which shades the key lights unshadowed (the
// rest of the image as in 0), so that their shadow's share of the light can be taken apart from what it shadows.
#if defined(SHELL_DEBUG) && SHELL_DEBUG == 6
float key_fibres(int m, vec3 p) { return 0.0; }
#else
float key_fibres(int m, vec3 p) { return textureLod(u_key_volume[m], (u_key_frame[m] * vec4(p, 1.0)).xyz, 0.0).r; }
#endif

// Key light m's weight at p from its texels of the lighting sums (shell_lighting.comp: the unshadowed light `direct`,
// the forward-scattered light per unit share `forward`, the forward loss `loss`): the light that crosses the n fibres
// unscattered, and what they scatter forward beyond it, D e^{-n} + max(T_f - e^{-n}, 0) F with T_f = e^{-n loss}.
vec3 key_light_weight_at(int m, vec3 p, vec3 direct, vec3 forward, vec3 loss) {
    float n = key_fibres(m, p);
    float T_direct = exp(-n);
    return direct * T_direct + max(exp(-n * loss) - vec3(T_direct), vec3(0.0)) * forward;
}

// A layer's fibres fill its slab, from its surface (ρ = rho, in cluster radii) in to the next layer's, `spacing` further
// in (the layers are evenly spaced, DiskLayout::layer_v), and a shell point stands for all of them. So a key light's
// shadow is taken at two points of the slab on the line from the cluster's axis through the point p (which lies at
// ρ = rho_p: the mesh's surface, which a folded inner layer's is not): the Gauss-Legendre nodes in ρ, each weighed by
// its ρ, since a slab's fibres per unit of ρ grow with ρ. At the surface alone, the fibres under it were lit as if
// nothing of their own layer lay toward the light (docs/quality.md, "A key light's shadow over the layer's slab").
// Both points then move u_key_toward_camera along `to_eye` (unit, toward the camera): the fibres a layer shows the camera
// are its slab's side toward it (ShellSettings::key_toward_camera).
struct KeySlab {
    vec3 p0, p1;   // the two points
    float w1;      // the outer point's weight; the inner one's is 1 - w1
};
KeySlab key_slab(vec3 p, vec3 axis, float rho_p, float spacing, float rho, vec3 to_eye) {
    const float g = 0.28867513;  // 1 / (2 sqrt 3): the nodes lie at the slab's middle -/+ g of its depth
    float rho_inner = max(rho - spacing, 0.0);
    float r0 = mix(rho_inner, rho, 0.5 - g), r1 = mix(rho_inner, rho, 0.5 + g);
    KeySlab s;
    s.p0 = axis + (r0 / rho_p) * (p - axis) + u_key_toward_camera * to_eye;
    s.p1 = axis + (r1 / rho_p) * (p - axis) + u_key_toward_camera * to_eye;
    s.w1 = r1 / (r0 + r1);
    return s;
}

// Key light m's transmittance over a layer's slab, e^{-n} at its two points (ShellSettings::debug 5).
float key_transmittance(int m, KeySlab s) { return mix(exp(-key_fibres(m, s.p0)), exp(-key_fibres(m, s.p1)), s.w1); }

// Key light m's weight over a layer's slab (key_slab).
vec3 key_light_weight(int m, KeySlab s, vec3 direct, vec3 forward, vec3 loss) {
    return mix(key_light_weight_at(m, s.p0, direct, forward, loss), key_light_weight_at(m, s.p1, direct, forward, loss),
               s.w1);
}

#endif
