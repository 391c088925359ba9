#pragma once
// Options shared by the commands that draw a scene (render, view): which strands, and the camera.
#include <glm/glm.hpp>
#include <string>
#include <utility>

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
    std::string frame_strands;  // when set, the camera frames this strand file (oriented as --strands) instead

    void add_to(CLI::App* app);
    // The strands to draw: the --strands file, else strands sampled from the style's densities
    // (oriented y-up unless keep_axes). `label` says which, for messages and image metadata.
    Strands load_strands(std::string* label = nullptr) const;
    // `s` as load_strands orients what it loads: its hang axis turned to -y, unless keep_axes.
    Strands oriented(Strands s) const;
    // The box the camera frames: the --frame-strands file's strands' (oriented as load_strands orients a
    // --strands file) when given, else `drawn`'s.
    std::pair<glm::vec3, glm::vec3> frame_box(const Strands& drawn) const;
    // The orbit camera of these options around a box.
    Camera camera_around(const std::pair<glm::vec3, glm::vec3>& box) const;
    Camera camera_for(const Strands& drawn) const { return camera_around(frame_box(drawn)); }
};

}  // namespace coif::cli
