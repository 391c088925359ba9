#pragma once
// The interactive viewer: a window (online/window/window.h) showing strands with the strand preview
// (online/strand_preview.h) and an orbit camera. Drag with the left mouse button to orbit, scroll to zoom,
// Esc or Q to quit. Its inputs are plain data; `coif view` parses them from options.
#include <glm/glm.hpp>
#include <optional>

#include "models/core/camera.h"
#include "models/core/image.h"
#include "models/strands.h"
#include "online/strand_preview.h"

namespace coif::gl {

struct ViewerOptions {
    Strands strands;                           // what is drawn
    glm::vec3 frame_min{0.0f}, frame_max{0.0f};  // the box the camera orbits (and frames at zoom 1)
    OrbitView view;                            // the first frame's camera; width × height is the window's size
    StrandPreviewSettings preview;
    int frames = 0;                            // quit after this many frames; 0: when the window is closed
    bool keep_last_frame = false;              // read the last frame back (ViewerResult::last_frame)
};

struct ViewerResult {
    int frames = 0;                   // frames drawn
    std::optional<Image> last_frame;  // linear RGBA, when asked for and a frame was drawn
};

// Opens the window and runs until Esc/Q, the window's closing or `frames` frames; throws coif::Error when no
// window can be opened.
ViewerResult run_viewer(const ViewerOptions& options);

}  // namespace coif::gl
