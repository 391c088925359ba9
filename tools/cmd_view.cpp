// coif view — the interactive viewer (online/window/viewer.h). Current state: the strand preview with an orbit
// camera; appearance editing arrives with the renderer.
#include <cstdio>
#include <memory>
#include <tuple>

#include "models/core/error.h"
#include "models/core/image.h"
#include "online/window/viewer.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct ViewOptions {
    coif::cli::SceneOptions scene;
    int frames = 0;
    std::string screenshot;
};

void add_view(CLI::App& root) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* view = root.add_subcommand(
        "view",
        "Open the interactive viewer in a window\n"
        "It needs a display: use `xvfb-run -a coif view` without one.\n"
        "Drag with the left mouse button to orbit, scroll to zoom, Esc or Q to quit.\n"
        "Current state: strands drawn with the preview shading (see `coif render --help`).");
    o->scene.add_to(view);
    view->add_option("--frames", o->frames, "Quit after this many frames (0 = run until closed); for scripts and tests")
        ->check(CLI::NonNegativeNumber);
    view->add_option("--screenshot", o->screenshot, "Write the last frame to this image (.png/.exr) when the viewer quits");
    coif::cli::examples(view, "  coif view\n  coif view --strands ../shared/data/harolongo.data\n"
                              "  xvfb-run -a coif view --frames 3 --screenshot shot.png");
    view->callback([o] {
        coif::gl::ViewerOptions vo;
        vo.strands = o->scene.load_strands();
        std::tie(vo.frame_min, vo.frame_max) = o->scene.frame_box(vo.strands);
        vo.view = o->scene.orbit_view();
        vo.frames = o->frames;
        vo.keep_last_frame = !o->screenshot.empty();
        const coif::gl::ViewerResult result = coif::gl::run_viewer(vo);
        if (!o->screenshot.empty()) {
            if (!result.last_frame) throw coif::Error(o->screenshot, "", "no frame was drawn, so there is nothing to save");
            coif::WriteOptions wo;
            wo.description = coif::gl::kStrandPreviewLabel;
            coif::write_image(o->screenshot, *result.last_frame, wo);
            std::fprintf(stderr, "wrote %s\n", o->screenshot.c_str());
        }
    });
}

COIF_REGISTER_COMMAND(70, add_view);

}  // namespace
