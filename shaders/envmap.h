#pragma once
// C++ view of shaders/envmap.glsl (the equirectangular pixel <-> direction mapping and the SRBF of
// 000 Table 1) in namespace coif::glsl. The conventions are documented in the .glsl file.
#include "shaders/glsl_prelude.h"

namespace coif::glsl {
#include "shaders/envmap.glsl"
}  // namespace coif::glsl
