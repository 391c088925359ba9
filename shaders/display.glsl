#ifndef COIF_SHADERS_DISPLAY_GLSL
#define COIF_SHADERS_DISPLAY_GLSL
// Linear radiance to a display value: THE tone map of coif, written once for the PNG writer (models/core/image.cpp,
// through shaders/display.h) and the viewer's display pass (shaders/gl/viewer_present.frag). The exposure scale
// (2^stops) multiplies, the result is clipped to [0, 1] (NaN shows as 0, +inf as 1) and encoded with the sRGB curve
// (IEC 61966-2-1).
#ifndef COIF_FN
#define COIF_FN
#endif

COIF_FN float tone_map_srgb(float linear, float exposure_scale) {
    float v = linear * exposure_scale;
    v = (v != v) ? 0.0 : clamp(v, 0.0, 1.0);  // v != v: NaN
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

#endif  // COIF_SHADERS_DISPLAY_GLSL
