#ifndef COIF_SHADERS_ENVMAP_GLSL
#define COIF_SHADERS_ENVMAP_GLSL
// Environment maps: THE pixel <-> direction mapping of equirectangular maps in coif, and the SRBF of
// 000 Table 1. GLSL, also compiled as C++ through shaders/glsl_prelude.h; used by the SRBF fit
// (offline/srbf_fit.cpp), the GL renderer's background and the reference renderer.
//
// World frame: right-handed, y up. Texture coordinates (u, v) in [0,1]^2: u runs along a row from the
// left edge to the right edge, v runs down the columns from the TOP row (row 0) to the bottom row.
//   polar angle from +y:      theta = pi v         (v = 0: zenith +y, v = 1: nadir -y)
//   azimuth from +x to +z:    phi   = 2 pi u - pi
//   direction:                omega = (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi))
// so the centre column (u = 0.5) faces +x, the column at u = 0.25 faces -z, u = 0.75 faces +z and the
// left/right edges (u = 0, 1) face -x. This is Blender's world convention after its z-up -> y-up
// export (Blender +x -> +x, Blender -y -> +z) and three.js's equirectangular convention, so the
// CC0 Blender studio-light maps in ../shared/data look in coif as they do in Blender.
// Pixel (col, row) of a W x H map covers u in [col/W, (col+1)/W], v in [row/H, (row+1)/H]; its centre
// is at u = (col + 0.5)/W, v = (row + 0.5)/H. OpenGL texture lookups use the same (u, v) with the image
// uploaded top row first (t = v).
// C++ callers include shaders/envmap.h (this file inside namespace coif::glsl, functions inline).

#ifndef COIF_FN
#define COIF_FN
#endif

const float ENVMAP_PI = 3.14159265358979;

// Unit world direction of texture coordinates (u, v).
COIF_FN vec3 envmap_direction(vec2 uv) {
    float theta = ENVMAP_PI * uv.y;
    float phi = 2.0 * ENVMAP_PI * uv.x - ENVMAP_PI;
    float s = sin(theta);
    return vec3(s * cos(phi), cos(theta), s * sin(phi));
}

// Texture coordinates of a direction (need not be unit length; must not be zero). u in [0, 1]
// (both 0 and 1 on the -x seam), v in [0, 1]. At the poles u is arbitrary (atan(0, 0) = 0: u = 0.5).
COIF_FN vec2 envmap_uv(vec3 omega) {
    vec3 w = normalize(omega);
    float u = atan(w.z, w.x) / (2.0 * ENVMAP_PI) + 0.5;
    float v = acos(clamp(w.y, float(-1.0), float(1.0))) / ENVMAP_PI;
    return vec2(u, v);
}

// Solid angle (sr) of one pixel of row `row` in a `width` x `height` map (rows and sizes as floats so
// the function reads the same in GLSL and C++): (2 pi / W) (cos(pi row / H) - cos(pi (row + 1) / H)),
// written as a product of sines so that it keeps full float precision next to the poles.
COIF_FN float envmap_pixel_solid_angle(float row, float width, float height) {
    return (4.0 * ENVMAP_PI / width) * sin(ENVMAP_PI * (row + 0.5) / height) * sin(0.5 * ENVMAP_PI / height);
}

// The SRBF of 000 Table 1 / eq. 1: G(omega; omega_j, lambda_j) = exp(2 (omega . omega_j - 1) / lambda_j^2).
// omega, omega_j unit vectors; lambda_j > 0 is the bandwidth (not a standard deviation: near omega_j,
// G ~ exp(-gamma^2 / lambda_j^2) for the angle gamma between omega and omega_j).
COIF_FN float srbf_G(vec3 omega, vec3 omega_j, float lambda_j) {
    return exp(2.0 * (dot(omega, omega_j) - 1.0) / (lambda_j * lambda_j));
}

// Integral of G over the sphere: 2 pi Int_{-1}^{1} exp(2 (mu - 1) / lambda^2) dmu
//   = pi lambda^2 (1 - exp(-4 / lambda^2)).
// The energy (radiance x sr) of an SRBF light is L_j srbf_integral(lambda_j).
COIF_FN float srbf_integral(float lambda_j) {
    float l2 = lambda_j * lambda_j;
    return ENVMAP_PI * l2 * (1.0 - exp(-4.0 / l2));
}

// G as a distribution of directions: the cosine of the angle γ from ω_j below which (toward ω_j) a fraction 1 − xi of
// the light's energy arrives, xi ∈ (0, 1]. G ∝ exp(κ (cos γ − 1)), κ = 2 / λ_j², is uniform in the azimuth about ω_j
// and exponential in cos γ, whose inverse CDF is cos γ = 1 + log(xi + (1 − xi) e^{−2κ}) / κ (xi = 1: ω_j itself; xi → 0:
// −ω_j). Written without e^{κ}, which overflows a float for the narrowest lights (λ = 0.033: κ = 1836). Used by the
// reference to sample the lights and by the shell renderer's shadow pass to stratify each light's rays.
COIF_FN float srbf_lobe_cos(float lambda_j, float xi) {
    float kappa = 2.0 / (lambda_j * lambda_j);
    return clamp(1.0 + log(xi + (1.0 - xi) * exp(-2.0 * kappa)) / kappa, float(-1.0), float(1.0));
}

#endif  // COIF_SHADERS_ENVMAP_GLSL
