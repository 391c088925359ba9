// coif bench lighting — throughput of the SRBF lighting (issue 6) in lights × shading points per
// second: the shared GLSL as a compute shader (headless GL, llvmpipe on this machine) and the same
// code compiled as C++ on the CPU, plus texture look-ups per light and the largest GPU/CPU difference.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/random.h"
#include "models/core/units.h"
#include "online/benchmarks.h"
#include "online/gl_context.h"
#include "online/lighting_uniforms.h"
#include "shaders/lighting_check.h"
#include "tools/cli.h"

namespace {

using namespace coif::shading;

struct BenchOptions {
    int points = 16384, lights = 16, segments = 4, repeats = 3;
    bool multiple = true, json = false, cpu_only = false, paper = false;
};


void add_bench_lighting(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "lighting",
        "Throughput of the SRBF circular-Gaussian Marschner lighting: every shading point sums single (and\n"
        "multiple) scattering over all SRBF lights. Runs the shared GLSL (shaders/lighting/) as a compute\n"
        "shader on the headless GL context and the same code compiled as C++ on the CPU (2 threads), reports\n"
        "lights x points per second for each, texture look-ups per light (counted on the CPU), and the largest\n"
        "relative difference between GPU and CPU results. Random views, lights with lambda in [0.05, 2], default\n"
        "hair parameters, m segments.");
    cmd->add_option("--points", o->points, "Shading points (default 16384)")->check(CLI::Range(64, 1 << 24));
    cmd->add_option("--lights", o->lights, "SRBF lights per point (default 16)")->check(CLI::Range(1, 1024));
    cmd->add_option("-m,--segments", o->segments, "Linear-quadrature segments m (default 4)")->check(CLI::Range(2, 256));
    cmd->add_option("--repeats", o->repeats, "Timed GPU dispatches (default 3)")->check(CLI::Range(1, 1000));
    cmd->add_flag("!--no-multiple", o->multiple, "Single scattering only");
    cmd->add_flag("--cpu-only", o->cpu_only, "Skip the GL benchmark");
    cmd->add_flag("--paper", o->paper, "The paper's variant (Schlick, sqrt(pi) lambda, Taylor T, one-Gaussian N_TT) instead of ours");
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif bench lighting\n  coif bench lighting --points 65536 --lights 40 --json");
    cmd->callback([o] {
        const HairParams params = default_hair_params();
        const LightingConfig config = o->paper ? paper_config(o->segments) : default_config(o->segments);
        const LightingEvaluator eval(params, config);
        coif::Rng rng = coif::seeded_rng(5);
        std::uniform_real_distribution<float> U(0.0f, 1.0f);
        std::vector<glm::vec4> points(size_t(o->points)), lights(size_t(o->lights));
        for (auto& p : points) p = glm::vec4(std::asin(2.0f * U(rng) - 1.0f), coif::kTwoPiF * U(rng) - coif::kPiF, 0, 0);
        for (auto& l : lights)
            l = glm::vec4(std::asin(2.0f * U(rng) - 1.0f), coif::kTwoPiF * U(rng) - coif::kPiF,
                          0.05f * std::pow(40.0f, U(rng)), 0.02f * U(rng));

        // CPU: the GLSL compiled as C++, on every hardware thread.
        std::vector<glm::vec3> cpu_single(points.size()), cpu_multiple(points.size());
        const int cpu_threads = coif::thread_count(0);
        const auto t0 = std::chrono::steady_clock::now();
        coif::parallel_for(points.size(), cpu_threads, [&](size_t i) {
            glm::vec3 s(0.0f), m(0.0f);
            for (const auto& l : lights) {
                s += eval.single(points[i].x, points[i].y, l.x, l.y, l.z);
                if (o->multiple) m += eval.multiple(points[i].x, points[i].y, l.x, l.y, l.z, l.w);
            }
            cpu_single[i] = s;
            cpu_multiple[i] = m;
        });
        const double cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double pairs = double(points.size()) * double(lights.size());
        const auto cost = check::count_fetches(o->segments);

        nlohmann::json result = {{"variant", o->paper ? "paper" : "improved"},
                                 {"points", o->points},
                                 {"lights", o->lights},
                                 {"segments", o->segments},
                                 {"multiple_scattering", o->multiple},
                                 {"tables_build_seconds", global_lighting_tables().build_seconds},
                                 {"ms_tables_build_seconds", eval.ms_tables().build_seconds},
                                 {"cpu_threads", cpu_threads},
                                 {"cpu_seconds", cpu_seconds},
                                 {"cpu_light_points_per_s", pairs / cpu_seconds}};
        for (const auto& c : cost) result["texture_fetches"].push_back({{"what", c.what}, {"per_light", c.fetches_per_light}});

        if (!o->cpu_only) {
            auto context = coif::gl::Context::headless();
            const coif::gl::GpuLightingRun gpu =
                coif::gl::run_gpu_lighting(points, lights, params, config, o->multiple, o->repeats);
            result["renderer"] = context->renderer();
            result["gl_compile_seconds"] = gpu.compile_seconds;
            result["gpu_seconds"] = gpu.dispatch_seconds;
            result["gpu_light_points_per_s"] = pairs / gpu.dispatch_seconds;
            result["gpu_vs_cpu_max_difference"] = coif::gl::max_relative_difference(gpu, cpu_single, cpu_multiple);
        }
        if (o->json) {
            coif::cli::print_json(result);
            return;
        }
        std::printf("SRBF lighting throughput (%s variant): %d points x %d lights, m = %d, %s\n",
                    o->paper ? "paper" : "improved", o->points, o->lights, o->segments,
                    o->multiple ? "single + multiple scattering" : "single scattering only");
        std::printf("  tables at start-up       %.3f s (global), %.3f s (dual-scattering 1D tables)\n",
                    result["tables_build_seconds"].get<double>(), result["ms_tables_build_seconds"].get<double>());
        std::printf("  CPU (C++, %d threads)     %.3f s   %.3g lights x points / s\n", result["cpu_threads"].get<int>(),
                    cpu_seconds, pairs / cpu_seconds);
        if (!o->cpu_only) {
            std::printf("  GPU (%s)\n", result["renderer"].get<std::string>().c_str());
            std::printf("    compile                %.3f s\n", result["gl_compile_seconds"].get<double>());
            std::printf("    dispatch               %.3f s   %.3g lights x points / s\n", result["gpu_seconds"].get<double>(),
                        result["gpu_light_points_per_s"].get<double>());
            std::printf("    max |GPU - CPU|        %.2e of the largest value\n", result["gpu_vs_cpu_max_difference"].get<double>());
        }
        std::printf("  texture look-ups (counted):\n");
        for (const auto& c : cost) std::printf("    %-45s %6.2f\n", c.what.c_str(), c.fetches_per_light);
    });
}

COIF_REGISTER_COMMAND(91, add_bench_lighting);

}  // namespace
