#include "tools/animation_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "models/animation.h"
#include "models/core/error.h"
#include "online/scene/hair_motion.h"
#include "online/scene/hair_scene.h"

namespace coif::cli {
namespace fs = std::filesystem;
namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// The extremes (min, max) of the roots' signed distances from their nearest body vertex's tangent plane (the
// collider's measure: models/hair_dynamics.h).
glm::dvec2 root_offsets(const std::vector<glm::vec3>& roots, const BodyMesh& body) {
    BodyCollider collider;
    collider.set(body.positions, body.normals, kBodyColliderCell);
    glm::dvec2 range(INFINITY, -INFINITY);
    for (const glm::vec3& r : roots) {
        const double s = collider.signed_distance(r);
        range = {std::min(range.x, s), std::max(range.y, s)};
    }
    return range;
}
}  // namespace

AnimationResult run_animation(const SceneOptions& scene, const ShellOptions& shell, const AnimationSpec& spec,
                              const std::function<void(int, const Image&)>& frame_out) {
    SceneInputs inputs = shell.read_inputs(scene);
    if (inputs.cooked)
        throw Error::parameter("option --animate", "needs a style (its strands and bone weights), not a baked .coif asset");
    if (!inputs.style.skinning)
        throw Error::parameter("option --animate",
                               "the style has no bone weights: import it with `coif style import MODEL --skinning FILE.tfxbone`");
    if (!inputs.body) throw Error::parameter("option --animate", "needs the character's skinned --body (a .tfxmesh)");
    if (inputs.body->bones.empty()) throw Error::parameter("option --body", "the body has no bones to animate (an .obj has none)");
    // The spec's bones, in the body's skeleton, before anything is built.
    animation_pose(spec, inputs.body->bones, rest_pose(*inputs.body), 0);
    gl::ShellSettings settings = shell.settings(inputs);
    settings.timed = true;
    const BodyMesh body = *inputs.body;
    const glm::mat3 hair_orientation = style_orientation(inputs.style);
    const glm::mat3 body_turn = body_orientation(inputs.style);
    const std::optional<AbsorptionMap> absorption = shell.absorption_map(inputs);
    gl::HairScene hs(hair_scene_desc(scene, std::move(inputs), shell.db, shell.lighting_rows, absorption ? &*absorption : nullptr));
    gl::ShellRenderer& renderer = *hs.renderer;
    gl::HairMotion motion(hs.style, body, hair_orientation, body_turn);
    if (spec.dynamics) motion.simulate(*spec.dynamics);

    AnimationResult out;
    out.fps = spec.fps;
    out.width = hs.camera.width;
    out.height = hs.camera.height;
    out.renderer = hs.context ? hs.context->renderer() : "";
    // The static frame: the rest pose drawn once (shadows and lighting made), then again with nothing moved.
    renderer.render(hs.camera, settings);
    {
        const auto t0 = Clock::now();
        renderer.render(hs.camera, settings);
        out.still.total_ms = ms_since(t0);
        out.still.shadows_ms = renderer.timings().shadows_ms;
        out.still.lighting_ms = renderer.timings().lighting_wall_ms;
        out.still.shells_ms = renderer.timings().shells_wall_ms;
    }
    out.rest_root_offset = root_offsets(motion.roots(), motion.posed_body());
    out.animated_root_offset = glm::dvec2(INFINITY, -INFINITY);
    for (int f = 0; f < spec.frames; ++f) {
        const auto t0 = Clock::now();
        motion.pose(renderer, animation_pose(spec, motion.bones(), motion.rest(), f));
        const Image image = renderer.render(hs.camera, settings);
        AnimationFrame a;
        a.total_ms = ms_since(t0);
        a.skinning_ms = motion.timings().skinning_ms;
        a.deformation_ms = motion.timings().deformation_ms;
        a.shadow_grid_ms = motion.timings().shadow_grid_ms;
        a.shadows_ms = renderer.timings().shadows_ms;
        a.lighting_ms = renderer.timings().lighting_wall_ms;
        a.shells_ms = renderer.timings().shells_wall_ms;
        out.frames.push_back(a);
        const glm::dvec2 o = root_offsets(motion.roots(), motion.posed_body());
        out.animated_root_offset = {std::min(out.animated_root_offset.x, o.x), std::max(out.animated_root_offset.y, o.y)};
        if (frame_out) frame_out(f, image);
    }
    return out;
}

std::string animation_frame_path(const std::string& output, int frame) {
    const fs::path p(output);
    char n[16];
    std::snprintf(n, sizeof n, "_%04d", frame);
    return (p.parent_path() / (p.stem().string() + n + p.extension().string())).string();
}

std::string animation_sheet_path(const std::string& output) {
    const fs::path p(output);
    return (p.parent_path() / (p.stem().string() + "_sheet" + p.extension().string())).string();
}

int sheet_factor(int frames, int width) {
    const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(std::max(frames, 1)))));
    return std::max(1, (cols * width + 2047) / 2048);
}

Image shrink(const Image& im, int f) {
    const int w = im.width / f, h = im.height / f, c = im.channels;
    Image out(w, h, c, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k) {
                float sum = 0.0f;
                for (int j = 0; j < f; ++j)
                    for (int q = 0; q < f; ++q)
                        sum += im.pixels[(static_cast<std::size_t>(y * f + j) * im.width + static_cast<std::size_t>(x * f + q)) * c + k];
                out.pixels[(static_cast<std::size_t>(y) * w + x) * c + k] = sum / static_cast<float>(f * f);
            }
    return out;
}

Image contact_sheet(const std::vector<Image>& thumbs) {
    if (thumbs.empty()) return {};
    const int n = static_cast<int>(thumbs.size());
    const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const int rows = (n + cols - 1) / cols;
    const int tw = thumbs[0].width, th = thumbs[0].height, c = thumbs[0].channels;
    Image sheet(cols * tw, rows * th, c, 0.0f);
    for (int i = 0; i < n; ++i) {
        const Image& im = thumbs[static_cast<std::size_t>(i)];
        const int ox = (i % cols) * tw, oy = (i / cols) * th;
        for (int y = 0; y < th; ++y)
            std::copy_n(&im.pixels[static_cast<std::size_t>(y) * tw * c], static_cast<std::size_t>(tw) * c,
                        &sheet.pixels[(static_cast<std::size_t>(oy + y) * sheet.width + ox) * c]);
    }
    return sheet;
}

}  // namespace coif::cli
