#pragma once
// The viewer's actions as data (`coif view --script FILE`): what a person does in the window, replayable by tests
// and by people. The whole script is read and checked before the window opens, so a bad one changes and writes
// nothing.
//
// The file: a JSON array of actions, each an object with exactly one key, done in order; the viewer draws a frame
// after each one (so each change shows in the next frame) and quits after the last:
//   {"orbit": [AZIMUTH_DEG, ELEVATION_DEG]}  the camera's angles around the hair (as coif render's options)
//   {"zoom": FACTOR}                        the eye's distance times FACTOR (0.1 … 10 times the framing distance)
//   {"pan": [X, Y]}                         move the view by X, Y times the framed height (right, up)
//   {"fit": true}                           frame the hair again: no pan, no zoom
//   {"set": {KEY: VALUE, …}}                parameters, the keys of `coif render --params` (coif render --help)
//   {"params": "FILE.json"}                 parameters read from a file, as coif render --params reads it
//   {"background": true|false}              the environment's lights behind the hair, or the plain background
//   {"exposure": STOPS}                     the display's and the PNG screenshots' exposure
//   {"rotate_lights": DEG}                  the environment turned about +y, as coif render --rotate-lights
//   {"env": "FILE"}                         the environment: SRBF lights JSON, or a map fitted with 40 lights
//   {"env": {"file": "FILE", "lights": N}}  a map fitted with N lights (1 … 1024), as `coif env fit --lights N`
//   {"paint": {"at": [X, Y], "radius": PX, "strength": S, "sigma_a": [R, G, B]}}
//                                           one dab of the absorption brush at window pixel (X, Y) (top left 0, 0);
//                                           radius (default 12), strength 0 … 1 (0.5) and sigma_a (4 5 6) optional
//   {"undo": true} / {"redo": true}         the last paint stroke undone, or redone
//   {"save_absorption": "FILE.exr"}         the painted map, as coif render --absorption reads it
//   {"frames": N}                           draw N more frames (1 … 10000) with nothing changed
//   {"screenshot": "FILE.png|.exr"}         write what `coif render` writes for this camera and these parameters
//   {"capture": "FILE.png"}                 write the window's pixels as shown, the panel included when shown
//   {"panel": true|false}                   show or hide the panel
#include <filesystem>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace coif::gl {

struct ViewerAction {
    enum class Kind {
        orbit, zoom, pan, fit, set, params, background, panel, exposure, rotate_lights, env, paint, undo, redo,
        save_absorption, frames, screenshot, capture
    };
    Kind kind = Kind::frames;
    double x = 0, y = 0;            // orbit (degrees), pan, zoom (x), exposure (x), rotate_lights (x), frames (x)
    int lights = 40;                // env: SRBF lights fitted to a map
    double radius = 12, strength = 0.5;        // paint (at: x, y)
    glm::vec3 sigma_a{4.0f, 5.0f, 6.0f};       // paint
    bool on = false;                // background, panel
    nlohmann::json values;          // set: the parameters' keys and values
    std::filesystem::path path;     // params, env, save_absorption, screenshot, capture
    std::string where;              // "FILE: action N" for messages
};

// Reads and checks a script; throws coif::Error naming the file and the action (unknown actions, values out of
// range, parameters that `coif render --params` would refuse, image names without .png or .exr).
std::vector<ViewerAction> read_viewer_script(const std::filesystem::path& file);

}  // namespace coif::gl
