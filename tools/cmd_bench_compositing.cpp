// coif bench compositing — decision 4's figures: every compositing mode of the shell renderer against the
// exact CPU compositing of the same fragments (online/fragment_lists.h), with its GPU cost.
#include <memory>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "models/core/error.h"
#include "models/core/image_metrics.h"
#include "online/fragment_lists.h"
#include "models/core/statistics.h"
#include "online/gl_context.h"
#include "online/scene/hair_scene.h"
#include "online/shell_renderer.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct BenchCompositingOptions {
    coif::cli::SceneOptions scene;
    std::string db, env, params;
    int frames = 3, msaa = 4, lighting_rows = 0;
    bool json = false;
};

struct Row {
    std::string name;
    coif::gl::Compositing mode;
    int samples;
    int slots = 0;  // the k-buffer's
};

void add_bench_compositing(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchCompositingOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "compositing",
        "Error and cost of the shell renderer's compositing modes (004 eq. 14, DESIGN.md decision 4)\n"
        "Captures every shell fragment of the view in per-pixel lists (single sample), composites them exactly on the\n"
        "CPU (per pixel sorted by eye distance, \"over\" back to front, double precision), and compares each mode's\n"
        "image with it: sorted (clusters back to front), unsorted, exact (the lists sorted on the GPU), weighted\n"
        "(weighted blended, bounded memory) and the k-buffer with k = 2, 4, 8, 16 (the nearest k fragments exact, the\n"
        "rest weighted blended; bounded memory), at 1 sample, then sorted at --msaa samples (MSAA also changes edge coverage,\n"
        "which the 1-sample reference does not have).\n"
        "PSNR on linear RGB, peak = 99th percentile of the reference's largest channel on the hair pixels (those with\n"
        "a fragment); wall time of the shells pass with its compositing and of the exact or weighted resolve alone (each\n"
        "waited for on the GPU, as `coif bench render`: llvmpipe's timer queries misattribute; the modes take turns, median of\n"
        "--frames after a warm-up round).");
    o->scene.add_to(cmd);
    cmd->add_option("--db", o->db, "HRIR database; default: the cached default database (built on first use)");
    cmd->add_option("--env", o->env, "SRBF lights JSON or an environment map; default: the embedded 40 lights");
    cmd->add_option("--params", o->params, "Scattering parameters JSON (see coif render)");
    cmd->add_option("--frames", o->frames, "Frames timed per mode (after one warm-up frame)")->check(CLI::Range(1, 100))->capture_default_str();
    cmd->add_option("--msaa", o->msaa, "MSAA samples of the extra sorted row (1: no extra row)")->check(CLI::Range(1, 16))->capture_default_str();
    cmd->add_option("--lighting-rows", o->lighting_rows, "Lighting samples per HSV (see coif render)")->check(CLI::Range(0, 64))->capture_default_str();
    cmd->add_flag("--json", o->json, "Print JSON instead of a table");
    coif::cli::examples(cmd, "  coif bench compositing\n  coif bench compositing --width 360 --height 240 --json");
    cmd->callback([o] {
        coif::gl::ShellSettings base;
        if (!o->params.empty()) base = coif::gl::read_shell_settings(o->params, base);
        coif::gl::HairScene scene(
            coif::cli::hair_scene_desc(o->scene, coif::cli::read_scene_inputs(o->scene, o->env), o->db, o->lighting_rows));
        coif::gl::ShellRenderer& renderer = *scene.renderer;
        const coif::Camera& cam = scene.camera;

        const coif::gl::FragmentCapture capture = renderer.capture_fragments(cam, base);
        if (capture.dropped > 0)
            throw coif::Error::parameter("fragment lists", std::to_string(capture.dropped) +
                                                               " fragments did not fit this GPU's largest storage block; "
                                                               "use a smaller --width/--height");
        const coif::Image exact = coif::gl::composite_exact(capture, base.background);
        const coif::gl::FragmentDepthStats depth = coif::gl::fragment_depth_stats(capture);

        std::vector<Row> rows = {{"sorted", coif::gl::Compositing::sorted, 1},
                                 {"unsorted", coif::gl::Compositing::unsorted, 1},
                                 {"exact (GPU lists)", coif::gl::Compositing::exact, 1},
                                 {"weighted", coif::gl::Compositing::weighted, 1}};
        for (const int k : {2, 4, 8, 16}) rows.push_back({"kbuffer k=" + std::to_string(k), coif::gl::Compositing::kbuffer, 1, k});
        if (o->msaa > 1) rows.push_back({"sorted", coif::gl::Compositing::sorted, o->msaa});
        nlohmann::ordered_json out = {
            {"renderer", scene.context->renderer()}, {"width", cam.width}, {"height", cam.height},
            {"fragments", depth.fragments}, {"hair_pixels", depth.covered_pixels},
            {"fragments_per_pixel_mean_all", depth.mean_all}, {"fragments_per_pixel_mean_hair", depth.mean_covered},
            {"fragments_per_pixel_max", depth.max}, {"resolve_limit", coif::gl::kResolveFragments},
            {"pixels_over_resolve_limit", depth.pixels_over_resolve_limit}, {"modes", nlohmann::json::array()}};
        std::vector<coif::gl::ShellSettings> settings;
        std::vector<std::unique_ptr<coif::gl::RenderTarget>> targets;
        for (const Row& row : rows) {
            coif::gl::ShellSettings s = base;
            s.compositing = row.mode;
            s.samples = row.samples;
            if (row.slots > 0) s.kbuffer_slots = row.slots;
            s.timed = true;  // wall-clock per pass, each waited for
            settings.push_back(s);
            targets.push_back(std::make_unique<coif::gl::RenderTarget>(coif::gl::camera_target(cam, s.samples)));
        }
        // Timing: the modes take turns frame by frame, each round starting one mode later (the machine's load
        // changes slowly, and a frame's time depends a little on the frame before; turns spread both over every
        // mode alike); the first round warms up and is not counted.
        std::vector<std::vector<double>> shells_ms(rows.size()), resolve_ms(rows.size());
        for (int f = 0; f <= o->frames; ++f)
            for (std::size_t turn = 0; turn < rows.size(); ++turn) {
                const std::size_t i = (turn + static_cast<std::size_t>(f)) % rows.size();
                targets[i]->bind();
                renderer.draw(cam, settings[i]);
                if (f == 0) continue;
                shells_ms[i].push_back(renderer.timings().shells_wall_ms);
                resolve_ms[i].push_back(renderer.timings().resolve_wall_ms);
            }
        std::vector<coif::Image> images;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            targets[i]->bind();
            renderer.draw(cam, settings[i]);
            images.push_back(targets[i]->read_back());
            const coif::gl::CompositingError e = coif::gl::compositing_error(exact, images.back(), capture);
            out["peak"] = e.peak;
            out["modes"].push_back({{"mode", rows[i].name}, {"samples", rows[i].samples}, {"psnr_hair_db", e.psnr_hair_db},
                                    {"psnr_all_db", e.psnr_all_db}, {"rms_hair", e.rms_hair}, {"max_abs", e.max_abs},
                                    {"shells_ms", coif::median(shells_ms[i])},
                                    {"resolve_ms", coif::median(resolve_ms[i])}});
        }
        if (o->msaa > 1) {  // MSAA's own effect: sorted at --msaa samples against sorted at 1
            const coif::gl::CompositingError e = coif::gl::compositing_error(images[0], images.back(), capture);
            out["msaa_vs_1_sample_sorted"] = {{"psnr_hair_db", e.psnr_hair_db}, {"psnr_all_db", e.psnr_all_db},
                                              {"rms_hair", e.rms_hair}};
        }
        if (o->json) {
            std::printf("%s\n", out.dump(2).c_str());
            return;
        }
        std::printf("renderer   %s, %dx%d, %zu lights\n", scene.context->renderer().c_str(), cam.width, cam.height,
                    scene.lights.size());
        std::printf("fragments  %llu on %zu hair pixels: %.1f per hair pixel (%.1f over the image), max %zu; %zu pixels over "
                    "the GPU resolve's %d\n",
                    static_cast<unsigned long long>(depth.fragments), depth.covered_pixels, depth.mean_covered, depth.mean_all,
                    depth.max, depth.pixels_over_resolve_limit, coif::gl::kResolveFragments);
        std::printf("reference  exact CPU compositing of the same fragments; PSNR peak %.4f (linear)\n", out["peak"].get<double>());
        std::printf("%-20s %7s %14s %13s %10s %9s %14s %11s\n", "mode", "samples", "PSNR hair dB", "PSNR all dB", "RMS hair",
                    "max |d|", "shells ms", "of which resolve");
        for (const auto& m : out["modes"])
            std::printf("%-20s %7d %14s %13s %10.5f %9.4f %14.1f %11.1f\n", m["mode"].get<std::string>().c_str(),
                        m["samples"].get<int>(), coif::format_metric(m["psnr_hair_db"].get<double>(), 2).c_str(),
                        coif::format_metric(m["psnr_all_db"].get<double>(), 2).c_str(), m["rms_hair"].get<double>(),
                        m["max_abs"].get<double>(), m["shells_ms"].get<double>(), m["resolve_ms"].get<double>());
        if (o->msaa > 1)
            std::printf("MSAA alone: sorted at %d samples against sorted at 1: PSNR hair %s dB, all %s dB, RMS hair %.5f\n", o->msaa,
                        coif::format_metric(out["msaa_vs_1_sample_sorted"]["psnr_hair_db"].get<double>(), 2).c_str(),
                        coif::format_metric(out["msaa_vs_1_sample_sorted"]["psnr_all_db"].get<double>(), 2).c_str(),
                        out["msaa_vs_1_sample_sorted"]["rms_hair"].get<double>());
    });
}

COIF_REGISTER_COMMAND(93, add_bench_compositing);

}  // namespace
