// The fibres' tangents about the one tangent T that a cluster is lit with (ShellSettings::tangent_spread,
// docs/quality.md "The fibres' tangents about the axis"). GLSL compiled also as C++ (shaders/glsl_prelude.h);
// see the rules there.
//
// The strands a cluster stands for stray from its axis: by 35° RMS for the default style. Lighting them all
// with T gives every fibre the axis's angles to the view and the lights. A fibre tilted toward or across the
// view also has other azimuths, and TT and TRT depend on them; widening the longitudinal lobes alone left
// that out. So the lighting is the mean over four fibre tangents. A tilt is a vector v ⟂ T whose length is the
// angle: the tangent tilted by v is cos|v| T + sin|v| v/|v|. The four tilts are m ± a and m ± b:
//   - measured (the default): m is the mean tilt of the style's strands at a lighting sample, and a, b are the
//     principal axes of their spread about it, scaled by √2 so that the four tilts have the strands' second
//     moment (online/shells/prepared_shells.h measure_fibre_tilts);
//   - a ring (tangent_spread_deg given): m = 0 and a, b of length σ at ±45° from e, the view projected on T's
//     normal plane (r0 when the view lies along T), so that the ring turns with the view.
// Tangent q's frame is Tq and the normal rq (r0 made perpendicular to Tq).
#ifndef COIF_SHADERS_LIGHTING_FIBRE_TANGENTS_GLSL
#define COIF_SHADERS_LIGHTING_FIBRE_TANGENTS_GLSL

#ifndef COIF_FN
#define COIF_FN
#endif

// Tilt q (0..3) of the four: m + a, m − a, m + b, m − b.
COIF_FN vec3 fibre_tilt(vec3 m, vec3 a, vec3 b, int q) {
    if (q == 0) return m + a;
    if (q == 1) return m - a;
    if (q == 2) return m + b;
    return m - b;
}

// The ring's axes a, b for an isotropic spread σ (RMS angle) seen from V.
COIF_FN void fibre_ring_axes(vec3 T, vec3 r0, vec3 V, float sigma, OUT(vec3) a, OUT(vec3) b) {
    vec3 e = V - dot(V, T) * T;
    if (dot(e, e) > 1e-8) e = normalize(e);
    else e = r0;
    vec3 f = cross(T, e);
    a = (0.70710678 * sigma) * (e + f);
    b = (0.70710678 * sigma) * (e - f);
}

// The tangent tilted by v (its part ⟂ T) and its normal.
COIF_FN void fibre_tangent(vec3 T, vec3 r0, vec3 v, OUT(vec3) Tq, OUT(vec3) rq) {
    vec3 w = v - dot(v, T) * T;
    float angle = length(w);
    if (angle > 1e-6) Tq = normalize(cos(angle) * T + sin(angle) * (w / angle));
    else Tq = T;
    rq = normalize(r0 - dot(r0, Tq) * Tq);
}

// Tangent q of n (q < n) and its normal: T itself when n is 1, else the tangent tilted by tilt q of the four.
COIF_FN void fibre_tangent_of(vec3 T, vec3 r0, vec3 m, vec3 a, vec3 b, int q, int n, OUT(vec3) Tq, OUT(vec3) rq) {
    if (n <= 1) {
        Tq = T;
        rq = r0;
        return;
    }
    fibre_tangent(T, r0, fibre_tilt(m, a, b, q), Tq, rq);
}

#endif
