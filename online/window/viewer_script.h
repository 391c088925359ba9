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
// Cluster authoring (a style's, not a baked asset's: models/style_edit.h, as `coif style transform|…` does them); each
// edit is one undo step with the strokes, and the shells are cooked again:
//   {"select": ["c3", …]}                   select clusters by name ([]: none)
//   {"pick": [X, Y]}                        select the cluster under window pixel (X, Y) (none there: none)
//   {"drag_point": {"point": I, "from": [X, Y], "to": [X, Y], "axis": "view"|"x"|"y"|"z", "steps": N}}
//                                           drag the selected cluster's trajectory control point I: it moves with the
//                                           cursor in the plane facing the camera through it ("view", the default), or
//                                           along one axis only; the cursor passes N even steps (default 1), each
//                                           applied as a mouse drag's frames are, the whole drag one undo step
//   {"transform": {"translate": [X, Y, Z], "rotate_deg": [X, Y, Z], "scale": S}}   the selection moved (each key
//                                           optional; turned and scaled about the centre of its roots)
//   {"duplicate": {"translate": [X, Y, Z], "as_copy": false}}   copies of the selection, moved; they become the selection
//   {"mirror": {"axis": "x", "at": X}}      mirror images of the selection (at: default the middle of the roots)
//   {"add": [X, Y]}                         a cluster added from nothing, rooted on the scalp under window pixel
//                                           (X, Y) (the sphere that fits the roots), leaving it outward and falling,
//                                           shaped like its nearest neighbour (and its mirror image in symmetry mode);
//                                           it becomes the selection
//   {"delete": true}                        the selection removed
//   {"profile": {"a"|"b"|"theta_deg": [V, …]}}   the selected cluster's profile's control points
//   {"layers": N}                           the selected cluster's own number of layered shells (its prototype's)
//   {"symmetry": true|false}                symmetry mode: a drag, profile edit or transform also makes each mirror
//                                           partner across the head's plane (x = the middle of the roots) not selected
//                                           the mirror image of its edited cluster
//   {"save_style": "FILE.json"}             the edited style, as `coif render --style` reads it
#include <filesystem>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace coif::gl {

struct ViewerAction {
    enum class Kind {
        orbit, zoom, pan, fit, set, params, background, panel, exposure, rotate_lights, env, paint, undo, redo,
        save_absorption, frames, screenshot, capture, select, pick, drag_point, transform, duplicate, mirror, remove,
        add, profile, save_style, symmetry, layers
    };
    Kind kind = Kind::frames;
    double x = 0, y = 0;            // orbit (degrees), pan, zoom (x), exposure (x), rotate_lights (x), frames (x), pick, add
    int lights = 40;                // env: SRBF lights fitted to a map
    double radius = 12, strength = 0.5;        // paint (at: x, y)
    glm::vec3 sigma_a{4.0f, 5.0f, 6.0f};       // paint
    bool on = false;                // background, panel, symmetry
    nlohmann::json values;          // set: the parameters' keys and values
    std::filesystem::path path;     // params, env, save_absorption, screenshot, capture
    std::string where;              // "FILE: action N" for messages
    // Cluster authoring.
    std::vector<std::string> names;          // select
    double to_x = 0, to_y = 0;               // drag_point: from (x, y) to (to_x, to_y)
    int point = 0;                           // drag_point; layers: the count
    int steps = 1;                           // drag_point
    int axis = -1;                           // drag_point (−1: the view plane), mirror: 0, 1, 2 = x, y, z
    std::optional<double> at;                // mirror's plane
    glm::dvec3 translate{0.0}, rotate_deg{0.0};
    double scale = 1.0;                      // transform, duplicate
    bool as_copy = false;                    // duplicate
    std::string profile;                     // profile: a, b or theta_deg
    std::vector<double> profile_values;
};

// Reads and checks a script; throws coif::Error naming the file and the action (unknown actions, values out of
// range, parameters that `coif render --params` would refuse, image names without .png or .exr).
std::vector<ViewerAction> read_viewer_script(const std::filesystem::path& file);

}  // namespace coif::gl
