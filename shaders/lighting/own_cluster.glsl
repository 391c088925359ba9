// The own cluster's shadow on a shell fragment, by the fragment's side of its cluster toward the light
// (docs/quality.md, "The own cluster's shadow per fragment"). GLSL compiled also as C++
// (shaders/glsl_prelude.h); see the rules there.
//
// A cluster's cross-section is taken as a disc of radius R holding fibres at a uniform density; τ_R is
// the optical depth of one radius, κ_shadow Σ ᾱ over the layers at the fragment's (i, k) (ᾱ each sector's
// mean α: 004 eq. 12's units, which counts only the layers outside a fragment, for light from outside;
// this is eq. 12 turned toward each light). A fibre at ρR from the axis, whose radial direction makes the in-plane
// angle Δ with the light, sees the light through the chord
//     s(ρ, Δ) = −ρ cos Δ + √(1 − ρ² sin² Δ)        (in units of R; 1 − ρ facing it, 1 + ρ away)
// of its own cluster, so its light is multiplied by O(Δ) = exp(−τ s(ρ, Δ)), with τ = τ_R times
// own_cluster_stretch (the ray's path across the disc grows as the light turns along the hair). Shadows between clusters then start outside the own cluster (shaders/gl/shell_shadow.comp).
//
// The shells' Fourier path holds the lights only as harmonics of their azimuth (shell_lighting.comp:
// Σ_j w_j cos kψ_j, …, k ≤ 4) and the records' re(Δ) as harmonics of the light's azimuth Δ from the
// fragment's radial direction. O multiplies re for every light alike (τ then folds the lights' angles to
// the axis into one value per lighting sample), so the product h(Δ) = re(Δ) O(Δ) takes re's place:
// own_cluster_harmonics gives h's harmonics 0..4 by the trapezoid rule over OWN_CLUSTER_POINTS azimuths.
// With 16 points the rule is exact for h = re (τ = 0: re·cos kΔ has degree ≤ 8 < 16), and its error for
// τ > 0 is the aliasing of O's harmonics beyond 11: below 1e-3 of re's mean for τ ≤ 4 and ρ ≤ 0.9, and
// about 5 % at ρ = 1, where the chord has a kink as the light grazes the cluster and the harmonics decay
// slowly (tests/shading/test_own_cluster.cpp; 32 points: 1.4 %, at twice the cost per fragment; the disc of
// uniform density is a far cruder model than that). The shells take ρ at each layer mesh's own surface, the outer
// layer's at ρ = 1 (its middle measured darker against the reference: docs/quality.md).
#ifndef COIF_SHADERS_LIGHTING_OWN_CLUSTER_GLSL
#define COIF_SHADERS_LIGHTING_OWN_CLUSTER_GLSL

#ifndef COIF_FN
#define COIF_FN
#endif

const int OWN_CLUSTER_POINTS = 16;

// s(ρ, Δ) above, from cos Δ and sin Δ.
COIF_FN float own_cluster_path(float rho, float cos_d, float sin_d) {
    return max(-rho * cos_d + sqrt(max(1.0 - rho * rho * sin_d * sin_d, 0.0)), 0.0);
}

// How much longer than the in-plane chord a ray along the unit direction d runs through a cluster of axis T:
// 1 / the sine of its angle to the axis, at most 4 (a ray along the hair would cross it endlessly; 4 radii is
// about where the hair around it takes over). The shadow pass starts its rays this many radii out.
COIF_FN float own_cluster_stretch(vec3 d, vec3 T) {
    return 1.0 / max(length(d - dot(d, T) * T), 0.25);
}

COIF_FN float own_cluster_transmittance(float tau, float rho, float cos_d, float sin_d) {
    return exp(-tau * own_cluster_path(rho, cos_d, sin_d));
}

// re's harmonics in, h = re · O's out, in the shells' layout: c01 = (a0, a1, b1), c23 = (a2, b2, a3, b3),
// c4 = (a4, b4), re(Δ) = a0 + Σ_k a_k cos kΔ + b_k sin kΔ.
COIF_FN void own_cluster_harmonics(float tau, float rho, vec3 c01, vec4 c23, vec2 c4, OUT(vec3) h01, OUT(vec4) h23,
                                   OUT(vec2) h4) {
    h01 = vec3(0.0);
    h23 = vec4(0.0);
    h4 = vec2(0.0);
    float step_angle = 6.28318530717959 / float(OWN_CLUSTER_POINTS);
    float cs = cos(step_angle);
    float sn = sin(step_angle);
    float c1 = 1.0;  // cos Δ_q, sin Δ_q by rotation from Δ_0 = 0
    float s1 = 0.0;
    for (int q = 0; q < OWN_CLUSTER_POINTS; ++q) {
        float c2 = c1 * c1 - s1 * s1;
        float s2 = 2.0 * c1 * s1;
        float c3 = c2 * c1 - s2 * s1;
        float s3 = s2 * c1 + c2 * s1;
        float cos4 = c2 * c2 - s2 * s2;
        float sin4 = 2.0 * c2 * s2;
        float re = c01.x + c01.y * c1 + c01.z * s1 + c23.x * c2 + c23.y * s2 + c23.z * c3 + c23.w * s3 + c4.x * cos4 + c4.y * sin4;
        float h = re * own_cluster_transmittance(tau, rho, c1, s1);
        h01 += h * vec3(0.5, c1, s1);
        h23 += h * vec4(c2, s2, c3, s3);
        h4 += h * vec2(cos4, sin4);
        float c_next = c1 * cs - s1 * sn;
        s1 = s1 * cs + c1 * sn;
        c1 = c_next;
    }
    float norm = 2.0 / float(OWN_CLUSTER_POINTS);
    h01 *= norm;
    h23 *= norm;
    h4 *= norm;
}

#endif
