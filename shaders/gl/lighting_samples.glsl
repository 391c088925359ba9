// The shell renderer's lighting samples along each cluster's axis (online/shells/prepared_shells.h
// LightingSample, its std430 mirror), cluster-major, as the lighting and shadow passes read them.
#ifndef COIF_SHADERS_GL_LIGHTING_SAMPLES_GLSL
#define COIF_SHADERS_GL_LIGHTING_SAMPLES_GLSL

struct LightingSample {
    vec4 position;  // world; w: the cross-section's half-axis A (world units) along e1 = cos θ n + sin θ (t × n)
    vec4 tangent;   // root → tip; w: the half-axis B along t × e1
    vec4 normal;    // the cylinder's frame normal n: the reference axis of azimuths; w: θ (radians)
    vec4 tilt_mean;  // the fibres' tilts about the tangent: mean, and the axes a, b of their spread
    vec4 tilt_a;     // (shaders/lighting/fibre_tangents.glsl), vectors ⟂ tangent of length the angle
    vec4 tilt_b;
};
layout(std430, binding = 2) readonly buffer Samples { LightingSample samples[]; };

// The frame normal made ⟂ T (T the sample's normalised tangent): the reference axis of azimuths.
vec3 sample_frame_normal(LightingSample s, vec3 T) { return normalize(s.normal.xyz - dot(s.normal.xyz, T) * T); }
// The cross-section's axis of A, e1 = cos θ n + sin θ (T × n).
vec3 sample_ellipse_axis(LightingSample s, vec3 T) {
    vec3 n = sample_frame_normal(s, T);
    return cos(s.normal.w) * n + sin(s.normal.w) * cross(T, n);
}

// The cluster's axis at t ∈ [0, 1] of lighting cluster `cluster`, `rows` samples to a cluster: linear between the
// two samples around t.
vec3 sample_axis_point(float t, uint cluster, int rows) {
    float tr = clamp(t, 0.0, 1.0) * float(rows - 1);
    int row = min(int(tr), rows - 2);
    int first = int(cluster) * rows + row;
    return mix(samples[first].position.xyz, samples[first + 1].position.xyz, tr - float(row));
}

#endif
