// coif bench render — frame time of the SATF shell renderer with the SRBF lights, and its ratio to a
// trivial-shader pass over the same shells in the same run (the floor).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "models/core/error.h"
#include "online/gl_context.h"
#include "online/shell_renderer.h"
#include "tools/cli.h"
#include "tools/render_scene.h"
#include "tools/scene_options.h"

namespace {

struct BenchRenderOptions {
    coif::cli::SceneOptions scene;
    std::string db, env, params;
    int frames = 10, samples = 1, lighting_rows = 0;
    bool json = false;
};

struct FrameStats {
    double wall_ms = 0, lighting_ms = 0, shells_ms = 0;
};

// Median over `frames` frames after one warm-up frame (shader compilation, first-use uploads).
FrameStats measure(coif::gl::ShellRenderer& r, const coif::Camera& cam, const coif::gl::ShellSettings& s, bool floor,
                   int frames) {
    std::vector<FrameStats> all;
    for (int f = 0; f <= frames; ++f) {
        const auto t0 = std::chrono::steady_clock::now();
        r.draw(cam, s, floor);
        glFinish();
        const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (f > 0) all.push_back({wall, r.timings().lighting_ms, r.timings().shells_ms});
    }
    const auto med = [&](auto field) {
        std::vector<double> v;
        for (const FrameStats& x : all) v.push_back(x.*field);
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
    };
    return {med(&FrameStats::wall_ms), med(&FrameStats::lighting_ms), med(&FrameStats::shells_ms)};
}

void add_bench_render(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchRenderOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "render",
        "Frame time of `coif render`'s SATF shell renderer (SRBF Marschner lighting, 40 lights by default)\n"
        "Renders the scene --frames times after one warm-up frame into an offscreen target and reports the median wall\n"
        "time (glFinish) and the GPU time of the lighting pass and of the shells (GL_TIME_ELAPSED), then the same\n"
        "shells in the same order with a trivial constant-colour shader (the floor) and the ratio of the two.");
    o->scene.add_to(cmd);
    cmd->add_option("--db", o->db, "HRIR database; default: the cached default database (built on first use)");
    cmd->add_option("--env", o->env, "SRBF lights JSON or an environment map; default: the embedded 40 lights");
    cmd->add_option("--params", o->params, "Scattering parameters JSON (see coif render)");
    cmd->add_option("--frames", o->frames, "Frames measured (after one warm-up frame)")->check(CLI::Range(1, 1000))->capture_default_str();
    cmd->add_option("--lighting-rows", o->lighting_rows,
                   "Lighting samples per HSV along each cluster (0 = one per mesh row, the style's mesh[0])")
        ->check(CLI::Range(0, 64))->capture_default_str();
    cmd->add_option("--samples", o->samples, "MSAA samples per pixel")->check(CLI::Range(1, 16))->capture_default_str();
    cmd->add_flag("--json", o->json, "Print JSON instead of a table");
    coif::cli::examples(cmd, "  coif bench render\n"
                             "  coif bench render --width 1920 --height 1080 --frames 5 --json");
    cmd->callback([o] {
        coif::gl::ShellSettings settings;
        settings.samples = o->samples;
        if (!o->params.empty()) settings = coif::gl::read_shell_settings(o->params, settings);
        std::string lights_label;
        const auto lights = coif::cli::load_render_lights(o->env, &lights_label);
        const coif::HairStyle style = coif::cli::load_style(o->scene.style);
        const coif::HrirDatabase db = coif::cli::open_render_database(o->db);
        const coif::SatfIndex satf = coif::SatfIndex::open(db, coif::SatfOptions{});
        auto context = coif::gl::Context::headless();
        coif::gl::ShellRenderer renderer(style, satf, coif::gl::style_orientation(style), o->lighting_rows);
        renderer.set_lights(lights);
        const coif::Camera cam = coif::cli::shell_camera(o->scene, renderer);
        coif::gl::RenderTarget target(cam.width, cam.height, GL_RGBA16F, settings.samples);
        target.bind();
        const FrameStats full = measure(renderer, cam, settings, false, o->frames);
        const FrameStats floor = measure(renderer, cam, settings, true, o->frames);
        const auto& st = renderer.stats();
        nlohmann::ordered_json j = {
            {"renderer", context->renderer()},
            {"width", cam.width}, {"height", cam.height}, {"samples", settings.samples},
            {"lights", lights.size()}, {"multiple_scattering", settings.multiple}, {"neighbours", settings.neighbours},
            {"clusters", st.clusters}, {"sectors", st.sectors}, {"triangles", st.triangles},
            {"lighting_samples", st.lighting_samples}, {"records", st.records}, {"prepare_s", st.prepare_seconds},
            {"frame_ms", full.wall_ms}, {"fps", 1000.0 / full.wall_ms},
            {"gpu_lighting_ms", full.lighting_ms}, {"gpu_shells_ms", full.shells_ms},
            {"floor_ms", floor.wall_ms}, {"floor_gpu_shells_ms", floor.shells_ms},
            {"ratio_to_floor", full.wall_ms / floor.wall_ms}, {"frames", o->frames}};
        if (o->json) {
            std::printf("%s\n", j.dump(2).c_str());
            return;
        }
        std::printf("renderer          %s\n", context->renderer().c_str());
        std::printf("scene             %s: %zu clusters, %zu sectors, %zu triangles, %zu lights, %dx%d, %d sample(s)\n",
                    o->scene.style.c_str(), st.clusters, st.sectors, st.triangles, lights.size(), cam.width, cam.height,
                    settings.samples);
        std::printf("frame             %.1f ms (%.1f fps), median of %d\n", full.wall_ms, 1000.0 / full.wall_ms, o->frames);
        std::printf("  lighting pass   %.1f ms GPU (%zu samples x %zu lights%s)\n", full.lighting_ms, st.lighting_samples,
                    lights.size(), settings.multiple ? ", single + multiple" : ", single scattering");
        std::printf("  shells          %.1f ms GPU (re/alpha look-up, shadow, lighting combine, compositing)\n", full.shells_ms);
        std::printf("floor             %.1f ms (trivial shader, same shells and order)\n", floor.wall_ms);
        std::printf("ratio to floor    %.2f\n", full.wall_ms / floor.wall_ms);
    });
}

COIF_REGISTER_COMMAND(92, add_bench_render);

}  // namespace
