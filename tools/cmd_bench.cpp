// coif bench gl — the floor of this GPU: fill rate of a trivial fragment shader with alpha blending
// into an RGBA16F target, the configuration every renderer benchmark is compared against.
#include <chrono>
#include <cstdio>

#include "models/core/error.h"
#include "online/gl.h"
#include "online/gl_context.h"
#include "tools/cli.h"

namespace {

struct GlBenchOptions {
    int width = 720, height = 480, layers = 8, frames = 20;
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
    gl->add_option("--width", o->width, "Target width in pixels")->check(CLI::Range(1, 16384));
    gl->add_option("--height", o->height, "Target height in pixels")->check(CLI::Range(1, 16384));
    gl->add_option("--layers", o->layers, "Full-screen layers per frame (overdraw)")->check(CLI::Range(1, 1000));
    gl->add_option("--frames", o->frames, "Frames to time (after one warm-up frame)")->check(CLI::Range(1, 100000));
    coif::cli::add_json_flag(gl, o->json);
    coif::cli::examples(gl, "  coif bench gl\n  coif bench gl --width 1920 --height 1080 --json");
    gl->callback([o] {
        auto context = coif::gl::Context::headless();
        coif::gl::Program program({"shaders/gl/fullscreen.vert", "shaders/gl/constant.frag"});
        coif::gl::RenderTarget target(o->width, o->height, GL_RGBA16F, 1);
        coif::gl::VertexArray vao = coif::gl::make_vertex_array();
        GLuint query_id = 0;
        glCreateQueries(GL_TIME_ELAPSED, 1, &query_id);
        coif::gl::Query query(query_id);
        target.bind();
        program.use();
        glUniform4f(program.uniform("u_color"), 0.4f, 0.3f, 0.2f, 0.25f);
        glBindVertexArray(vao.id());
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        const auto frame = [&] {
            glClear(GL_COLOR_BUFFER_BIT);
            for (int i = 0; i < o->layers; ++i) glDrawArrays(GL_TRIANGLES, 0, 3);
        };
        frame();
        glFinish();
        double gpu_seconds = 0;
        const auto start = std::chrono::steady_clock::now();
        for (int f = 0; f < o->frames; ++f) {
            glBeginQuery(GL_TIME_ELAPSED, query.id());
            frame();
            glEndQuery(GL_TIME_ELAPSED);
            GLuint64 ns = 0;
            glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &ns);
            gpu_seconds += double(ns) * 1e-9;
        }
        glFinish();
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        coif::gl::check_errors("bench gl");
        const double fragments = double(o->width) * o->height * o->layers * o->frames;
        const nlohmann::json result = {{"renderer", context->renderer()},
                                       {"width", o->width},
                                       {"height", o->height},
                                       {"layers", o->layers},
                                       {"frames", o->frames},
                                       {"gpu_ms_per_frame", 1e3 * gpu_seconds / o->frames},
                                       {"wall_ms_per_frame", 1e3 * wall / o->frames},
                                       {"mfragments_per_s_gpu", fragments / gpu_seconds * 1e-6},
                                       {"mfragments_per_s_wall", fragments / wall * 1e-6}};
        if (o->json) {
            coif::cli::print_json(result);
        } else {
            std::printf("renderer         %s\n", context->renderer().c_str());
            std::printf("target           %dx%d RGBA16F, %d blended full-screen layers, %d frames\n", o->width,
                        o->height, o->layers, o->frames);
            std::printf("frame time       %.3f ms (GPU timer), %.3f ms (wall)\n", result["gpu_ms_per_frame"].get<double>(),
                        result["wall_ms_per_frame"].get<double>());
            std::printf("fill rate        %.1f M fragments/s (GPU timer), %.1f M/s (wall)\n",
                        result["mfragments_per_s_gpu"].get<double>(), result["mfragments_per_s_wall"].get<double>());
        }
    });
}

COIF_REGISTER_COMMAND(90, add_bench);

}  // namespace
