#include "online/benchmarks.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "models/core/statistics.h"
#include "online/gl.h"
#include "online/lighting_uniforms.h"

namespace coif::gl {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Storage bindings of shaders/lighting/bench_lighting.comp.
constexpr GLuint kPointsBinding = 0, kLightsBinding = 1, kResultsBinding = 2;
constexpr int kLocalSize = 64;  // its local_size_x

}  // namespace

FillRate measure_fill_rate(const FillRateOptions& o) {
    Program program({"shaders/gl/fullscreen.vert", "shaders/gl/constant.frag"});
    RenderTarget target(o.width, o.height, GL_RGBA16F, 1);
    VertexArray vao = make_vertex_array();
    GLuint query_id = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &query_id);
    Query query(query_id);
    target.bind();
    program.use();
    glUniform4f(program.uniform("u_color"), 0.4f, 0.3f, 0.2f, 0.25f);
    glBindVertexArray(vao.id());
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    const auto frame = [&] {
        glClear(GL_COLOR_BUFFER_BIT);
        for (int i = 0; i < o.layers; ++i) glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    frame();
    glFinish();
    double gpu_seconds = 0;
    const auto start = Clock::now();
    for (int f = 0; f < o.frames; ++f) {
        glBeginQuery(GL_TIME_ELAPSED, query.id());
        frame();
        glEndQuery(GL_TIME_ELAPSED);
        GLuint64 ns = 0;
        glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &ns);
        gpu_seconds += double(ns) * 1e-9;
    }
    glFinish();
    const double wall = seconds_since(start);
    glDisable(GL_BLEND);
    check_errors("bench gl");
    const double fragments = double(o.width) * o.height * o.layers * o.frames;
    FillRate r;
    r.gpu_ms_per_frame = 1e3 * gpu_seconds / o.frames;
    r.wall_ms_per_frame = 1e3 * wall / o.frames;
    r.mfragments_per_s_gpu = fragments / gpu_seconds * 1e-6;
    r.mfragments_per_s_wall = fragments / wall * 1e-6;
    return r;
}

GpuLightingRun run_gpu_lighting(std::span<const glm::vec4> points, std::span<const glm::vec4> lights,
                                const shading::HairParams& hair, const shading::LightingConfig& config, bool multiple,
                                int repeats) {
    GpuLightingRun run;
    const auto c0 = Clock::now();
    Program program({"shaders/lighting/bench_lighting.comp"});
    run.compile_seconds = seconds_since(c0);
    LightingTextures textures;
    textures.update(hair, config);
    program.use();
    textures.bind(program, 0);
    set_lighting_uniforms(program, hair, config);
    Buffer pbuf = make_buffer(points.data(), points.size_bytes());
    Buffer lbuf = make_buffer(lights.data(), lights.size_bytes());
    Buffer rbuf = make_buffer(nullptr, points.size() * 2 * sizeof(glm::vec4), GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPointsBinding, pbuf.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightsBinding, lbuf.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kResultsBinding, rbuf.id());
    glUniform1i(program.uniform("u_num_points"), static_cast<GLint>(points.size()));
    glUniform1i(program.uniform("u_num_lights"), static_cast<GLint>(lights.size()));
    glUniform1i(program.uniform("u_multiple"), multiple ? 1 : 0);
    const GLuint groups = static_cast<GLuint>((points.size() + kLocalSize - 1) / kLocalSize);
    glDispatchCompute(groups, 1, 1);  // warm-up
    glFinish();
    const auto g0 = Clock::now();
    for (int r = 0; r < repeats; ++r) glDispatchCompute(groups, 1, 1);
    glFinish();
    run.dispatch_seconds = seconds_since(g0) / repeats;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> results(points.size() * 2);
    glGetNamedBufferSubData(rbuf.id(), 0, GLsizeiptr(results.size() * sizeof(glm::vec4)), results.data());
    check_errors("bench lighting");
    run.single.resize(points.size());
    run.multiple.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        run.single[i] = glm::vec3(results[2 * i]);
        run.multiple[i] = glm::vec3(results[2 * i + 1]);
    }
    return run;
}

double max_relative_difference(const GpuLightingRun& gpu, std::span<const glm::vec3> cpu_single,
                               std::span<const glm::vec3> cpu_multiple) {
    double max_diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < cpu_single.size(); ++i)
        for (int c = 0; c < 3; ++c) scale = std::max(scale, double(cpu_single[i][c] + cpu_multiple[i][c]));
    for (std::size_t i = 0; i < cpu_single.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            max_diff = std::max(max_diff, std::abs(double(gpu.single[i][c]) - cpu_single[i][c]) / scale);
            max_diff = std::max(max_diff, std::abs(double(gpu.multiple[i][c]) - cpu_multiple[i][c]) / scale);
        }
    return max_diff;
}

ShellFrameTimes time_shell_frames(ShellRenderer& r, const Camera& camera, const ShellSettings& settings, bool floor,
                                  int frames) {
    std::vector<ShellFrameTimes> all;
    for (int f = 0; f <= frames; ++f) {
        const auto t0 = Clock::now();
        r.draw(camera, settings, floor);
        glFinish();
        const double wall = 1e3 * seconds_since(t0);
        if (f > 0) all.push_back({wall, r.timings().lighting_wall_ms, r.timings().shells_wall_ms, r.timings().resolve_wall_ms});
    }
    const auto med = [&](double ShellFrameTimes::*field) {
        std::vector<double> v;
        for (const ShellFrameTimes& x : all) v.push_back(x.*field);
        return median(std::move(v));
    };
    return {med(&ShellFrameTimes::wall_ms), med(&ShellFrameTimes::lighting_ms), med(&ShellFrameTimes::shells_ms),
            med(&ShellFrameTimes::resolve_ms)};
}

}  // namespace coif::gl
