// The weighted blended compositing's weight of a fragment (online/weighted_blend.h; McGuire and Bavoil 2013), for the
// weighted mode (shell_weighted.frag) and the k-buffer's tail (shell_kbuffer.frag).
#ifndef COIF_SHADERS_GL_WEIGHTED_WEIGHT_GLSL
#define COIF_SHADERS_GL_WEIGHTED_WEIGHT_GLSL

// The hair's eye distances in this view, in the shells' space: (nearest, 1 / (farthest − nearest)).
uniform vec2 u_depth_range;

// A fragment's eye distance normalised to the hair's depth range in the view: 0 nearest, 1 farthest.
float weighted_depth(vec3 position) {
    return clamp((distance(position, u_eye) - u_depth_range.x) * u_depth_range.y, 0.0, 1.0);
}

// The weight of a fragment at z, its eye distance normalised to the hair's depth range in the view (0 nearest, 1
// farthest): α e^(−60 z). McGuire and Bavoil's eq. 9, α max(10⁻², 3·10³ (1 − z)³), falls too slowly across the few
// per cent of the range that one pixel's ~40 layers span, so the deep, shadowed layers weigh almost as much as the
// front ones (24.9 dB blurred PSNR against exact on the default scene, blue at 0.69 of exact's). Measured with
// e^(−kz) (docs/renderer.md "Decision 4"): k = 10, 30, 60, 100, 200 gave 25.6, 28.1, 30.2, 28.6, 27.1 dB; 60 is kept.
// The floor keeps the weight a normal float.
float blend_weight(float alpha, float z) {
    return alpha * max(exp(-60.0 * z), 1e-30);
}

#endif
