#pragma once
// What `coif render` and `coif bench render` share: the default database, the lights, the camera.
#include <filesystem>
#include <string>
#include <vector>

#include "db/hrir_db.h"
#include "models/core/camera.h"
#include "offline/srbf_lights.h"
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
// The orbit camera of the scene options around the style's sampled strands (SceneOptions::camera_for of
// load_strands, as `coif reference` frames them) or --frame-strands; refuses an eye inside the shells' box.
Camera shell_camera(const SceneOptions& scene, const gl::ShellRenderer& renderer);

}  // namespace coif::cli
