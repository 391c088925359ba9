#pragma once
// What the commands that draw the SATF shells (`coif render`, `coif bench render`, `coif bench compositing`)
// share: the default database, the lights, the camera, and the scene built from them.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "db/hrir_db.h"
#include "db/satf.h"
#include "models/absorption_map.h"
#include "models/core/camera.h"
#include "models/hair_style.h"
#include "models/strands.h"
#include "offline/srbf_lights.h"
#include "online/gl_context.h"
#include "online/shell_renderer.h"
#include "tools/scene_options.h"

namespace coif::cli {

// Sectors of the default database that `coif render` builds when given no --db.
inline constexpr std::uint64_t kDefaultRenderSectors = 1000;
// <cache>/coif/default-<sectors>-<params hash>.db, cache = $XDG_CACHE_HOME or ~/.cache.
std::filesystem::path default_database_path();
// The given database, or the cached default one (built on first use, saying so on stderr).
HrirDatabase open_render_database(const std::string& db_path);
// --env: "" = the embedded default lights, *.json = a lights file, else a map fitted with 40 lights.
std::vector<SrbfLight> load_render_lights(const std::string& env, std::string* label);
// Throws coif::Error::parameter if the camera's eye lies inside the renderer's shells' box.
void refuse_eye_inside(const Camera& camera, const gl::ShellRenderer& renderer);

// The median of timings (of frames, of passes); `v` not empty.
double median(std::vector<double> v);

// What the shell commands read first, before the database (which may take minutes to build) and GL: the
// --env lights and the --style, so that a wrong option is refused at once.
struct SceneInputs {
    std::string lights_label;
    std::vector<SrbfLight> lights;
    HairStyle style;
};
SceneInputs read_scene_inputs(const SceneOptions& scene, const std::string& env);

// The scene the shell commands draw: the style's shells in the SATF shell renderer (with the database, its SATF
// index and a headless GL context), lit by the lights, painted with `absorption` if given (it must outlive the
// scene), and the camera. The style's strands are sampled once, by the renderer, for its shadow grid and the
// camera both.
struct ShellScene {
    ShellScene(const SceneOptions& scene, SceneInputs inputs, const std::string& db_path, int lighting_rows,
               const AbsorptionMap* absorption = nullptr);
    ShellScene(const ShellScene&) = delete;
    ShellScene& operator=(const ShellScene&) = delete;

    std::string lights_label;
    std::vector<SrbfLight> lights;
    HairStyle style;
    HrirDatabase db;
    SatfIndex satf;
    std::unique_ptr<gl::Context> context;
    std::unique_ptr<gl::ShellRenderer> renderer;
    // The orbit camera of the scene options around the style's strands as the renderer sampled them, oriented as
    // SceneOptions::load_strands orients them (what `coif reference` frames), or around --strands or
    // --frame-strands when given; its eye outside the shells' box.
    Camera camera;
};

}  // namespace coif::cli
