#pragma once
// C++ view of shaders/lighting/common.glsl (the SRBF lighting's shared math and the luminance weights) in namespace
// coif::glsl, for C++ that needs those alone without the lighting's tables.
#include "shaders/glsl_prelude.h"

namespace coif::glsl {
#include "shaders/lighting/common.glsl"
}  // namespace coif::glsl
