#pragma once
// Options shared by the commands that draw a scene (render, view, reference, bench): which strands, the camera,
// and for the shell commands the lights and the scene (online/scene/hair_scene.h) built from them.
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "models/absorption_map.h"
#include "models/core/camera.h"
#include "models/hair_style.h"
#include "models/strands.h"
#include "offline/srbf_lights.h"
#include "online/shells/hair_asset.h"
#include "online/shells/shell_settings.h"
#include "tools/cli.h"

namespace coif::gl {
struct SceneFraming;   // online/scene/hair_scene.h (only the shell commands need it, and GL with it)
struct HairSceneDesc;
}  // namespace coif::gl

namespace coif::cli {

// "@default" names the hairstyle embedded in the binary (tools/assets/default_style.json).
inline constexpr const char* kDefaultStyleName = "@default";

// A style file, or the embedded default style for "@default".
HairStyle load_style(const std::string& path);

struct SceneOptions {
    std::string style = kDefaultStyleName;
    std::string strands;      // when set, these strands instead of the style's
    int width = 720, height = 480;
    double azimuth_deg = 20, elevation_deg = 10, fov_deg = 40;
    bool keep_axes = false;   // do not rotate the model's hang axis to -y
    std::string frame_strands;  // when set, the camera frames this strand file (oriented as --strands) instead

    void add_to(CLI::App* app);
    // The strands to draw: the --strands file, else strands sampled from the style's densities
    // (oriented y-up unless keep_axes). `label` says which, for messages and image metadata.
    Strands load_strands(std::string* label = nullptr) const;
    // `s` as load_strands orients what it loads: its hang axis turned to -y, unless keep_axes.
    Strands oriented(Strands s) const;
    // The box the camera frames: the --frame-strands file's strands' (oriented as load_strands orients a
    // --strands file) when given, else `drawn`'s.
    std::pair<glm::vec3, glm::vec3> frame_box(const Strands& drawn) const;
    // The orbit of these options (degrees turned to radians) and the camera it places around a box.
    OrbitView orbit_view() const;
    Camera camera_around(const std::pair<glm::vec3, glm::vec3>& box) const { return orbit_view().around(box.first, box.second); }
    Camera camera_for(const Strands& drawn) const { return camera_around(frame_box(drawn)); }
    // How the shell commands frame a style's shells: around the --frame-strands file's strands, else (when
    // `strands_option`) the --strands file's, else the style's own strands as the renderer sampled them.
    gl::SceneFraming shell_framing(bool strands_option = true) const;
};

// --background R G B (linear), shared by the commands that write a picture of the hair (render, reference):
// `add_background_option` declares it; `background_color` gives the colour (kDefaultBackground when not given),
// throwing coif::Error for a count other than 3 or a non-finite number.
void add_background_option(CLI::App* app, std::vector<float>& rgb);
glm::vec3 background_color(const std::vector<float>& rgb);

// --rotate-lights DEG: the environment (map or SRBF lights) turned about +y, right-handed (+x toward −z), for
// render and reference alike; `lights_rotation` gives radians, throwing coif::Error for a non-finite value.
void add_rotate_lights_option(CLI::App* app, double& degrees);
float lights_rotation(double degrees);

// --env: "" = the embedded default lights, *.json = a lights file, else a map fitted with 40 lights.
std::vector<SrbfLight> load_render_lights(const std::string& env, std::string* label);

// What the shell commands read first, before the database (which may take minutes to build) and GL: the
// --env lights and the --style, so that a wrong option is refused at once.
struct SceneInputs {
    std::string lights_label;
    std::vector<SrbfLight> lights;
    HairStyle style;                     // empty when --style names a `.coif` asset
    std::optional<CookedShells> cooked;  // the asset, when --style names one (online/shells/hair_asset.h)
    std::optional<BodyMesh> body;        // --body, when given (the shell commands)
    std::size_t clusters() const { return cooked ? cooked->shells.clusters() : style.clusters.size(); }
};
SceneInputs read_scene_inputs(const SceneOptions& scene, const std::string& env);

// The scene the shell commands draw: the inputs' style and lights, the --db database (empty: the cached default
// one, its messages on stderr), painted with `absorption` if given (it must outlive the scene), framed by
// shell_framing().
gl::HairSceneDesc hair_scene_desc(const SceneOptions& scene, SceneInputs inputs, const std::string& db_path,
                                  int lighting_rows, const AbsorptionMap* absorption = nullptr);

// The shell renderer's options beyond the scene, declared once for the commands that draw the shells (render, view):
// --db, --env, --params, --absorption, --body, --lighting-rows, --samples, --quality, --compositing, --radius,
// --background and --rotate-lights.
struct ShellOptions {
    std::string db, env, params, absorption, quality, compositing, body;
    int samples = 4;
    int lighting_rows = 0;
    float radius = 0.0f;
    std::vector<float> background;
    double rotate_lights_deg = 0;
    bool scalp = false;

    void add_to(CLI::App* app);
    // The --body mesh, or with --scalp the ellipsoid fitted to the style's roots (models/character.h), in the strand
    // file's frame as HairSceneDesc::body wants it; none without either. Throws coif::Error for both, or --scalp with an
    // asset.
    std::optional<BodyMesh> body_mesh(const SceneInputs& inputs) const;
    // The parameters to draw with: an asset's baked ones (else the library's), then --params, then the options.
    gl::ShellSettings settings(const SceneInputs& inputs) const;
    // read_scene_inputs with these options' --env, the lights turned by --rotate-lights, and the --body mesh.
    SceneInputs read_inputs(const SceneOptions& scene) const;
    // The --absorption map for these inputs' clusters, when given.
    std::optional<AbsorptionMap> absorption_map(const SceneInputs& inputs) const;
};

}  // namespace coif::cli
