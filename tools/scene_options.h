#pragma once
// Options shared by the commands that draw a scene (render, view): which strands, and the camera.
#include <glm/glm.hpp>
#include <string>

#include "models/core/camera.h"
#include "models/hair_style.h"
#include "models/strands.h"
#include "tools/cli.h"

namespace coif::cli {

// "@default" names the hairstyle embedded in the binary (tools/assets/default_style.json).
inline constexpr const char* kDefaultStyleName = "@default";

// A style file, or the embedded default style for "@default".
HairStyle load_style(const std::string& path);

struct SceneOptions {
    std::string style = kDefaultStyleName;
    std::string strands;      // when set, these strands instead of the style's
    int width = 720, height = 480;
    double azimuth_deg = 20, elevation_deg = 10, fov_deg = 40;
    bool keep_axes = false;   // do not rotate the model's hang axis to -y

    void add_to(CLI::App* app);
    // The strands to draw: the --strands file, else strands sampled from the style's densities
    // (oriented y-up unless keep_axes). `label` says which, for messages and image metadata.
    Strands load_strands(std::string* label = nullptr) const;
    Camera camera_for(const Strands& strands) const;
};

}  // namespace coif::cli
