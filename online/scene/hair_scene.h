#pragma once
// The scene that `coif render`, `coif bench render` and `coif bench compositing` draw, as one library call: a
// hairstyle's SATF shells in the shell renderer (online/shell_renderer.h) with the HRIR database (given, or the
// cached default one: db/default_database.h), its SATF index and a headless GL context, lit by SRBF lights,
// painted with an absorption map if given, and a camera orbiting the hair. Its inputs are plain data
// (HairSceneDesc); the command line's options are parsed into them by tools/.
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "db/hrir_db.h"
#include "db/satf.h"
#include "models/absorption_map.h"
#include "models/character.h"
#include "models/core/camera.h"
#include "models/hair_style.h"
#include "models/strands.h"
#include "offline/srbf_lights.h"
#include "online/gl_context.h"
#include "online/scene/cook.h"
#include "online/shell_renderer.h"

namespace coif::gl {

// How a scene's camera frames its hair: an orbit (models/core/camera.h) around a box.
struct SceneFraming {
    OrbitView view;
    // Frame this box (world space) instead of the hair itself, e.g. another geometry of the same hair, so that
    // images of both line up.
    std::optional<std::pair<glm::vec3, glm::vec3>> box;
    bool keep_axes = false;  // frame the sampled strands in the style's axes (else turned y-up, as drawn)

    // The camera around `box` when set, else around the style's strands as the renderer sampled them
    // (ShellRenderer's `sampled_strands`), turned y-up unless keep_axes: what `coif reference` frames for the same
    // options, so that the two images line up pixel for pixel.
    Camera camera_for(Strands sampled) const;
    // The box camera_for frames.
    std::pair<glm::vec3, glm::vec3> box_for(Strands sampled) const;
};

struct HairSceneDesc {
    HairStyle style;
    // A cooked hair (online/shells/hair_asset.h, e.g. read from a `.coif` asset) to draw instead of `style`: no
    // database is opened, and the camera frames the box the asset holds (SceneFraming::keep_axes is refused: it
    // needs the style's strands).
    std::optional<CookedShells> cooked;
    std::vector<SrbfLight> lights;
    std::string lights_label;          // where the lights come from, in words (messages, image metadata)
    std::filesystem::path database;    // empty: the default database, built on first use
    std::ostream* log = nullptr;       // the default database's messages (which file, building it); null: none
    int lighting_rows = 0;             // ShellRenderer's lighting_rows_per_hsv (0: one per mesh row)
    const AbsorptionMap* absorption = nullptr;  // painted σa, or null; must outlive the scene
    CookCache* cook_cache = nullptr;  // online/scene/cook.h: kept for later cooks of edits (view_of); or null
    // A character's body under the hair (ShellRenderer::set_body), in the strand file's frame: turned as the style's
    // strands were on import (style_source_rotation) and are when drawn (style_orientation), which an asset holds
    // (CookedShells::body_orientation). Unless framing.box is set, the camera frames the hair and the body together.
    std::optional<BodyMesh> body;
    SceneFraming framing;
    // Make a headless GL context (EGL) for the scene; false: draw with the caller's, current on this thread (a
    // window's: coif view).
    bool headless = true;
};

// Throws coif::Error::parameter if the camera's eye lies inside the renderer's shells' box (nothing sensible
// can be drawn from there).
void refuse_eye_inside(const Camera& camera, const ShellRenderer& renderer);
// The same for the box [lo, hi] (e.g. a cooked hair's PreparedShells bounds).
void refuse_eye_inside(const Camera& camera, glm::vec3 lo, glm::vec3 hi);

// An offscreen target of the camera's size in the renderers' linear format (RGBA16F), with `samples` samples
// (MSAA when more than 1): what ShellRenderer::draw draws into for benchmarks.
RenderTarget camera_target(const Camera& camera, int samples);

// A style's shells in a renderer and the camera framing them.
struct ShellView {
    std::unique_ptr<ShellRenderer> renderer;
    Camera camera;
    glm::vec3 frame_min{0.0f}, frame_max{0.0f};  // the box the camera frames (to place other cameras around it)
};

struct HairScene {
    // Opens (or builds) the database and its SATF index, makes a headless GL context (unless desc.headless is
    // false), prepares the style's shells and frames them; throws coif::Error (also when the camera's eye is inside the hair).
    explicit HairScene(HairSceneDesc desc);
    HairScene(const HairScene&) = delete;
    HairScene& operator=(const HairScene&) = delete;

    // Another style's shells in a renderer sharing this scene's database, SATF index and lights, framed by
    // `framing` (without absorption); throws as the constructor, and coif::Error if the scene is an asset's (it has
    // no database). The renderer must not outlive the scene.
    ShellView view_of(const HairStyle& style, const SceneFraming& framing, int lighting_rows, CookCache* cache = nullptr) const;
    // Another style cooked with this scene's database, as the constructor cooks (for ShellRenderer::set_hair: coif view's
    // edits, with a cache that keeps what they did not change); throws as view_of.
    CookedShells cook(const HairStyle& style, int lighting_rows, CookCache* cache = nullptr) const;

    std::string lights_label;
    std::vector<SrbfLight> lights;
    HairStyle style;                  // empty for an asset
    std::optional<HrirDatabase> db;   // none for an asset
    std::optional<SatfIndex> satf;
    std::string database_label;       // the database drawn with: its path, or for an asset the one it was baked against
    std::unique_ptr<Context> context;  // null when HairSceneDesc::headless was false
    std::unique_ptr<ShellRenderer> renderer;
    Camera camera;
    glm::vec3 frame_min{0.0f}, frame_max{0.0f};  // the box the camera frames (SceneFraming)
};

}  // namespace coif::gl
