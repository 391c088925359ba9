// coif bench render — frame time of the SATF shell renderer with the SRBF lights, and its ratio to a
// trivial-shader pass over the same shells in the same run (the floor).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "models/core/error.h"
#include "models/style_fit.h"
#include "online/benchmarks.h"
#include "online/gl_context.h"
#include "online/scene/hair_scene.h"
#include "online/shell_renderer.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct BenchRenderOptions {
    coif::cli::SceneOptions scene;
    std::string db, env, params, data = "../shared/data";
    int frames = 10, samples = 1, lighting_rows = 0, clusters = 64;
    bool json = false, models = true;
};

struct BenchScene {
    std::string name;
    coif::HairStyle style;
    double fit_seconds = 0;  // style import (models only)
};

void add_bench_render(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchRenderOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "render",
        "Frame time of `coif render`'s SATF shell renderer (SRBF Marschner lighting, 40 lights by default)\n"
        "Renders the scene --frames times after one warm-up frame into an offscreen target and reports the median wall\n"
        "time per frame and per pass (each pass waited for on the GPU: GPU timer queries misattribute on llvmpipe), then the same\n"
        "shells in the same order with a trivial constant-colour shader (the floor) and the ratio of the two, for the\n"
        "--style scene and for every model in --data (fitted with --clusters clusters, as `coif style import` does).");
    o->scene.add_to(cmd);
    cmd->add_option("--db", o->db, "HRIR database; default: the cached default database (built on first use)");
    cmd->add_option("--env", o->env, "SRBF lights JSON or an environment map; default: the embedded 40 lights");
    cmd->add_option("--params", o->params, "Scattering parameters JSON (see coif render)");
    cmd->add_option("--frames", o->frames, "Frames measured (after one warm-up frame)")->check(CLI::Range(1, 1000))->capture_default_str();
    cmd->add_option("--lighting-rows", o->lighting_rows,
                   "Lighting samples per HSV along each cluster (0 = one per mesh row, the style's mesh[0])")
        ->check(CLI::Range(0, 64))->capture_default_str();
    cmd->add_option("--samples", o->samples, "MSAA samples per pixel (sorted/unsorted compositing; the exact compositing draws 1)")->check(CLI::Range(1, 16))->capture_default_str();
    cmd->add_option("--data", o->data, "Folder of .hair/.data models: each is fitted (coif style import) and benchmarked too")
        ->capture_default_str();
    cmd->add_option("--clusters", o->clusters, "Clusters fitted to each model")->check(CLI::Range(1, 100000))->capture_default_str();
    cmd->add_flag("!--no-models", o->models, "Only the --style scene, no models from --data");
    cmd->add_flag("--json", o->json, "Print JSON instead of a table");
    coif::cli::examples(cmd, "  coif bench render\n"
                             "  coif bench render --no-models --frames 3\n"
                             "  coif bench render --width 1920 --height 1080 --frames 5 --json");
    cmd->callback([o] {
        coif::gl::ShellSettings settings;
        settings.samples = o->samples;
        if (!o->params.empty()) settings = coif::gl::read_shell_settings(o->params, settings);
        settings.timed = true;  // wall-clock per pass, each waited for (llvmpipe's timer queries misattribute)
        // Every frame lights again, as when the view moves; the still frame, below, reuses the lighting.
        settings.reuse_lighting = false;
        coif::gl::ShellSettings still = settings;
        still.reuse_lighting = true;
        coif::cli::SceneInputs inputs = coif::cli::read_scene_inputs(o->scene, o->env);
        std::vector<BenchScene> models;
        if (o->models) {
            namespace fs = std::filesystem;
            std::vector<fs::path> files;
            if (fs::is_directory(o->data))
                for (const auto& e : fs::directory_iterator(o->data))
                    if (e.path().extension() == ".hair" || e.path().extension() == ".data") files.push_back(e.path());
            if (files.empty())
                std::fprintf(stderr, "note: no .hair/.data models in %s (--data): only the default style\n", o->data.c_str());
            std::sort(files.begin(), files.end());
            for (const fs::path& f : files) {
                std::fprintf(stderr, "coif: fitting %d clusters to %s\n", o->clusters, f.filename().c_str());
                const auto t0 = std::chrono::steady_clock::now();
                coif::FitOptions fit;
                fit.clusters = o->clusters;
                fit.progress = false;
                BenchScene sc{f.filename().string(), coif::fit_style(coif::read_strands(f), fit), 0.0};
                sc.fit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                models.push_back(std::move(sc));
            }
        }
        // The --style scene; each model is framed around its own sampled strands by the same orbit options.
        coif::gl::HairScene scene(coif::cli::hair_scene_desc(o->scene, std::move(inputs), o->db, o->lighting_rows));
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        const auto bench_scene = [&](const std::string& name, double fit_seconds, coif::gl::ShellRenderer& renderer,
                                     const coif::Camera& cam) {
            const coif::gl::RenderTarget target = coif::gl::camera_target(cam, settings.samples);
            target.bind();
            renderer.draw(cam, settings);  // the shadow pass runs on the first frame only (lights unchanged after)
            scene.context->finish();
            const double shadows_ms = renderer.timings().shadows_ms;
            const coif::gl::ShellFrameTimes full =
                coif::gl::time_shell_frames(renderer, cam, settings, false, o->frames);
            const coif::gl::ShellFrameTimes floor =
                coif::gl::time_shell_frames(renderer, cam, settings, true, o->frames);
            const coif::gl::ShellFrameTimes unmoved = coif::gl::time_shell_frames(renderer, cam, still, false, o->frames);
            const auto& st = renderer.stats();
            rows.push_back({{"scene", name}, {"fit_s", fit_seconds}, {"clusters", st.clusters}, {"sectors", st.sectors},
                            {"triangles", st.triangles}, {"lighting_samples", st.lighting_samples},
                            {"shadow_grid", {st.grid_x, st.grid_y, st.grid_z}}, {"prepare_s", st.prepare_seconds},
                            {"frame_ms", full.wall_ms}, {"fps", 1000.0 / full.wall_ms}, {"still_frame_ms", unmoved.wall_ms},
                            {"shadow_pass_ms", shadows_ms}, {"lighting_pass_ms", full.lighting_ms},
                            {"shells_ms", full.shells_ms}, {"resolve_ms", full.resolve_ms}, {"floor_ms", floor.wall_ms},
                            {"floor_shells_ms", floor.shells_ms}, {"ratio_to_floor", full.wall_ms / floor.wall_ms}});
        };
        bench_scene(o->scene.style, 0.0, *scene.renderer, scene.camera);
        for (const BenchScene& sc : models) {
            const coif::gl::ShellView view = scene.view_of(sc.style, o->scene.shell_framing(false), o->lighting_rows);
            bench_scene(sc.name, sc.fit_seconds, *view.renderer, view.camera);
        }
        nlohmann::ordered_json j = {
            {"renderer", scene.context->renderer()}, {"width", o->scene.width}, {"height", o->scene.height},
            {"samples", settings.samples}, {"lights", scene.lights.size()}, {"lights_source", scene.lights_label},
            {"multiple_scattering", settings.hair.multiple}, {"shadows_between_clusters", settings.shadows},
            {"neighbours", settings.neighbours}, {"records", scene.renderer->stats().database_records}, {"frames", o->frames}, {"scenes", rows}};
        if (o->json) {
            std::printf("%s\n", j.dump(2).c_str());
            return;
        }
        std::printf("renderer  %s; %dx%d, %d sample(s), %zu lights (%s), %s, shadows between clusters %s; median of %d frames\n",
                    scene.context->renderer().c_str(), o->scene.width, o->scene.height, settings.samples,
                    scene.lights.size(), scene.lights_label.c_str(), settings.hair.multiple ? "single + multiple scattering" : "single scattering",
                    settings.shadows ? "on" : "off", o->frames);
        std::printf("Wall-clock per pass, each waited for on the GPU. Per hairstyle, once: SATF parameters and look-up\n"
                    "(prepare); per light change: the shadow pass; per frame: the lighting pass, and the shells (re/α\n"
                    "look-up, lighting combine, blending or appending to the per-pixel lists), of which the exact\n"
                    "compositing's per-pixel sort and blend is the resolve; the floor is the same shells rasterised and\n"
                    "blended with a trivial shader. Every frame lights again, as when the view moves; a still frame (nothing\n"
                    "moved: the lighting pass's sums reused) is the last figure.\n\n");
        std::printf("%-22s %8s %9s %8s %7s %9s %9s %9s %9s %8s %7s\n", "scene", "clusters", "triangles", "prepare", "frame",
                    "fps", "shadows", "lighting", "shells", "resolve", "floor");
        std::printf("%-22s %8s %9s %8s %7s %9s %9s %9s %9s %8s %7s\n", "", "", "", "s", "ms", "", "ms(once)", "ms", "ms",
                    "ms", "ms");
        for (const auto& r : rows)
            std::printf("%-22s %8zu %9zu %8.2f %7.1f %9.2f %9.1f %9.1f %9.1f %8.1f %7.1f   ratio %.2f, still frame %.1f ms\n",
                        r["scene"].get<std::string>().c_str(), r["clusters"].get<std::size_t>(),
                        r["triangles"].get<std::size_t>(), r["prepare_s"].get<double>(), r["frame_ms"].get<double>(),
                        r["fps"].get<double>(), r["shadow_pass_ms"].get<double>(), r["lighting_pass_ms"].get<double>(),
                        r["shells_ms"].get<double>(), r["resolve_ms"].get<double>(), r["floor_ms"].get<double>(),
                        r["ratio_to_floor"].get<double>(), r["still_frame_ms"].get<double>());
    });
}

COIF_REGISTER_COMMAND(92, add_bench_render);

}  // namespace
