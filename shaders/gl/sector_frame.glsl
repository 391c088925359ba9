// In-plane angles of a generalized sector, defined once for the renderer (DESIGN.md "Sector
// coordinates", docs/db.md, offline/planar_tracer.h). GLSL compiled also as C++ (no GL calls).
//
// A sector lies in the normal plane of the hair tangent T. Its radial axis r is the outward surface
// normal N of the layer mesh projected into that plane (r follows v, outward); its track axis is
// s = T × r, which follows u (the layer mesh's normal is N = ∂P/∂u × ∂P/∂t, so s × T = N).
// An azimuth θ is measured from r towards s: dir(θ) = (sin θ, cos θ) in (s, r), θ ∈ (−π, π].
// The view azimuth θv is the direction from the surface TOWARDS the eye, θl the one towards the light.
#ifndef COIF_SHADERS_GL_SECTOR_FRAME_GLSL
#define COIF_SHADERS_GL_SECTOR_FRAME_GLSL

#ifndef COIF_FN
#define COIF_FN
#endif

// The sector's outward radial axis r from the surface normal N and the unit tangent T.
COIF_FN vec3 sector_radial(vec3 N, vec3 T) {
    vec3 r = N - dot(N, T) * T;
    float len = length(r);
    return len > 1e-6 ? r / len : N;
}

// In-plane azimuth of d (any length) about the unit tangent T from the unit radial axis r.
COIF_FN float sector_azimuth(vec3 d, vec3 T, vec3 r) {
    vec3 s = cross(T, r);
    float x = dot(d, r);
    float y = dot(d, s);
    return (abs(x) + abs(y) > 1e-12) ? atan(y, x) : 0.0;
}

// A light's spread as an in-plane angle about the unit tangent T: λ' = λ over the length of its unit direction l
// projected on the normal plane of T. Harmonic k of the light's azimuth is damped by d_k = exp(−k² λ'² / 4) (the Fourier
// coefficient of a circular Gaussian of bandwidth λ' for small λ').
COIF_FN float light_spread(vec3 l, float lambda, vec3 T) { return lambda / max(length(l - dot(l, T) * T), 1e-3f); }

#endif
