// coif bench gl — the floor of this GPU: fill rate of a trivial fragment shader with alpha blending
// into an RGBA16F target, the configuration every renderer benchmark is compared against.
#include <cstdio>

#include "models/core/error.h"
#include "online/benchmarks.h"
#include "online/gl_context.h"
#include "tools/cli.h"

namespace {

struct GlBenchOptions {
    coif::gl::FillRateOptions fill;
    bool json = false;
};

void add_bench(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<GlBenchOptions>();
    CLI::App* gl = bench->add_subcommand(
        "gl",
        "The fill-rate floor of this GPU: blended full-screen layers of a constant-colour shader\n"
        "Full-screen layers of a constant-colour fragment shader, alpha blended into an RGBA16F target, headless. Reports fragments per second (GPU timer queries and wall\n"
        "clock). Renderer benchmarks express their cost as a ratio to this floor.");
    gl->add_option("--width", o->fill.width, "Target width in pixels")->check(CLI::Range(1, 16384));
    gl->add_option("--height", o->fill.height, "Target height in pixels")->check(CLI::Range(1, 16384));
    gl->add_option("--layers", o->fill.layers, "Full-screen layers per frame (overdraw)")->check(CLI::Range(1, 1000));
    gl->add_option("--frames", o->fill.frames, "Frames to time (after one warm-up frame)")->check(CLI::Range(1, 100000));
    coif::cli::add_json_flag(gl, o->json);
    coif::cli::examples(gl, "  coif bench gl\n  coif bench gl --width 1920 --height 1080 --json");
    gl->callback([o] {
        auto context = coif::gl::Context::headless();
        const coif::gl::FillRate r = coif::gl::measure_fill_rate(o->fill);
        const nlohmann::json result = {{"renderer", context->renderer()},
                                       {"width", o->fill.width},
                                       {"height", o->fill.height},
                                       {"layers", o->fill.layers},
                                       {"frames", o->fill.frames},
                                       {"gpu_ms_per_frame", r.gpu_ms_per_frame},
                                       {"wall_ms_per_frame", r.wall_ms_per_frame},
                                       {"mfragments_per_s_gpu", r.mfragments_per_s_gpu},
                                       {"mfragments_per_s_wall", r.mfragments_per_s_wall}};
        if (o->json) {
            coif::cli::print_json(result);
        } else {
            std::printf("renderer         %s\n", context->renderer().c_str());
            std::printf("target           %dx%d RGBA16F, %d blended full-screen layers, %d frames\n", o->fill.width,
                        o->fill.height, o->fill.layers, o->fill.frames);
            std::printf("frame time       %.3f ms (GPU timer), %.3f ms (wall)\n", result["gpu_ms_per_frame"].get<double>(),
                        result["wall_ms_per_frame"].get<double>());
            std::printf("fill rate        %.1f M fragments/s (GPU timer), %.1f M/s (wall)\n",
                        result["mfragments_per_s_gpu"].get<double>(), result["mfragments_per_s_wall"].get<double>());
        }
    });
}

COIF_REGISTER_COMMAND(90, add_bench);

}  // namespace
