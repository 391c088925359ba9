#include "tools/render_scene.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "offline/envmap.h"
#include "offline/srbf_fit.h"
#include "tools/assets.h"

namespace coif::cli {
namespace {

// ShellScene::camera: what `coif reference` frames for the same options, so that the two images line up pixel
// for pixel; `sampled` are the style's strands as sampled (not yet oriented).
Camera shell_camera(const SceneOptions& scene, Strands sampled) {
    if (!scene.frame_strands.empty()) return scene.camera_for(Strands{});
    if (!scene.strands.empty()) return scene.camera_for(scene.load_strands());
    return scene.camera_for(scene.oriented(std::move(sampled)));
}

}  // namespace

std::filesystem::path default_database_path() {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    const std::filesystem::path base = xdg && *xdg ? std::filesystem::path(xdg)
                                     : home && *home ? std::filesystem::path(home) / ".cache"
                                                     : std::filesystem::temp_directory_path();
    DbParams p;
    p.sectors = kDefaultRenderSectors;
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(params_hash(p)));
    return base / "coif" / ("default-" + std::to_string(p.sectors) + "-" + hash + ".db");
}

HrirDatabase open_render_database(const std::string& db_path) {
    if (!db_path.empty()) return HrirDatabase::open(db_path);
    const std::filesystem::path path = default_database_path();
    if (std::filesystem::exists(path)) {
        std::fprintf(stderr, "coif: no --db given: using the cached default database %s\n", path.string().c_str());
        return HrirDatabase::open(path);
    }
    std::filesystem::create_directories(path.parent_path());
    BuildOptions b;
    b.params.sectors = kDefaultRenderSectors;
    b.threads = thread_count(0);  // every hardware thread
    std::fprintf(stderr,
                 "coif: no --db given: building the default database (%llu sectors, %d threads) into %s; later runs reuse it\n",
                 static_cast<unsigned long long>(b.params.sectors), b.threads, path.string().c_str());
    build_database(b, path);
    return HrirDatabase::open(path);
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
        return read_srbf_lights(p).lights;
    }
    const EnvMap map = load_envmap(p);
    SrbfFitSettings fs;
    std::fprintf(stderr, "coif: fitting %d SRBF lights to %s (save them with `coif env fit` to skip this)\n", fs.lights,
                 env.c_str());
    *label = env + " (fitted " + std::to_string(fs.lights) + " SRBF lights)";
    return fit_srbf_lights(map, fs).lights;
}

void refuse_eye_inside(const Camera& camera, const gl::ShellRenderer& r) {
    const glm::vec3 lo = r.bounds_min(), hi = r.bounds_max();
    if (glm::all(glm::greaterThan(camera.eye, lo)) && glm::all(glm::lessThan(camera.eye, hi)))
        throw Error::parameter("camera", "the eye lies inside the hair's bounding box");
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

SceneInputs read_scene_inputs(const SceneOptions& scene, const std::string& env) {
    SceneInputs in;
    in.lights = load_render_lights(env, &in.lights_label);
    in.style = load_style(scene.style);
    return in;
}

ShellScene::ShellScene(const SceneOptions& scene, SceneInputs inputs, const std::string& db_path, int lighting_rows,
                       const AbsorptionMap* absorption)
    : lights_label(std::move(inputs.lights_label)),
      lights(std::move(inputs.lights)),
      style(std::move(inputs.style)),
      db(open_render_database(db_path)),
      satf(SatfIndex::open(db, SatfOptions{})),
      context(gl::Context::headless()) {
    Strands sampled;
    renderer = std::make_unique<gl::ShellRenderer>(style, satf, gl::style_orientation(style), lighting_rows, &sampled);
    renderer->set_lights(lights);
    if (absorption) renderer->set_absorption(absorption);
    camera = shell_camera(scene, std::move(sampled));
    refuse_eye_inside(camera, *renderer);
}

}  // namespace coif::cli
