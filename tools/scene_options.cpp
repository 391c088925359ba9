#include "tools/scene_options.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "models/core/error.h"
#include "models/style_strands.h"
#include "offline/envmap.h"
#include "offline/srbf_fit.h"
#include "online/scene/hair_scene.h"
#include "tools/assets.h"

namespace coif::cli {

void add_background_option(CLI::App* app, std::vector<float>& rgb) {
    app->add_option("--background", rgb,
                    "Background colour R G B, linear (default 0.05 0.05 0.06; 0 0 0 for coif compare's radiance ratio "
                    "of images without alpha)")
        ->expected(3);
}

void add_rotate_lights_option(CLI::App* app, double& degrees) {
    app->add_option("--rotate-lights", degrees,
                    "Turn the environment (map or lights) by DEG degrees about +y (right-handed: +x toward -z); the same "
                    "number gives the same lighting in coif render, coif reference and coif env fit --rotate");
}

float lights_rotation(double degrees) { return srbf_rotation_radians(degrees, "option --rotate-lights"); }

glm::vec3 background_color(const std::vector<float>& v) {
    if (v.empty()) return kDefaultBackground;
    if (v.size() != 3) throw Error::parameter("option --background", "needs three numbers R G B");
    for (float c : v)
        if (!std::isfinite(c)) throw Error::parameter("option --background", "must be finite numbers");
    return {v[0], v[1], v[2]};
}

// Largest image side the commands accept (the GL target may allow less; it is checked too): 8192, a size the exact
// compositing honours in tiles on llvmpipe's 16.8 M fragments (ShellRenderer::render; the default style at 8192 x 8192
// took 118 tiles and about 6 minutes), and a 1 GiB linear image.
constexpr int kMaxRenderSide = 8192;

HairStyle load_style(const std::string& path) {
    if (path == kDefaultStyleName) {
        constexpr const char* kAsset = "default_style.json";
        const std::vector<std::byte> bytes = asset_bytes(kAsset);
        return parse_style(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                           std::string("<embedded ") + kAsset + ">");
    }
    if (is_hair_asset(path))
        throw Error(path, "", "a cooked .coif asset holds no style or strands: coif render --style draws it; this command "
                              "needs the style it was baked from");
    return read_style(path);
}

void SceneOptions::add_to(CLI::App* app) {
    app->add_option("--style", style,
                    "Cluster hairstyle (JSON) to draw, @default for the embedded one, or a cooked .coif asset (coif bake)");
    app->add_option("--strands", strands, "Draw this strand file (" + coif::strand_extensions() + ") instead of a style");
    app->add_option("--width", width, "Image width in pixels")->check(CLI::Range(1, kMaxRenderSide));
    app->add_option("--height", height, "Image height in pixels")->check(CLI::Range(1, kMaxRenderSide));
    app->add_option("--azimuth", azimuth_deg, "Camera azimuth about +y in degrees, 0 = looking from +z");
    app->add_option("--elevation", elevation_deg, "Camera elevation in degrees above the horizontal")->check(CLI::Range(-89.0, 89.0));
    app->add_option("--fov", fov_deg, "Vertical field of view in degrees")->check(CLI::Range(1.0, 150.0));
    app->add_flag("--keep-axes", keep_axes, "Keep the file's axes (by default a model whose hair hangs along -x or -z is turned y-up)");
    app->add_option("--frame-strands", frame_strands,
                    "Frame the camera on this strand file (oriented as --strands) instead of what is drawn: lines up images "
                    "of different geometry of the same hair, e.g. a style fitted to the file and the file itself");
}

Strands SceneOptions::load_strands(std::string* label) const {
    if (label)
        *label = !strands.empty() ? strands
               : style == kDefaultStyleName ? "strands sampled from the embedded default style (harolongo, 64 clusters)"
                                            : "strands sampled from " + style;
    return oriented(strands.empty() ? sample_strands(load_style(style), StrandSampling{}) : read_strands(strands));
}

Strands SceneOptions::oriented(Strands s) const {
    if (keep_axes) return s;
    return oriented_y_up(std::move(s));
}

std::pair<glm::vec3, glm::vec3> SceneOptions::frame_box(const Strands& drawn) const {
    const StrandStats st = frame_strands.empty() ? strand_stats(drawn) : strand_stats(oriented(read_strands(frame_strands)));
    return {glm::vec3(st.bbox_min), glm::vec3(st.bbox_max)};
}

OrbitView SceneOptions::orbit_view() const {
    OrbitView v;
    v.azimuth = static_cast<float>(radians(azimuth_deg));
    v.elevation = static_cast<float>(radians(elevation_deg));
    v.width = width;
    v.height = height;
    v.fov_y = static_cast<float>(radians(fov_deg));
    return v;
}

gl::SceneFraming SceneOptions::shell_framing(bool strands_option) const {
    gl::SceneFraming f;
    f.view = orbit_view();
    f.keep_axes = keep_axes;
    if (!frame_strands.empty()) f.box = frame_box(Strands{});
    else if (strands_option && !strands.empty()) f.box = frame_box(load_strands());
    return f;
}

std::vector<SrbfLight> load_render_lights(const std::string& env, std::string* label) {
    if (env.empty()) {
        const std::vector<std::byte> bytes = asset_bytes("default_lights.json");
        *label = "embedded default lights (40 SRBF, courtyard)";
        return srbf_lights_from_json(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                                     "<embedded default_lights.json>")
            .lights;
    }
    const std::filesystem::path p(env);
    if (p.extension() == ".json") {
        *label = env;
    } else {
        const SrbfFitSettings fs;
        std::fprintf(stderr, "coif: fitting %d SRBF lights to %s (save them with `coif env fit` to skip this)\n", fs.lights,
                     env.c_str());
        *label = env + " (fitted " + std::to_string(fs.lights) + " SRBF lights)";
    }
    return environment_lights(p);
}

SceneInputs read_scene_inputs(const SceneOptions& scene, const std::string& env) {
    SceneInputs in;
    in.lights = load_render_lights(env, &in.lights_label);
    if (scene.style != kDefaultStyleName && is_hair_asset(scene.style)) in.cooked = read_hair_asset(scene.style);
    else in.style = load_style(scene.style);
    return in;
}

gl::HairSceneDesc hair_scene_desc(const SceneOptions& scene, SceneInputs inputs, const std::string& db_path,
                                  int lighting_rows, const AbsorptionMap* absorption) {
    gl::HairSceneDesc d;
    d.style = std::move(inputs.style);
    d.cooked = std::move(inputs.cooked);
    d.lights = std::move(inputs.lights);
    d.lights_label = std::move(inputs.lights_label);
    d.database = db_path;
    d.log = &std::cerr;
    d.lighting_rows = lighting_rows;
    d.absorption = absorption;
    d.body = std::move(inputs.body);
    d.framing = scene.shell_framing();
    return d;
}

void ShellOptions::add_to(CLI::App* app) {
    app->add_option("--db", db, "HRIR database (coif db build); default: the cached default database");
    app->add_option("--env", env,
                    "Environment: SRBF lights JSON (coif env fit) or an equirectangular .exr/.hdr map (fitted with 40 "
                    "lights); default: the embedded courtyard lights");
    app->add_option("--params", params,
                    "Parameters file: a JSON object of the keys listed below, each optional; default: 000's brown hair and "
                    "the renderer's defaults (for a .coif asset: the parameters it was baked with); the strand lines read the hair keys only");
    app->add_option("--absorption", absorption,
                    "Painted absorption map (coif style paint-absorption): σa per cluster and along it, instead of "
                    "--params' sigma_a");
    app->add_option("--body", body,
                    "A character's body (" + body_extensions() + ") drawn opaque under the hair: it hides the hair behind it "
                    "and shadows the hair (within the hair's box). TressFX's .tfxmesh is read from metres into centimetres, "
                    "the frame of its .tfx strands; an .obj is kept as stored, and must be in the strand file's units and axes")
        ->check(CLI::ExistingFile);
    app->add_flag("--scalp", scalp,
                  "For hair without a head: a sphere fitted to the style's cluster roots (they lie on it), drawn and "
                  "shadowing as --body does");
    app->add_option("--lighting-rows", lighting_rows,
                    "Lighting samples per HSV along each cluster (0 = one per mesh row, the style's mesh[0])")
        ->check(CLI::Range(0, 64))
        ->capture_default_str();
    app->add_option("--samples", samples,
                    "Samples per pixel: MSAA with --compositing sorted/unsorted; with exact (the default) and weighted "
                    "round(sqrt(N))^2 frames shifted within the pixel are averaged (N = 4: 2x2, 4x the time)")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    std::string presets;
    for (const gl::QualityPreset& p : gl::kQualityPresets) presets += std::string("\n  ") + p.name + ": " + p.summary;
    app->add_option("--quality", quality,
                    "Quality preset, a set of the choices that trade the image for time (after --params, which may name one "
                    "too as \"quality\"; --compositing overrides it):" + presets)
        ->check(CLI::IsMember(gl::quality_names()));
    app->add_option("--compositing", compositing,
                    "exact (per-pixel fragment lists sorted on the GPU; --samples supersamples it: the default), weighted "
                    "(weighted blended order-independent transparency: bounded memory, no order; supersampled as exact), "
                    "kbuffer (each pixel's nearest fragments exact, --params kbuffer_slots of them, 8 by default, the rest "
                    "weighted blended behind them: bounded memory; supersampled as exact), sorted (clusters back to front, "
                    "blended; MSAA applies), or unsorted; overrides the --params key")
        ->check(CLI::IsMember(gl::compositing_names()));
    app->add_option("--radius", radius,
                    "Fibre radius in scene units, as coif reference --radius: the strand lines' pixel coverage 2r/pixel, and "
                    "the fibres that the shells' shadows between clusters count (the --params key fiber_radius; 0 = the "
                    "reference's auto radius, 1e-3 of the strands' bounding-box diagonal)")
        ->check(CLI::Range(0.0f, 1e6f))
        ->capture_default_str();
    add_background_option(app, background);
    add_rotate_lights_option(app, rotate_lights_deg);
}

gl::ShellSettings ShellOptions::settings(const SceneInputs& inputs) const {
    gl::ShellSettings s = inputs.cooked ? inputs.cooked->defaults : gl::ShellSettings{};
    s.samples = samples;
    if (!params.empty()) s = gl::read_shell_settings(params, s);
    if (radius > 0) s.fiber_radius = radius;
    s.background = background_color(background);
    if (!quality.empty()) gl::apply_quality(s, gl::parse_quality(quality, "", "option --quality"));
    if (!compositing.empty()) s.compositing = gl::parse_compositing(compositing, "", "option --compositing");
    return s;
}

SceneInputs ShellOptions::read_inputs(const SceneOptions& scene) const {
    SceneInputs in = read_scene_inputs(scene, env);
    in.lights = rotate_srbf_lights_y(in.lights, lights_rotation(rotate_lights_deg));
    in.body = body_mesh(in);
    return in;
}

std::optional<BodyMesh> ShellOptions::body_mesh(const SceneInputs& inputs) const {
    if (scalp && !body.empty()) throw Error::parameter("option --scalp", "give either --body or --scalp");
    if (!body.empty()) return read_body(body);
    if (!scalp) return std::nullopt;
    if (inputs.cooked) throw Error::parameter("option --scalp", "needs a style's roots, not a baked .coif asset");
    // The roots and their directions in the strand file's frame (the scene turns a body from there).
    const glm::mat3 to_file = glm::transpose(style_source_rotation(inputs.style));
    std::vector<glm::vec3> roots;
    for (const Cluster& c : inputs.style.clusters) roots.push_back(to_file * glm::vec3(c.placement.apply(c.shape->position(0.0))));
    return scalp_from_roots(roots);
}

std::optional<AbsorptionMap> ShellOptions::absorption_map(const SceneInputs& inputs) const {
    if (absorption.empty()) return std::nullopt;
    return read_absorption_map(absorption, inputs.clusters());
}

}  // namespace coif::cli
