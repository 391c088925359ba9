// coif reference — the brute-force CPU reference image of a scene (offline/reference.h): Embree fibres,
// the exact Marschner model, environment lighting, ray-traced shadows, path-traced multiple scattering.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "models/core/error.h"
#include "models/core/image.h"
#include "offline/reference.h"
#include "tools/cli.h"
#include "tools/reference_options.h"
#include "tools/scene_options.h"

namespace {

struct ReferenceCommandOptions {
    coif::cli::SceneOptions scene;
    coif::cli::ReferenceCliOptions reference;
    std::string output = "reference.exr";
    float exposure = 0.0f;
    bool json = false;
};

void add_reference(CLI::App& root) {
    auto o = std::make_shared<ReferenceCommandOptions>();
    CLI::App* cmd = root.add_subcommand(
        "reference",
        "Render the brute-force reference image of a hair scene on the CPU, to measure `coif render` against\n"
        "(`coif compare`). Same scene options and camera as `coif render` (pixels line up exactly). Strands are\n"
        "thin round fibres (Embree round linear curves through the file's points), shaded with the exact Marschner\n"
        "model of the lighting module (R, TT, TRT, eccentricity, exact Fresnel; σa per unit fibre radius), lit by an\n"
        "environment map (importance-sampled from the map), its fitted SRBF lights (--lights, to separate lighting-fit\n"
        "error from rendering error) or a constant environment, with ray-traced shadows and multiple scattering by\n"
        "path tracing up to --max-depth fibre bounces. The environment mapping is shaders/envmap.glsl's (row 0 = +y,\n"
        "centre column = +x). Deterministic for a seed; uses every core; prints samples per pixel and time.\n"
        "Output: .exr (linear; RGB over the background, or RGBA with --alpha) or .png (tone-mapped sRGB).");
    o->scene.add_to(cmd);
    o->reference.add_to(cmd);
    cmd->add_option("-o,--output", o->output, "Image to write (.exr, .png or .hdr)");
    cmd->add_option("--exposure", o->exposure, "Exposure in stops for the PNG tone map");
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif reference -o ref.exr --spp 64\n"
                             "  coif reference --strands ../shared/data/harolongo.data --env ../shared/data/blender_studiolight_city.exr -o ref.exr\n"
                             "  coif reference --lights city_lights.json --max-depth 1 --alpha -o single.exr\n"
                             "  coif render -o r.exr && coif reference -o ref.exr && coif compare ref.exr r.exr");
    cmd->callback([o] {
        const auto t0 = std::chrono::steady_clock::now();
        // Everything is validated before any work, so bad input never leaves an output file.
        const coif::shading::HairParams params = o->reference.hair_params();
        const coif::ReferenceSettings settings = o->reference.reference_settings();
        if (!std::isfinite(o->exposure)) throw coif::Error::parameter("option --exposure", "must be a finite number of stops");
        const coif::ReferenceEnvironment env = o->reference.environment();
        coif::cli::lock_output(o->output);
        std::string label;
        const coif::Strands strands = o->scene.load_strands(&label);
        const coif::Camera camera = o->scene.camera_for(strands);
        const coif::MarschnerFiber bsdf(params);
        coif::ReferenceSettings s = settings;
        s.progress = !o->json;
        const coif::ReferenceRenderer renderer(strands, env, bsdf, s);
        coif::ReferenceStats stats;
        const coif::Image image = renderer.render(camera, &stats);
        coif::WriteOptions wo;
        wo.exposure = o->exposure;
        char desc[512];
        std::snprintf(desc, sizeof desc,
                      "coif reference: Embree fibres (radius %g), exact Marschner, path traced (max depth %d%s), %d spp, seed %llu; %s; %s",
                      double(stats.fiber_radius), s.max_depth, s.shadows ? "" : ", no shadows", stats.samples_per_pixel, static_cast<unsigned long long>(s.seed),
                      env.label().c_str(), label.c_str());
        wo.description = desc;
        coif::write_image(o->output, image, wo);
        const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (o->json) {
            coif::cli::print_json({{"output", o->output},
                                   {"strands", label},
                                   {"segments", stats.segments},
                                   {"fiber_radius", stats.fiber_radius},
                                   {"width", camera.width},
                                   {"height", camera.height},
                                   {"samples_per_pixel", stats.samples_per_pixel},
                                   {"max_depth", s.max_depth},
                                   {"seed", s.seed},
                                   {"environment", env.label()},
                                   {"coverage", stats.coverage},
                                   {"rays", stats.rays},
                                   {"build_seconds", stats.build_seconds},
                                   {"render_seconds", stats.render_seconds},
                                   {"total_seconds", total},
                                   {"mrays_per_second", 1e-6 * double(stats.rays) / stats.render_seconds}});
            return;
        }
        std::fprintf(stderr, "reference: %s (%zu segments, fibre radius %g), %dx%d, %d spp, max depth %d, seed %llu, %s\n",
                     label.c_str(), stats.segments, double(stats.fiber_radius), camera.width, camera.height,
                     stats.samples_per_pixel, s.max_depth, static_cast<unsigned long long>(s.seed), env.label().c_str());
        std::fprintf(stderr, "time: %.2f s render (%.1f M rays/s), %.2f s total; fibre coverage %.1f %% of the image -> %s\n",
                     stats.render_seconds, 1e-6 * double(stats.rays) / stats.render_seconds, total, 100.0 * stats.coverage,
                     o->output.c_str());
    });
}

COIF_REGISTER_COMMAND(65, add_reference);

}  // namespace
