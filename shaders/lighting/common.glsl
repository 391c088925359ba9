// Shared math of the SRBF lighting (issue 6): Gaussians, circular Gaussians and their closed-form
// integrals. GLSL compiled also as C++ (shaders/glsl_prelude.h); see the rules there.
//
// Conventions (DESIGN.md, 000 Table 1): angles in radians; λ is a *bandwidth*, not a standard
// deviation:  g(x;μ,λ) = exp(-(x-μ)²/λ²)   (variance λ²/2),
//             g^u(x;μ,λ) = g(x;μ,λ) / (√π λ),
//             g^c(x;μ,λ) = exp(2(cos(x-μ)-1)/λ²) = exp(-4 sin²((x-μ)/2)/λ²)   (a von Mises shape
//             with concentration κ = 2/λ²; the sin² form keeps float precision for small x-μ).
#ifndef COIF_SHADERS_LIGHTING_COMMON_GLSL
#define COIF_SHADERS_LIGHTING_COMMON_GLSL

#ifndef COIF_FN
#define COIF_FN
#endif

const float COIF_PI = 3.14159265358979;
const float COIF_TWO_PI = 6.28318530717959;
const float COIF_HALF_PI = 1.57079632679490;
const float COIF_SQRT_PI = 1.77245385090552;
const float COIF_INV_PI = 0.318309886183791;

// Rec. 709 / sRGB luminance of linear RGB: coif's one set of weights, for the shaders and for C++
// (offline/envmap.h, the image metrics).
const vec3 COIF_LUMINANCE = vec3(0.2126, 0.7152, 0.0722);
COIF_FN float luminance(vec3 c) { return dot(c, COIF_LUMINANCE); }

// x wrapped to [-π, π).
COIF_FN float wrap_pi(float x) {
    return x - COIF_TWO_PI * floor((x + COIF_PI) / COIF_TWO_PI);
}

COIF_FN float safe_sqrt(float x) { return sqrt(max(x, 0.0)); }
COIF_FN float safe_asin(float x) { return asin(clamp(x, -1.0, 1.0)); }

// 000 Table 1.
COIF_FN float gauss(float x, float mu, float lambda) {
    float d = (x - mu) / lambda;
    return exp(-d * d);
}
COIF_FN float gauss_u(float x, float mu, float lambda) {
    return gauss(x, mu, lambda) / (COIF_SQRT_PI * lambda);
}
COIF_FN float circ_gauss(float x, float mu, float lambda) {
    float s = sin(0.5 * (x - mu));
    return exp(-4.0 * s * s / (lambda * lambda));
}

// Scaled modified Bessel functions e^{-x} I0(x), e^{-x} I1(x) for x >= 0 (Abramowitz & Stegun
// 9.8.1-9.8.4; relative error < 2e-7). The circular-Gaussian integrals below are Bessel functions.
COIF_FN float bessel_i0e(float x) {
    if (x < 3.75) {
        float t = x / 3.75;
        t = t * t;
        float i0 = 1.0 + t * (3.5156229 + t * (3.0899424 + t * (1.2067492 + t * (0.2659732 +
                   t * (0.0360768 + t * 0.0045813)))));
        return i0 * exp(-x);
    }
    float u = 3.75 / x;
    return (0.39894228 + u * (0.01328592 + u * (0.00225319 + u * (-0.00157565 + u * (0.00916281 +
           u * (-0.02057706 + u * (0.02635537 + u * (-0.01647633 + u * 0.00392377)))))))) / sqrt(x);
}
COIF_FN float bessel_i1e(float x) {
    if (x < 3.75) {
        float t = x / 3.75;
        t = t * t;
        float i1 = x * (0.5 + t * (0.87890594 + t * (0.51498869 + t * (0.15084934 + t * (0.02658733 +
                   t * (0.00301532 + t * 0.00032411))))));
        return i1 * exp(-x);
    }
    float u = 3.75 / x;
    return (0.39894228 + u * (-0.03988024 + u * (-0.00362018 + u * (0.00163801 + u * (-0.01031555 +
           u * (0.02282967 + u * (-0.02895312 + u * (0.01787654 - u * 0.00420059)))))))) / sqrt(x);
}

// κ = 2/λ², clamped so that a huge λ (a flat lobe) or a tiny one stays finite.
COIF_FN float circ_kappa(float lambda) {
    float l = clamp(lambda, 1e-4, 1e4);
    return 2.0 / (l * l);
}

// ∫_{-π}^{π} g^c(x;0,λ) dx = 2π e^{-κ} I0(κ) (exact). The paper uses √π λ (000 §4.2.3, valid for
// small λ; 9 % low at λ = 1); `paper_norm` selects it so that its cost can be measured.
COIF_FN float circ_integral(float lambda, bool paper_norm) {
    if (paper_norm) return COIF_SQRT_PI * lambda;
    return COIF_TWO_PI * bessel_i0e(circ_kappa(lambda));
}

// ∫_{-π}^{π} g^c(x;0,λ1) g^c(x;d,λ2) dx: the product of two circular Gaussians is a circular
// Gaussian (000 §4.2.3, supplement §5): κ1 cos x + κ2 cos(x-d) = R cos(x-μ) with
// R² = κ1² + κ2² + 2κ1κ2 cos d, so the integral is 2π e^{R-κ1-κ2} e^{-R} I0(R). R-κ1-κ2 is formed
// without cancellation as -4κ1κ2 sin²(d/2) / (R+κ1+κ2).
COIF_FN float circ_product_integral(float lambda1, float lambda2, float d, bool paper_norm) {
    float k1 = circ_kappa(lambda1);
    float k2 = circ_kappa(lambda2);
    float s = sin(0.5 * d);
    float s2 = s * s;
    float r = sqrt(max((k1 + k2) * (k1 + k2) - 4.0 * k1 * k2 * s2, 0.0));
    float expo = -4.0 * k1 * k2 * s2 / (r + k1 + k2);
    if (paper_norm) return exp(expo) * COIF_SQRT_PI * sqrt(2.0 / max(r, 1e-12));
    return exp(expo) * COIF_TWO_PI * bessel_i0e(r);
}

// The bandwidth λ of a circular Gaussian of peak b that holds energy E: b ∫g^c(λ) = E
// (000 eq. 17 with the exact integral: Newton on e^{-κ}I0(κ) = E/(2πb), which is convex and
// decreasing in κ, started left of the root so that the iterates increase monotonically).
// Returns a huge λ (a flat lobe) when even a flat lobe of height b holds less than E; the caller
// then rescales b (see circ_fit_peak).
COIF_FN float circ_fit_width(float energy, float peak, bool paper_norm) {
    if (!(peak > 0.0) || !(energy > 0.0)) return 1.0;
    if (paper_norm) return energy / (COIF_SQRT_PI * peak);
    float r = energy / (COIF_TWO_PI * peak);
    if (r >= 1.0) return 1e4;
    float k = 1.0 / (COIF_TWO_PI * r * r);  // e^{-κ}I0(κ) > 1/sqrt(2πκ) for κ > 0.5
    if (k < 0.6 || bessel_i0e(k) < r) k = 0.0;
    for (int it = 0; it < 6; ++it) {
        float f = bessel_i0e(k) - r;
        float df = bessel_i1e(k) - bessel_i0e(k);
        k = k - f / min(df, -1e-12);
    }
    k = max(k, 2e-8);
    return sqrt(2.0 / k);
}

// The peak that makes a circular Gaussian of bandwidth λ hold energy E.
COIF_FN float circ_fit_peak(float energy, float lambda, bool paper_norm) {
    return energy / max(circ_integral(lambda, paper_norm), 1e-30);
}

// Complementary error function with small *relative* error everywhere (Numerical Recipes erfcc,
// fractional error < 1.2e-7); GLSL has no erf.
COIF_FN float erfc_approx(float x) {
    float z = abs(x);
    float t = 1.0 / (1.0 + 0.5 * z);
    float r = t * exp(-z * z - 1.26551223 + t * (1.00002368 + t * (0.37409196 + t * (0.09678418 +
              t * (-0.18628806 + t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 +
              t * (-0.82215223 + t * 0.17087277)))))))));
    return x >= 0.0 ? r : 2.0 - r;
}

// erf(b) - erf(a) for a <= b, accurate in the tails (differences of erfc on the same side).
COIF_FN float erf_diff(float a, float b) {
    if (a >= 0.0) return erfc_approx(a) - erfc_approx(b);
    if (b <= 0.0) return erfc_approx(-b) - erfc_approx(-a);
    return 2.0 - erfc_approx(b) - erfc_approx(-a);
}

// Product of two Gaussians g(x;μ1,λ1) g(x;μ2,λ2) = c g(x;μ,λ) (000 supplement §2).
struct GaussProduct {
    float c;
    float mu;
    float lambda;
};
COIF_FN GaussProduct gauss_product(float mu1, float lambda1, float mu2, float lambda2) {
    float l1 = lambda1 * lambda1;
    float l2 = lambda2 * lambda2;
    float s = l1 + l2;
    GaussProduct p;
    p.c = exp(-(mu1 - mu2) * (mu1 - mu2) / s);
    p.mu = (mu1 * l2 + mu2 * l1) / s;
    p.lambda = lambda1 * lambda2 / sqrt(s);
    return p;
}

// ∫_a^b g(x;μ,λ) (fa + (fb-fa)(x-a)/(b-a)) dx: one segment of the linear quadrature (000 §4.2.2;
// supplement §3: a Gaussian times a polynomial integrates in closed form).
COIF_FN vec3 gauss_linear_segment(float a, float b, vec3 fa, vec3 fb, float mu, float lambda) {
    if (!(b - a > 1e-7)) return vec3(0.0);
    float ta = (a - mu) / lambda;
    float tb = (b - mu) / lambda;
    float i0 = lambda * 0.5 * COIF_SQRT_PI * erf_diff(ta, tb);          // ∫ g
    float i1 = lambda * lambda * 0.5 * (exp(-ta * ta) - exp(-tb * tb));  // ∫ g (x-μ)
    vec3 slope = (fb - fa) / (b - a);
    return fa * i0 + slope * (i1 + (mu - a) * i0);
}

#endif
