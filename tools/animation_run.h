#pragma once
// `coif render --animate SPEC` and `coif bench animate`: the scene's skinned style on its --body, posed frame by frame
// by an animation spec (models/animation.h) through online/scene/hair_motion.h, each frame drawn by the shell renderer.
#include <functional>
#include <string>
#include <vector>

#include "models/animation.h"
#include "models/core/image.h"
#include "tools/scene_options.h"

namespace coif::cli {

struct AnimationFrame {  // wall-clock milliseconds of one frame
    double skinning_ms = 0, deformation_ms = 0, shadow_grid_ms = 0;  // the motion (CPU, and the uploads)
    double shadows_ms = 0, lighting_ms = 0, shells_ms = 0;            // the renderer's passes (timed)
    double total_ms = 0;                                              // the whole frame
};

struct AnimationResult {
    std::vector<AnimationFrame> frames;
    AnimationFrame still;  // the same scene at rest, drawn again with nothing moved (the static frame's cost)
    double fps = 30;
    int width = 0, height = 0;
    std::string renderer;  // the GL renderer's name
    // Where the clusters' roots sit on the body: each root's signed distance from its nearest body vertex along that
    // vertex's normal (scene units; < 0 inside), the extremes over the roots at rest and over every animated frame.
    // Hair that floats off or sinks in moves these beyond the rest range.
    glm::dvec2 rest_root_offset{0.0}, animated_root_offset{0.0};
};

// Reads and checks everything first (the style and its skinning, the --body, the spec's bones: a wrong input writes nothing),
// then renders every frame, handing each image to `frame_out` (may be empty), and the rest frame's cost. Throws
// coif::Error.
AnimationResult run_animation(const SceneOptions& scene, const ShellOptions& shell, const AnimationSpec& spec,
                              const std::function<void(int, const Image&)>& frame_out);

// The frame images' file names beside `output` (out.png → out_0000.png …) and the contact sheet's (out_sheet.png).
std::string animation_frame_path(const std::string& output, int frame);
std::string animation_sheet_path(const std::string& output);
// The contact sheet: n frames side by side, ⌈√n⌉ to a row, each shrunk by the whole factor sheet_factor (a box filter)
// so that the sheet is at most 2048 pixels wide.
int sheet_factor(int frames, int width);
Image shrink(const Image& image, int factor);
Image contact_sheet(const std::vector<Image>& thumbnails);

}  // namespace coif::cli
