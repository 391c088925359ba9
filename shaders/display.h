#pragma once
// C++ view of shaders/display.glsl (the tone map from linear radiance to sRGB display values) in namespace coif::glsl.
#include "shaders/glsl_prelude.h"

namespace coif::glsl {
#include "shaders/display.glsl"
}  // namespace coif::glsl
