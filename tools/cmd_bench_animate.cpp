// coif bench animate — what a moving frame costs against a still one: the scene's skinned style on its --body, posed
// through an animation spec (coif render --animate), each frame broken down into the motion (skinning, deformation, the
// shadow grid voxelized again) and the renderer's passes (the shadow march, the lighting, the shells), beside the same
// scene's still frame (nothing moved: the shadows and the lighting reused) in the same run.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "models/core/statistics.h"
#include "tools/animation_run.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct BenchAnimateOptions {
    coif::cli::SceneOptions scene;
    coif::cli::ShellOptions shell;
    std::string spec;
    bool json = false;
};

void add_bench_animate(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchAnimateOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "animate",
        "Per-frame cost of hair that moves: every frame of --animate SPEC (as coif render --animate, nothing written),\n"
        "broken down into skinning (the body's vertices and the clusters' transforms; with the spec's \"dynamics\", the\n"
        "simulation too), deformation (the clusters' instances and lighting samples placed and uploaded), shadow grid\n"
        "(the moved strands and the body voxelized and uploaded), and the renderer's passes that follow: the shadow\n"
        "march, the lighting, the shells. Beside them, the same scene's still frame (drawn twice at rest: the second\n"
        "reuses the shadows and the lighting). Medians over the frames (--json: also every frame's), wall-clock, each\n"
        "pass waited for.");
    o->scene.add_to(cmd);
    o->shell.add_to(cmd);
    cmd->add_option("--animate", o->spec, "Animation spec (models/animation.h; coif render --animate)")->required()->check(CLI::ExistingFile);
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif style import ../shared/data/Ratboy_mohawk.tfx --skinning ../shared/data/Ratboy_mohawk.tfxbone -o mohawk.json\n"
                             "  coif bench animate --style mohawk.json --body ../shared/data/Ratboy_body.tfxmesh \\\n"
                             "      --animate docs/examples/ratboy_head_turn.json --samples 1");
    cmd->callback([o] {
        const coif::cli::AnimationResult r = coif::cli::run_animation(o->scene, o->shell, coif::read_animation_spec(o->spec), {});
        std::vector<double> col[7];
        for (const coif::cli::AnimationFrame& f : r.frames) {
            const double v[7] = {f.skinning_ms, f.deformation_ms, f.shadow_grid_ms, f.shadows_ms, f.lighting_ms, f.shells_ms, f.total_ms};
            for (int k = 0; k < 7; ++k) col[k].push_back(v[k]);
        }
        double m[7];
        for (int k = 0; k < 7; ++k) m[k] = coif::median(col[k]);
        const double motion = m[0] + m[1] + m[2];
        const double still = r.still.total_ms;
        if (o->json) {
            nlohmann::json each = nlohmann::json::array();  // every frame's own breakdown
            for (const coif::cli::AnimationFrame& f : r.frames)
                each.push_back({{"skinning", f.skinning_ms}, {"deformation", f.deformation_ms}, {"shadow_grid", f.shadow_grid_ms},
                                {"shadow_pass", f.shadows_ms}, {"lighting", f.lighting_ms}, {"shells", f.shells_ms}, {"frame", f.total_ms}});
            coif::cli::print_json({{"frames", r.frames.size()},
                                   {"per_frame_milliseconds", each},
                                   {"width", r.width},
                                   {"height", r.height},
                                   {"renderer", r.renderer},
                                   {"median_milliseconds",
                                    {{"skinning", m[0]}, {"deformation", m[1]}, {"shadow_grid", m[2]}, {"shadow_pass", m[3]},
                                     {"lighting", m[4]}, {"shells", m[5]}, {"frame", m[6]}}},
                                   {"still_frame_milliseconds", still},
                                   {"motion_over_still", motion / still},
                                   {"motion_and_passes_over_still", (motion + m[3] + m[4]) / still},
                                   {"frame_over_still", m[6] / still}});
            return;
        }
        std::printf("coif bench animate: %zu frames at %dx%d on %s (medians, ms)\n", r.frames.size(), r.width, r.height, r.renderer.c_str());
        std::printf("  skinning/sim.   %8.1f\n  deformation     %8.1f\n  shadow grid     %8.1f   (motion: %.1f, %.1f %% of the still frame)\n",
                    m[0], m[1], m[2], motion, 100.0 * motion / still);
        std::printf("  shadow pass     %8.1f\n  lighting        %8.1f\n  shells          %8.1f\n", m[3], m[4], m[5]);
        std::printf("  frame           %8.1f   (%.2fx the still frame; motion with the shadow and lighting passes it reruns: %.1f %%)\n",
                    m[6], m[6] / still, 100.0 * (motion + m[3] + m[4]) / still);
        std::printf("  still frame     %8.1f   (the same scene at rest, nothing moved)\n", still);
    });
}

COIF_REGISTER_COMMAND(96, add_bench_animate);

}  // namespace
