// The shell renderer's lighting samples along each cluster's axis (online/shells/prepared_shells.h
// LightingSample, its std430 mirror), cluster-major, as the lighting and shadow passes read them.
#ifndef COIF_SHADERS_GL_LIGHTING_SAMPLES_GLSL
#define COIF_SHADERS_GL_LIGHTING_SAMPLES_GLSL

struct LightingSample {
    vec4 position;  // world; w: outer radius of the cluster at the sample (world units)
    vec4 tangent;   // root → tip
    vec4 normal;    // the cylinder's frame normal: the reference axis of azimuths
    vec4 tilt_mean;  // the fibres' tilts about the tangent: mean, and the axes a, b of their spread
    vec4 tilt_a;     // (shaders/lighting/fibre_tangents.glsl), vectors ⟂ tangent of length the angle
    vec4 tilt_b;
};
layout(std430, binding = 2) readonly buffer Samples { LightingSample samples[]; };

#endif
