#pragma once
// The GPU measurements behind `coif bench gl`, `coif bench lighting` and `coif bench render`, as library calls:
// each needs a current GL context (online/gl_context.h) and returns plain figures; the commands print them.
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "models/core/camera.h"
#include "online/gl_context.h"
#include "online/shell_renderer.h"
#include "shaders/lighting.h"

namespace coif::gl {

// The fill-rate floor of the GPU: `layers` full-screen triangles of a constant-colour shader, alpha blended into
// an RGBA16F target of width × height, per frame; `frames` frames timed after one warm-up frame.
struct FillRateOptions {
    int width = 720, height = 480, layers = 8, frames = 20;
};
struct FillRate {
    double gpu_ms_per_frame = 0, wall_ms_per_frame = 0;           // GPU timer queries; wall clock
    double mfragments_per_s_gpu = 0, mfragments_per_s_wall = 0;   // width · height · layers per frame
};
FillRate measure_fill_rate(const FillRateOptions& options);

// The SRBF lighting (shaders/lighting/) as a compute shader (shaders/lighting/bench_lighting.comp): every point
// (θo, φo, 0, 0) sums single (and, with `multiple`, multiple) scattering over every light (θj, φj, λj, σ̄_f²).
struct GpuLightingRun {
    double compile_seconds = 0;   // the compute program's compilation and link
    double dispatch_seconds = 0;  // per dispatch: the mean of `repeats` after a warm-up dispatch (wall clock)
    std::vector<glm::vec3> single, multiple;  // per point
};
GpuLightingRun run_gpu_lighting(std::span<const glm::vec4> points, std::span<const glm::vec4> lights,
                                const shading::HairParams& hair, const shading::LightingConfig& config, bool multiple,
                                int repeats);
// The largest |GPU − CPU| over points, channels and both sums, relative to the largest CPU single + multiple
// channel value.
double max_relative_difference(const GpuLightingRun& gpu, std::span<const glm::vec3> cpu_single,
                               std::span<const glm::vec3> cpu_multiple);

// Frame times of a shell renderer (wall clock, milliseconds): the median over `frames` frames after one warm-up
// frame (shader compilation, first-use uploads) of the whole frame (draw, then waiting for the GPU) and of its
// passes (ShellTimings, with ShellSettings::timed); `floor` draws the trivial-shader floor instead.
struct ShellFrameTimes {
    double wall_ms = 0, lighting_ms = 0, shells_ms = 0, resolve_ms = 0;
};
ShellFrameTimes time_shell_frames(ShellRenderer& renderer, const Camera& camera, const ShellSettings& settings,
                                  bool floor, int frames);

}  // namespace coif::gl
