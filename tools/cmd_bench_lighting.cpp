// coif bench lighting — throughput of the SRBF lighting (issue 6) in lights × shading points per
// second: the shared GLSL as a compute shader (headless GL, llvmpipe on this machine) and the same
// code compiled as C++ on the CPU, plus texture look-ups per light and the largest GPU/CPU difference.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "models/core/error.h"
#include "online/gl.h"
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
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<float> U(0.0f, 1.0f);
        std::vector<glm::vec4> points(size_t(o->points)), lights(size_t(o->lights));
        for (auto& p : points) p = glm::vec4(std::asin(2.0f * U(rng) - 1.0f), 6.2831853f * U(rng) - 3.1415927f, 0, 0);
        for (auto& l : lights)
            l = glm::vec4(std::asin(2.0f * U(rng) - 1.0f), 6.2831853f * U(rng) - 3.1415927f,
                          0.05f * std::pow(40.0f, U(rng)), 0.02f * U(rng));

        // CPU: the GLSL compiled as C++.
        std::vector<glm::vec3> cpu_single(points.size()), cpu_multiple(points.size());
        const auto t0 = std::chrono::steady_clock::now();
        {
            const int threads = std::clamp(int(std::thread::hardware_concurrency()), 1, 2);
            std::vector<std::thread> pool;
            for (int t = 0; t < threads; ++t)
                pool.emplace_back([&, t] {
                    for (size_t i = size_t(t); i < points.size(); i += size_t(threads)) {
                        glm::vec3 s(0.0f), m(0.0f);
                        for (const auto& l : lights) {
                            s += eval.single(points[i].x, points[i].y, l.x, l.y, l.z);
                            if (o->multiple) m += eval.multiple(points[i].x, points[i].y, l.x, l.y, l.z, l.w);
                        }
                        cpu_single[i] = s;
                        cpu_multiple[i] = m;
                    }
                });
            for (auto& th : pool) th.join();
        }
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
                                 {"cpu_threads", std::clamp(int(std::thread::hardware_concurrency()), 1, 2)},
                                 {"cpu_seconds", cpu_seconds},
                                 {"cpu_light_points_per_s", pairs / cpu_seconds}};
        for (const auto& c : cost) result["texture_fetches"].push_back({{"what", c.what}, {"per_light", c.fetches_per_light}});

        if (!o->cpu_only) {
            auto context = coif::gl::Context::headless();
            const auto c0 = std::chrono::steady_clock::now();
            coif::gl::Program program({"shaders/lighting/bench_lighting.comp"});
            const double compile_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
            const LightingTables& tables = global_lighting_tables();
            const struct {
                const char* name;
                const LutImage* image;
            } luts[] = {{"lut_ck_lo", &tables.ck_lo},         {"lut_ck_hi", &tables.ck_hi},
                        {"lut_h_tt", &tables.h_tt},           {"lut_h_trt", &tables.h_trt},
                        {"lut_half_mass", &tables.half_mass}, {"lut_fresnel_fit", &tables.fresnel_fit},
                        {"lut_ms_ab", &eval.ms_tables().ab},  {"lut_ms_sat_delta", &eval.ms_tables().sat_delta},
                        {"lut_ms_sat_sigma", &eval.ms_tables().sat_sigma}};
            std::vector<coif::gl::Texture> textures;
            program.use();
            int unit = 0;
            for (const auto& l : luts) {
                textures.push_back(coif::gl::make_lut_texture(*l.image));
                glBindTextureUnit(GLuint(unit), textures.back().id());
                glUniform1i(program.uniform(l.name), unit);
                ++unit;
            }
            coif::gl::Buffer pbuf = coif::gl::make_buffer(points.data(), points.size() * sizeof(glm::vec4));
            coif::gl::Buffer lbuf = coif::gl::make_buffer(lights.data(), lights.size() * sizeof(glm::vec4));
            coif::gl::Buffer rbuf = coif::gl::make_buffer(nullptr, points.size() * 2 * sizeof(glm::vec4), GL_DYNAMIC_STORAGE_BIT);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pbuf.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, lbuf.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, rbuf.id());
            glUniform1i(program.uniform("u_num_points"), o->points);
            glUniform1i(program.uniform("u_num_lights"), o->lights);
            glUniform1i(program.uniform("u_multiple"), o->multiple ? 1 : 0);
            coif::gl::set_lighting_uniforms(program, params, config);
            const GLuint groups = GLuint((o->points + 63) / 64);
            glDispatchCompute(groups, 1, 1);  // warm-up
            glFinish();
            const auto g0 = std::chrono::steady_clock::now();
            for (int r = 0; r < o->repeats; ++r) glDispatchCompute(groups, 1, 1);
            glFinish();
            const double gpu_seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - g0).count() / o->repeats;
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            std::vector<glm::vec4> gpu(points.size() * 2);
            glGetNamedBufferSubData(rbuf.id(), 0, GLsizeiptr(gpu.size() * sizeof(glm::vec4)), gpu.data());
            coif::gl::check_errors("bench lighting");
            double max_diff = 0.0, scale = 0.0;
            for (size_t i = 0; i < points.size(); ++i)
                for (int c = 0; c < 3; ++c) scale = std::max(scale, double(cpu_single[i][c] + cpu_multiple[i][c]));
            for (size_t i = 0; i < points.size(); ++i)
                for (int c = 0; c < 3; ++c) {
                    max_diff = std::max(max_diff, std::abs(double(gpu[2 * i][c]) - cpu_single[i][c]) / scale);
                    max_diff = std::max(max_diff, std::abs(double(gpu[2 * i + 1][c]) - cpu_multiple[i][c]) / scale);
                }
            result["renderer"] = context->renderer();
            result["gl_compile_seconds"] = compile_seconds;
            result["gpu_seconds"] = gpu_seconds;
            result["gpu_light_points_per_s"] = pairs / gpu_seconds;
            result["gpu_vs_cpu_max_difference"] = max_diff;
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
