// coif view — the interactive viewer (online/window/viewer.h): the shell renderer of `coif render` in a window, the
// same scene from the same options, and scripts of viewer actions (online/window/viewer_script.h).
#include <cstdio>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <memory>

#include "models/core/error.h"
#include "models/core/statistics.h"
#include "online/scene/hair_scene.h"
#include "online/window/viewer.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct ViewOptions {
    coif::cli::SceneOptions scene;
    coif::cli::ShellOptions shell;
    int frames = 0;
    float exposure = 0.0f;
    bool no_environment = false;
    std::string screenshot, script, maps;
};

// The viewer's inputs from the options; everything that can be refused is read before the window opens.
coif::gl::ViewerOptions viewer_options(const ViewOptions& opts) {
    const ViewOptions* o = &opts;
    coif::gl::ViewerOptions vo;
    if (!o->scene.strands.empty())
        throw coif::Error::parameter("option --strands", "coif view draws a style's shells; `coif render --strands` draws strands");
    if (!o->script.empty()) vo.script = coif::gl::read_viewer_script(o->script);
    // The lights as read: the viewer turns them (live, --rotate-lights to start with).
    coif::cli::SceneInputs inputs = coif::cli::read_scene_inputs(o->scene, o->shell.env);
    inputs.body = o->shell.body_mesh(inputs);
    vo.rotate_lights_deg = o->shell.rotate_lights_deg;
    (void)coif::cli::lights_rotation(vo.rotate_lights_deg);  // refused now if not finite
    vo.settings = o->shell.settings(inputs);
    namespace fs = std::filesystem;
    if (!o->maps.empty()) {
        if (!fs::is_directory(o->maps)) throw coif::Error(o->maps, "", "not a folder (option --maps)");
        vo.maps_folder = o->maps;
    } else if (!o->shell.env.empty()) {
        vo.maps_folder = fs::absolute(o->shell.env).parent_path();
    } else if (fs::is_directory("../shared/data")) {
        vo.maps_folder = "../shared/data";
    }
    vo.absorption = o->shell.absorption_map(inputs);
    vo.scene = coif::cli::hair_scene_desc(o->scene, std::move(inputs), o->shell.db, o->shell.lighting_rows);
    vo.view = o->scene.orbit_view();
    vo.exposure = o->exposure;
    vo.environment = !o->no_environment;
    vo.frames = o->frames;
    vo.screenshot = o->screenshot;
    if (!o->screenshot.empty() && o->script.empty() && o->frames > 0) {  // draw the frames, then the screenshot
        coif::gl::ViewerAction frames, shot;
        frames.kind = coif::gl::ViewerAction::Kind::frames;
        frames.x = o->frames;
        shot.kind = coif::gl::ViewerAction::Kind::screenshot;
        shot.path = o->screenshot;
        shot.where = "option --screenshot";
        vo.script = {frames, shot};
    }
    return vo;
}

void add_view(CLI::App& root) {
    auto o = std::make_shared<ViewOptions>();  // --samples: the screenshots' (frames are one sample, then refined)
    CLI::App* view = root.add_subcommand(
        "view",
        "Open the renderer in a window: `coif render`'s scene, live\n"
        "The SATF shells lit by the SRBF lights, exactly as `coif render` draws them from the same options (a style\n"
        "cooked against the database, or a baked .coif asset, view-only), shown sRGB as coif render's PNGs, over the\n"
        "environment's lights (B: the plain --background instead). It needs a display: use `xvfb-run -a coif view`\n"
        "without one.\n"
        "Left drag orbits, right drag (or Shift + left drag) pans, the wheel zooms, F frames the hair again, + and -\n"
        "change the exposure, S writes a screenshot (the image `coif render` writes for this camera), Ctrl + left drag\n"
        "paints absorption onto the hair under the cursor (Ctrl+Z undoes a stroke, Ctrl+Y redoes it; the panel saves\n"
        "the map that `coif render --absorption` reads), Esc or Q quits.\n"
        "On a style (not an asset) clusters are edited: Alt + click selects the cluster under the cursor (Alt + Shift\n"
        "adds or removes one), a left drag from one of its control points' handles moves that point (X, Y: along that\n"
        "axis only), Delete removes the selection, and the panel's \"clusters\" section edits A, B, theta and the layer\n"
        "count, adds a cluster on the scalp where you click next, duplicates, mirrors and saves the style. Ctrl+Z and\n"
        "Ctrl+Y undo and redo strokes and edits alike; each edit cooks only what it changed (about 35 ms for one\n"
        "cluster of the default style), so a dragged point follows the cursor.\n"
        "While the camera is dragged the frame is drawn at half size. Tab hides the panel: the frame time and its\n"
        "passes, every --params key (saved to and loaded from that file), the hair colour as melanin, the exposure,\n"
        "and the environment (its turn, and a map of --maps fitted with N SRBF lights while the viewer goes on).\n"
        "--script FILE replays viewer actions instead of a person (a JSON array; each action is one object):\n"
        "  {\"orbit\": [AZ, EL]} {\"zoom\": F} {\"pan\": [X, Y]} {\"fit\": true} {\"set\": {PARAMS}} {\"params\": FILE}\n"
        "  {\"background\": true|false} {\"panel\": true|false} {\"exposure\": STOPS} {\"rotate_lights\": DEG}\n"
        "  {\"env\": FILE} {\"env\": {\"file\": MAP, \"lights\": N}} {\"frames\": N} {\"screenshot\": FILE} {\"capture\": FILE}\n"
        "  {\"paint\": {\"at\": [X, Y], \"radius\": PX, \"strength\": S, \"sigma_a\": [R, G, B]}} {\"undo\": true} {\"redo\": true}\n"
        "  {\"save_absorption\": FILE.exr} {\"select\": [NAME, ...]} {\"pick\": [X, Y]}\n"
        "  {\"drag_point\": {\"point\": I, \"from\": [X, Y], \"to\": [X, Y], \"axis\": \"view\"|\"x\"|\"y\"|\"z\"}}\n"
        "  {\"transform\": {\"translate\": [X, Y, Z], \"rotate_deg\": [X, Y, Z], \"scale\": S}} {\"duplicate\": {\"translate\": [..],\n"
        "  \"as_copy\": false}} {\"mirror\": {\"axis\": \"x\", \"at\": X}} {\"add\": [X, Y]} {\"delete\": true}\n"
        "  {\"profile\": {\"a\": [V, ...]}} {\"layers\": N} {\"symmetry\": true|false} {\"save_style\": FILE.json}\n"
        "  (online/window/viewer_script.h says what each does)\n"
        "A frame is drawn after each action, and the viewer quits after the last. The whole script is checked first:\n"
        "an unknown action or a value out of range is refused before the window opens.");
    o->scene.add_to(view);
    o->shell.add_to(view);
    view->add_option("--frames", o->frames, "Quit after this many frames (0 = run until closed); for scripts and tests")
        ->check(CLI::NonNegativeNumber);
    view->add_option("--exposure", o->exposure, "Exposure in stops, of the display and of PNG screenshots")->capture_default_str();
    view->add_flag("--no-environment", o->no_environment, "Start with the plain --background behind the hair (B switches)");
    view->add_option("--screenshot", o->screenshot,
                     "The image the S key writes (.png/.exr; default coif-view-N.png); without a script, also written "
                     "when the viewer quits after --frames");
    view->add_option("--script", o->script, "Replay the viewer actions of this JSON file, then quit (see above)");
    view->add_option("--maps", o->maps,
                     "Folder of environment maps (.exr, .hdr) the panel offers to fit and light with; default: --env's "
                     "folder, else ../shared/data when present");
    coif::cli::examples(view, "  coif view\n  coif view --style hair.coif\n"
                              "  coif view --env ../shared/data/blender_studiolight_city.exr --params red.json\n"
                              "  xvfb-run -a coif view --frames 3 --screenshot shot.png\n"
                              "  xvfb-run -a coif view --script actions.json");
    view->callback([o] {
        coif::gl::ViewerOptions vo = viewer_options(*o);
        const coif::gl::ViewerResult r = coif::gl::run_viewer(std::move(vo));
        for (const auto& p : r.written) std::fprintf(stderr, "wrote %s\n", p.c_str());
        std::fprintf(stderr, "coif view: %d frames, the last %.1f ms\n", r.frames, r.last_frame_ms);
    });
}

struct BenchViewOptions {
    ViewOptions view;
    int frames = 5;
    bool no_panel = false, json = false;
};

void add_bench_view(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchViewOptions>();
    o->view.shell.samples = 1;
    CLI::App* cmd = bench->add_subcommand(
        "view",
        "Frame time of `coif view` against the renderer alone (`coif bench render`'s figure) in the same run\n"
        "Opens the viewer (a display is needed: xvfb-run -a without one), draws one warm-up frame and --frames\n"
        "frames with the panel and the environment behind the hair, each waited for, then times the same scene,\n"
        "camera and parameters drawn offscreen by the renderer alone, as `coif bench render` does; prints both\n"
        "medians and their ratio (the viewer's own cost: the environment, the display pass, the panel).");
    o->view.scene.add_to(cmd);
    o->view.shell.add_to(cmd);
    cmd->add_option("--frames", o->frames, "Frames measured of each (after one warm-up frame)")->check(CLI::Range(1, 1000))->capture_default_str();
    cmd->add_flag("--no-panel", o->no_panel, "Without the panel");
    cmd->add_flag("--no-environment", o->view.no_environment, "The plain --background behind the hair");
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  xvfb-run -a coif bench view\n  xvfb-run -a coif bench view --width 1280 --height 720 --json");
    cmd->callback([o] {
        coif::gl::ViewerOptions vo = viewer_options(o->view);
        coif::gl::ViewerAction panel, frames;
        panel.kind = coif::gl::ViewerAction::Kind::panel;
        panel.on = !o->no_panel;
        frames.kind = coif::gl::ViewerAction::Kind::frames;
        frames.x = o->frames;
        vo.script = {panel, frames};  // the panel action draws the warm-up frame
        vo.offscreen_frames = o->frames;
        const coif::gl::ViewerResult r = coif::gl::run_viewer(std::move(vo));
        // The median as `coif bench render` takes it (models/core/statistics.h), after the warm-up frame.
        const double viewer_ms = coif::median(std::vector<double>(r.frame_ms.begin() + 1, r.frame_ms.end()));
        const coif::gl::ShellFrameTimes& off = *r.offscreen;
        const nlohmann::ordered_json j = {{"width", o->view.scene.width},     {"height", o->view.scene.height},
                                          {"frames", o->frames},              {"panel", !o->no_panel},
                                          {"environment", !o->view.no_environment},
                                          {"viewer_frame_ms", viewer_ms},     {"renderer_frame_ms", off.wall_ms},
                                          {"renderer_lighting_ms", off.lighting_ms}, {"renderer_shells_ms", off.shells_ms},
                                          {"ratio", viewer_ms / off.wall_ms}};
        if (o->json) {
            coif::cli::print_json(j);
            return;
        }
        std::printf("%dx%d, median of %d frames each, panel %s, environment %s\n", o->view.scene.width,
                    o->view.scene.height, o->frames, o->no_panel ? "off" : "on", o->view.no_environment ? "off" : "on");
        std::printf("viewer frame       %8.1f ms  (%.2f fps)\n", viewer_ms, 1000.0 / viewer_ms);
        std::printf("renderer alone     %8.1f ms  (lighting %.1f, shells %.1f): coif bench render's figure\n", off.wall_ms,
                    off.lighting_ms, off.shells_ms);
        std::printf("ratio              %8.3f\n", viewer_ms / off.wall_ms);
    });
}

COIF_REGISTER_COMMAND(70, add_view);
COIF_REGISTER_COMMAND(95, add_bench_view);

}  // namespace
