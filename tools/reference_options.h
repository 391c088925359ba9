#pragma once
// Options of `coif reference` that `coif bench quality` shares: hair scattering parameters, lighting and
// path-tracing settings. Degrees at the interface, radians in the code (DESIGN.md).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "offline/reference.h"
#include "shaders/lighting.h"
#include "tools/cli.h"
#include "tools/hair_options.h"

namespace coif::cli {

struct ReferenceCliOptions {
    // Lighting: at most one of these; none = a constant white environment of radiance 1.
    std::string env;                 // equirectangular .exr/.hdr map
    std::string lights;              // SRBF lights JSON (coif env fit)
    std::vector<float> env_constant; // R G B
    double rotate_lights_deg = 0;    // the map or lights turned about +y
    // Hair: --params FILE and the shorthand flags (shading::default_hair_params unless given).
    HairCliOptions hair;
    // Path tracing.
    ReferenceSettings settings;
    std::vector<float> background;   // R G B
    bool background_env = false;

    void add_to(CLI::App* app);
    shading::HairParams hair_params() const;  // the fibre's parameters; validated (coif::Error naming the file or option)
    ReferenceEnvironment environment() const;
    ReferenceSettings reference_settings() const;
    // The lighting options as command-line text (for `coif bench quality`, which runs `coif reference`).
    std::string lighting_args() const;
};

}  // namespace coif::cli
