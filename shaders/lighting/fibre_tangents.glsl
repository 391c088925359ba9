// The fibres' tangents about the one tangent T that a cluster is lit with (ShellSettings::tangent_spread,
// docs/quality.md "The fibres' tangents about the axis"). GLSL compiled also as C++ (shaders/glsl_prelude.h);
// see the rules there.
//
// The strands a cluster stands for stray from its axis by an RMS angle σ (tangent_spread_about_axes,
// online/shells/prepared_shells.h: 35° for the default style). Lighting them all with T gives every fibre the
// axis's angles to the view and the lights; a fibre tilted toward or across the view has other azimuths for
// TT and TRT as well as another θ, which widening the longitudinal lobes alone left out. So the lighting is
// the mean over n tangents at angle σ from T, evenly around it: their mean square tilt is σ², and for n ≥ 3
// the tilts' second moment is isotropic. The ring starts half a step from the view's side, e = V projected
// on T's normal plane (r0 when V lies along T), so that it turns with the view rather than with the cluster's
// arbitrary frame. Tangent q (0 ≤ q < n): Tq, and the normal rq = r0 made perpendicular to Tq.
#ifndef COIF_SHADERS_LIGHTING_FIBRE_TANGENTS_GLSL
#define COIF_SHADERS_LIGHTING_FIBRE_TANGENTS_GLSL

#ifndef COIF_FN
#define COIF_FN
#endif

COIF_FN void fibre_tangent(vec3 T, vec3 r0, vec3 V, float sigma, int q, int n, OUT(vec3) Tq, OUT(vec3) rq) {
    if (n <= 1) {
        Tq = T;
        rq = r0;
        return;
    }
    vec3 e = V - dot(V, T) * T;
    if (dot(e, e) > 1e-8) e = normalize(e);
    else e = r0;
    float a = 6.28318530718 * (float(q) + 0.5) / float(n);
    Tq = normalize(cos(sigma) * T + sin(sigma) * (cos(a) * e + sin(a) * cross(T, e)));
    rq = normalize(r0 - dot(r0, Tq) * Tq);
}

#endif
