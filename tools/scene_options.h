#pragma once
// Options shared by the commands that draw a scene (render, view): which strands, and the camera.
#include <glm/glm.hpp>
#include <string>

#include "models/core/camera.h"
#include "models/strands.h"
#include "tools/cli.h"

namespace coif::cli {

struct SceneOptions {
    std::string strands;      // empty: the embedded default strands
    int width = 720, height = 480;
    double azimuth_deg = 20, elevation_deg = 10, fov_deg = 40;
    bool keep_axes = false;   // do not rotate the model's hang axis to -y

    void add_to(CLI::App* app);
    // Loads the strands (oriented y-up unless keep_axes) and frames them with the camera.
    Strands load_strands(std::string* label = nullptr) const;
    Camera camera_for(const Strands& strands) const;
};

}  // namespace coif::cli
