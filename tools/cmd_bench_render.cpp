// coif bench render — frame time of the SATF shell renderer with the SRBF lights, and its ratio to a
// trivial-shader pass over the same shells in the same run (the floor).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "models/core/error.h"
#include "models/core/image_metrics.h"
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
    std::vector<std::string> qualities;
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
    cmd->add_option("--params", o->params,
                    "Parameters JSON (see coif render): its keys apply over each preset's choices, e.g. {\"key_lights\": 0} "
                    "measures every preset, full included, without key lights");
    cmd->add_option("--quality", o->qualities,
                    "Quality presets measured (default: all; see coif render --help); each beside full, the reference: its "
                    "error against full's image, its frame against the floor of full's shells")
        ->check(CLI::IsMember(coif::gl::quality_names()));
    cmd->add_option("--frames", o->frames, "Frames measured (after one warm-up frame)")->check(CLI::Range(1, 1000))->capture_default_str();
    cmd->add_option("--lighting-rows", o->lighting_rows,
                   "Lighting samples per HSV along each cluster (0 = one per mesh row, the style's mesh[0])")
        ->check(CLI::Range(0, 64))->capture_default_str();
    cmd->add_option("--samples", o->samples, "MSAA samples per pixel (sorted/unsorted compositing; the exact and weighted compositings draw 1)")->check(CLI::Range(1, 16))->capture_default_str();
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
        // Read once; its keys apply over each preset's choices below.
        const nlohmann::json params = o->params.empty() ? nlohmann::json::object() : coif::read_json_file(o->params);
        settings = coif::gl::shell_settings_from_json(params, o->params, settings);
        settings.timed = true;  // wall-clock per pass, each waited for (llvmpipe's timer queries misattribute)
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
        std::vector<coif::gl::Quality> qualities;
        for (const coif::gl::QualityPreset& p : coif::gl::kQualityPresets)
            if (o->qualities.empty() || std::find(o->qualities.begin(), o->qualities.end(), p.name) != o->qualities.end())
                qualities.push_back(p.quality);
        const auto bench_scene = [&](const std::string& name, double fit_seconds, coif::gl::ShellRenderer& renderer,
                                     const coif::Camera& cam) {
            const auto preset = [&](coif::gl::Quality q, bool reuse) {
                coif::gl::ShellSettings s = settings;
                coif::gl::apply_quality(s, q);
                s = coif::gl::shell_settings_from_json(params, o->params, s);  // its keys over the preset's
                s.reuse_lighting = reuse;
                return s;
            };
            // The reference image (full, over black for the radiance ratio) and the floor of full's shells.
            coif::gl::ShellSettings full = preset(coif::gl::Quality::full, false);
            full.background = glm::vec3(0.0f);
            const coif::Image reference = renderer.render(cam, full);
            const double shadows_ms = renderer.timings().shadows_ms;  // the first render of the lights runs the shadow pass
            const coif::gl::RenderTarget target = coif::gl::camera_target(cam, settings.samples);
            target.bind();
            renderer.draw(cam, full);  // the shadow pass ran in render(), on its first frame (lights unchanged after)
            scene.context->finish();
            const coif::gl::ShellFrameTimes floor = coif::gl::time_shell_frames(renderer, cam, full, true, o->frames);
            for (const coif::gl::Quality q : qualities) {
                const coif::gl::ShellSettings moving = preset(q, false);
                coif::gl::ShellSettings image_settings = moving;
                image_settings.background = glm::vec3(0.0f);
                const coif::CompareResult error =
                    coif::compare_images(reference, renderer.render(cam, image_settings), coif::CompareOptions{}, "full",
                                         coif::gl::quality_preset(q).name);
                target.bind();
                renderer.draw(cam, moving);  // warm-up: the variant's shaders compiled
                scene.context->finish();
                const coif::gl::ShellFrameTimes t = coif::gl::time_shell_frames(renderer, cam, moving, false, o->frames);
                const std::size_t triangles_drawn = renderer.timings().triangles_drawn;
                const auto at_level = renderer.timings().clusters_at_level;
                const double lights_lit = renderer.mean_lights_lit();  // per lighting sample (ShellSettings::light_cull)
                // The same preset lighting every light: what its light culling saves, in the same run.
                double all_lights_ms = t.lighting_ms;
                if (moving.light_cull > 0.0f) {
                    coif::gl::ShellSettings no_cull = moving;
                    no_cull.light_cull = 0.0f;
                    all_lights_ms = coif::gl::time_shell_frames(renderer, cam, no_cull, false, o->frames).lighting_ms;
                }
                // The same preset with every cluster's full meshes: what its level of detail saves, in the same run.
                double full_meshes_ms = t.wall_ms;
                if (moving.lod_pixels > 0.0f) {
                    coif::gl::ShellSettings no_lod = moving;
                    no_lod.lod_pixels = 0.0f;
                    full_meshes_ms = coif::gl::time_shell_frames(renderer, cam, no_lod, false, o->frames).wall_ms;
                }
                const coif::gl::ShellFrameTimes unmoved =
                    coif::gl::time_shell_frames(renderer, cam, preset(q, true), false, o->frames);
                const auto& st = renderer.stats();
                const coif::AppearanceMetrics& a = error.appearance;
                rows.push_back({{"scene", name}, {"quality", coif::gl::quality_preset(q).name}, {"fit_s", fit_seconds},
                                {"clusters", st.clusters}, {"sectors", st.sectors}, {"triangles", st.triangles},
                                {"lighting_samples", st.lighting_samples}, {"shadow_grid", {st.grid_x, st.grid_y, st.grid_z}},
                                {"prepare_s", st.prepare_seconds}, {"shadow_pass_ms", shadows_ms},
                                {"lighting_step", renderer.timings().lighting_step},
                                {"lod_pixels", moving.lod_pixels}, {"triangles_drawn", triangles_drawn},
                                {"clusters_at_level", at_level}, {"frame_ms_full_meshes", full_meshes_ms},
                                {"frame_ms", t.wall_ms}, {"fps", 1000.0 / t.wall_ms},
                                {"still_frame_ms", unmoved.wall_ms}, {"lighting_pass_ms", t.lighting_ms},
                                {"light_cull", moving.light_cull}, {"lights_lit_per_sample", lights_lit},
                                {"lighting_pass_ms_all_lights", all_lights_ms},
                                {"shells_ms", t.shells_ms}, {"resolve_ms", t.resolve_ms}, {"full_floor_ms", floor.wall_ms},
                                {"ratio_to_full_floor", t.wall_ms / floor.wall_ms},
                                {"error_vs_full",
                                 {{"blurred_psnr_db", a.blurred_psnr_db},
                                  {"detail_ratio", a.detail_ratio},
                                  {"radiance_ratio", {a.radiance_ratio[0], a.radiance_ratio[1], a.radiance_ratio[2]}},
                                  {"mask_iou", a.mask_iou},
                                  {"psnr_tone_mapped_db", error.tone_mapped.psnr_db}}}});
            }
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
                    "compositing's per-pixel sort and blend is the resolve. Every frame lights again, as when the view\n"
                    "moves; 'still' is a frame where nothing moved (the lighting pass's sums reused). x floor: the frame over\n"
                    "full's shells rasterised and blended with a trivial shader. Error against full's image (coif compare's\n"
                    "appearance metrics): blurred PSNR, detail ratio, radiance ratio (lowest and highest channel), mask IoU.\n"
                    "Level of detail: the triangles drawn per frame (thousands), and the frame with every cluster's full\n"
                    "meshes ('full mesh', the preset otherwise the same) beside it. Lights culled per lighting sample:\n"
                    "the lights lit per sample on average ('lit'), and the lighting pass lighting every light ('all lt').\n");
        std::string last;
        for (const auto& r : rows) {
            const std::string scene_name = r["scene"].get<std::string>();
            if (scene_name != last) {
                std::printf("\n%s: %zu clusters, %zu triangles, prepare %.2f s, shadow pass %.1f ms, floor of full %.1f ms\n",
                            scene_name.c_str(), r["clusters"].get<std::size_t>(), r["triangles"].get<std::size_t>(),
                            r["prepare_s"].get<double>(), r["shadow_pass_ms"].get<double>(), r["full_floor_ms"].get<double>());
                std::printf("  %-7s %8s %6s %9s %5s %7s %8s %8s %8s %8s %6s %9s %8s %7s %11s %6s\n", "quality", "frame", "fps",
                            "lighting", "lit", "all lt", "shells", "resolve", "x floor", "still", "tris", "full mesh", "bPSNR",
                            "detail", "radiance", "IoU");
                std::printf("  %-7s %8s %6s %9s %5s %7s %8s %8s %8s %8s %6s %9s %8s %7s %11s %6s\n", "", "ms", "", "ms", "", "ms",
                            "ms", "ms", "", "ms", "k", "ms", "dB", "", "", "");
                last = scene_name;
            }
            const auto& e = r["error_vs_full"];
            const auto rad = e["radiance_ratio"].get<std::vector<double>>();
            std::printf("  %-7s %8.1f %6.2f %9.1f %5.1f %7.1f %8.1f %8.1f %8.2f %8.1f %6.0f %9.1f %8s %7.3f %5.3f-%5.3f %6.3f\n",
                        r["quality"].get<std::string>().c_str(), r["frame_ms"].get<double>(), r["fps"].get<double>(),
                        r["lighting_pass_ms"].get<double>(), r["lights_lit_per_sample"].get<double>(),
                        r["lighting_pass_ms_all_lights"].get<double>(), r["shells_ms"].get<double>(), r["resolve_ms"].get<double>(),
                        r["ratio_to_full_floor"].get<double>(), r["still_frame_ms"].get<double>(),
                        r["triangles_drawn"].get<double>() / 1000.0, r["frame_ms_full_meshes"].get<double>(),
                        coif::format_metric(e["blurred_psnr_db"].get<double>(), 1).c_str(), e["detail_ratio"].get<double>(),
                        *std::min_element(rad.begin(), rad.end()), *std::max_element(rad.begin(), rad.end()),
                        e["mask_iou"].get<double>());
        }
    });
}

COIF_REGISTER_COMMAND(92, add_bench_render);

}  // namespace
