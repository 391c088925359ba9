#pragma once
// The interactive viewer, `coif view`: the SATF shell renderer (online/shell_renderer.h) in a window
// (online/window/window.h), the scene built exactly as `coif render` builds it (online/scene/hair_scene.h: a style
// cooked against the database, or a baked `.coif` asset, view-only), shown with coif render's PNG tone map
// (shaders/display.glsl: exposure, clip, sRGB) over the environment's SRBF lights or the plain background.
//
// Mouse and keys: left drag orbits, right drag (or Shift + left drag) pans, the wheel zooms; F frames the hair
// again, B switches the environment background, + and − change the exposure by a third of a stop, S writes a
// screenshot (what `coif render` writes for this camera: --screenshot, else coif-view-N.png), Tab hides the panel,
// Esc or Q quits. Ctrl + left drag paints absorption. Cluster authoring (a style's; online/shells/authoring.h): Alt +
// click selects the cluster under the cursor (Alt + Shift + click adds or removes one), a left drag from one of its
// control points' handles moves that point in the plane facing the camera (X or Y: along that axis only), Delete
// removes the selection, and the panel's "clusters" section adds a cluster on the scalp where the next click lands,
// duplicates, mirrors, deletes and saves the style. Ctrl + Z and Ctrl + Y undo and redo strokes and edits alike. An
// edited style is cooked again, keeping what the edit did not change (online/scene/cook.h CookCache: 29–36 ms for a
// dragged point of the default style; the view keeps its framing).
// The panel (Dear ImGui) edits every parameter of `coif render --params` (saved to and loaded from that file), the
// hair's colour as melanin concentrations, the exposure, and the environment: its turn, and a map
// from `maps_folder` fitted with a chosen number of SRBF lights in the background while the viewer goes on (quitting
// during a fit waits for it to end).
// While the camera is dragged the frame is drawn at half size and scaled up, so that it follows the mouse; it is
// drawn at full size again when the mouse is let go, and refined when still: 2 × 2 frames shifted within the
// pixel (coif render --samples 4's offsets) are averaged, then the viewer only displays until something changes. The window's title shows the frame time and its passes.
// Scripts (online/window/viewer_script.h) replay the same actions without a person.
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "models/absorption_map.h"
#include "models/core/camera.h"
#include "online/benchmarks.h"
#include "online/scene/hair_scene.h"
#include "online/shells/shell_settings.h"
#include "online/window/viewer_script.h"

namespace coif::gl {

// The viewer's camera: an orbit around the framed box as coif render places it, then zoomed and panned.
struct ViewerCamera {
    double azimuth = 0, elevation = 0;  // radians, as OrbitView
    double zoom = 1;                    // the eye's distance over the framing distance, 0.1 … 10
    glm::dvec2 pan{0.0};                // the target moved right and up, in framed heights
    // The camera for a `width` × `height` frame of the box; with zoom 1 and no pan, exactly coif render's.
    Camera camera(const OrbitView& base, glm::vec3 box_min, glm::vec3 box_max, int width, int height) const;
};

struct ViewerOptions {
    // The scene (its `headless` and `absorption` are ignored: the window's context draws it, with `absorption`
    // below); its lights as read, before the turn.
    HairSceneDesc scene;
    std::optional<AbsorptionMap> absorption;  // painted σa to start from (coif render --absorption), or none
    double rotate_lights_deg = 0;        // the environment turned about +y (coif render --rotate-lights)
    std::filesystem::path maps_folder;   // where the panel lists environment maps (.exr, .hdr); empty: none
    ShellSettings settings;   // the parameters to start from
    OrbitView view;           // the first camera; width × height is the window's size
    float exposure = 0;       // stops: the display and PNG screenshots
    bool environment = true;  // the environment's lights as the background, else settings.background
    std::vector<ViewerAction> script;  // replayed in order, then the viewer quits (online/window/viewer_script.h)
    int frames = 0;                    // without a script: quit after this many frames (0: when closed)
    std::filesystem::path screenshot;  // the S key's file (empty: coif-view-N.png in the working folder)
    // After the script (coif bench view): time this many frames of the renderer alone, drawn offscreen at the
    // window's size with the same camera and parameters, as `coif bench render` times them (0: none).
    int offscreen_frames = 0;
};

struct ViewerResult {
    int frames = 0;                               // frames drawn
    double last_frame_ms = 0;                     // wall time of the last frame, display included
    std::vector<double> frame_ms;                 // of every frame, in order (each waited for)
    std::optional<ShellFrameTimes> offscreen;     // ViewerOptions::offscreen_frames' medians
    std::vector<std::filesystem::path> written;   // screenshots and captures, in order
};

// Builds the scene, opens the window and runs until Esc/Q, the window's closing, `frames` frames or the script's
// end; throws coif::Error when no window can be opened, the scene cannot be built, or an action fails (a file
// that cannot be written: nothing partial is left).
ViewerResult run_viewer(ViewerOptions options);

}  // namespace coif::gl
