// coif render — one image of the scene. Until the SATF shell renderer lands, this draws the strand
// preview (online/strand_preview.h) and says so.
#include <cstdio>

#include "models/core/error.h"
#include "models/core/image.h"
#include "online/gl_context.h"
#include "online/strand_preview.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct RenderOptions {
    coif::cli::SceneOptions scene;
    std::string output = "coif.png";
    float exposure = 0.0f;
};

void add_render(CLI::App& root) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* render = root.add_subcommand(
        "render",
        "Render one image of a hair scene, headless (the embedded default scene when given no arguments)\n"
        "Rendering goes through EGL, so no window or display is needed. Current state: strands are drawn as GL lines with a simple Kajiya-Kay preview\n"
        "shading (the SATF shell renderer with SRBF Marschner lighting is not built yet); the image metadata says so.\n"
        "Output: .png (tone-mapped sRGB: exposure, clip, sRGB curve) or .exr (linear half float); written atomically.");
    o->scene.add_to(render);
    render->add_option("-o,--output", o->output, "Image to write (.png, .exr or .hdr)");
    render->add_option("--exposure", o->exposure, "Exposure in stops for the PNG tone map");
    coif::cli::examples(render, "  coif render -o hair.png\n"
                                "  coif render --strands ../shared/data/harolongo.data --azimuth 90 -o side.exr\n"
                                "  coif render --width 1920 --height 1080 -o hd.png");
    render->callback([o] {
        std::string label;
        const coif::Strands strands = o->scene.load_strands(&label);
        const coif::Camera camera = o->scene.camera_for(strands);
        auto context = coif::gl::Context::headless();
        const coif::Image image = coif::gl::render_strand_preview(strands, camera, {});
        coif::WriteOptions wo;
        wo.exposure = o->exposure;
        wo.description = std::string(coif::gl::kStrandPreviewLabel) + "; " + label;
        coif::write_image(o->output, image, wo);
        std::fprintf(stderr, "%s\nrendered %s (%zu strands) at %dx%d on %s -> %s\n", coif::gl::kStrandPreviewLabel,
                     label.c_str(), strands.strand_count(), camera.width, camera.height, context->renderer().c_str(),
                     o->output.c_str());
    });
}

COIF_REGISTER_COMMAND(60, add_render);

}  // namespace
