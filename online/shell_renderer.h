#pragma once
// The online SATF renderer (004 §6) lit by the SRBF circular-Gaussian Marschner lighting (000):
// every cluster's layered shells drawn with re/α read from the HRIR database on the GPU, the
// within-cluster shadow of 004 eq. 12, and alpha compositing (004 eq. 14). docs/renderer.md states
// the choices and their measured cost and error.
//
// Once per hairstyle, cooked on the CPU (GL-free: online/scene/cook.h from a style and the database, or read from
// a `.coif` asset, online/shells/hair_asset.h), then uploaded by the constructor (online/shell_passes.h ShellGpu):
//   - prepared_shells.h: the prototypes' layer meshes, their sectors' SATF look-ups and shadow sums, and
//     every cluster's placement (one GL instance each) and lighting samples along its axis;
//   - record_atlas.h: the records the sectors use as one RGBA8 texture atlas (layout shaders/gl/record_atlas.glsl),
//     so x and θv are interpolated by the bilinear fetch;
//   - shadow_grid.h: the style's strands voxelized for the shadows between clusters.
// Per frame (online/shell_passes.h): a compute pass evaluates the SRBF lighting per lighting sample and light and folds it
// into the 9 Fourier sums of DESIGN.md decision 1 (shaders/gl/shell_lighting.comp); then the shells
// are composited (004 eq. 14) as ShellSettings::compositing says (decision 4, docs/renderer.md):
//   exact     (default) every fragment appended to per-pixel lists (online/fragment_lists.h), sorted
//             per pixel by eye distance and composited by a compute pass; single sample (no MSAA);
//   sorted    clusters back to front by the distance of their centre; each cluster draws its layers'
//             back faces outer → inner, then front faces inner → outer (the transparent core shows
//             what lies behind), blended "over" in that order: exact within one cluster, wrong where
//             clusters interpenetrate (22 dB against exact on the default scene);
//   unsorted  the same without the cluster sort (style order), for error figures;
//   weighted  weighted blended order-independent transparency (online/weighted_blend.h): every fragment added, in
//             any order, into a weighted mean colour and an exact transmittance; bounded memory, single sample.
// Nothing per frame runs on the CPU beyond the sort and the draw calls.
//
// Shadows between clusters (DESIGN.md decision 5): the style's strands (models/style_strands.h)
// voxelized once into a grid of their length by direction (online/shells/shadow_grid.h), two 3D textures; a
// compute pass (shaders/gl/shell_shadow.comp) marches it from every lighting sample towards every light for T̃
// and the fibres met n (fibres of the reference's radius), rerun only when the lights or the radius change;
// the lighting pass reads them (shaders/lighting/srbf_shadowed.glsl).
//
// Painted absorption: an optional σa per cluster and lighting row (models/absorption_map.h) in a texture
// that the lighting pass reads instead of the settings' σa.
//
// The shading is compiled per variant (records per sector, where the lighting is read, debug views):
// llvmpipe runs every branch of a shader under masks, so switches are #defines, not uniforms.
//
// Conventions: world is y-up centimetres after `orientation` (the style's hang axis turned to −y,
// as the strand preview does); light directions point towards the light; the camera is coif::Camera.
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "models/absorption_map.h"
#include "models/character.h"
#include "models/core/camera.h"
#include "models/core/image.h"
#include "online/fragment_lists.h"
#include "online/shells/shell_lod.h"
#include "online/frame.h"
#include "online/shells/hair_asset.h"
#include "online/shells/prepared_shells.h"
#include "online/shells/shell_settings.h"
#include "shaders/srbf_light.h"

namespace coif::gl {

struct ShellDraw;  // online/shell_passes.h

struct ShellStats {
    std::size_t clusters = 0, prototypes = 0, sectors = 0, triangles = 0, lighting_samples = 0;
    std::size_t records = 0;           // in the atlas: those the sectors use
    std::size_t database_records = 0;  // of the database the hair was cooked against
    int atlas_width = 0, atlas_height = 0;
    double prepare_seconds = 0;  // the constructor: the upload and the compilation of the passes' first programs
    double upload_seconds = 0;   // of which the buffers' and textures' upload (glFinish after it)
    float re_norm = 1;           // Σ mean re a_0 / Σ mean α over the database (see docs/renderer.md)
    std::size_t shadow_strands = 0;  // strands voxelized for the shadow grid
    int grid_x = 0, grid_y = 0, grid_z = 0;
    float voxel = 0;                 // shadow grid voxel edge, world units
    // RMS angle (radians) of the style's strands about their own cluster's axis (measure_fibre_tilts,
    // online/shells/prepared_shells.h, which also gives the lighting each sample's tilts).
    float tangent_spread = 0;
    // coif reference's auto fibre radius of the same strands as oriented (models/strands.h auto_fiber_radius):
    // the radius the shadows between clusters count unless ShellSettings::fiber_radius sets one.
    float auto_fiber_radius = 0;
};

// The own cluster's depth two ways (docs/quality.md, "re's dependence on the light is the tracer's Phong"), medians:
// `length`, the strands' projected length across its narrow diameter at each lighting sample, as the shadow grid holds
// it (DensityGrid::integrate; times 2r, the reference's fibres a light crosses there), and `alpha`, Σ ᾱ of every layer
// at each sector (the shells' depth along one radius before κ_shadow, shaders/lighting/own_cluster.glsl).
struct OwnClusterDepth {
    float length = 0;
    float alpha = 0;
};

// Of the last draw, milliseconds: with ShellSettings::timed, wall-clock times of each pass between glFinish
// calls (GL_TIME_ELAPSED is not used: llvmpipe's rasteriser runs on after a query ends; measured, a lighting
// pass of 0.5 ms read 430 ms).
struct ShellTimings {
    double shadows_ms = 0;  // wall time of the shadow pass and the key lights' grid and volumes (glFinish); 0 when cached
    double lighting_wall_ms = 0, shells_wall_ms = 0;  // with ShellSettings::timed, else 0
    double resolve_wall_ms = 0;  // of shells_wall_ms, the exact or weighted compositing's resolve (timed)
    std::size_t clusters_drawn = 0;  // clusters in the view (ShellSettings::cull), every instance counted
    std::array<std::size_t, kLodLevels> clusters_at_level{};  // of those, at each level of detail (ShellSettings::lod_pixels)
    std::size_t triangles_drawn = 0;  // by the last frame's draws, both faces of every layer counted
    int tiles = 1;              // render()'s last frame: 1, or the tiles it was drawn in (beyond the fragment storage)
    int lighting_step = 1;      // the last draw's step along the lighting samples (ShellSettings::lighting_step, as the style allows)
    bool lighting_ran = false;  // the last draw's lighting pass ran (false: its sums were reused, ShellSettings::reuse_lighting)
};

class ShellRenderer {
public:
    // Needs a current GL 4.5 context. Uploads a cooked hair (online/shells/hair_asset.h: cooked from a style by
    // online/scene/cook.h, or read from a `.coif` asset); throws coif::Error if it has no clusters or exceeds the
    // GPU's limits.
    explicit ShellRenderer(CookedShells cooked);
    // Draws another cooked hair from now on (coif view's edited style), keeping the compiled programs, the lights and
    // the body (set_lights, set_body); what was of the last hair goes: its motion (set_cluster_transforms), its painted
    // absorption (give it again: set_absorption) and its shadow grid (the new hair's). Throws as the constructor, with the
    // last hair kept.
    void set_hair(CookedShells cooked);
    ~ShellRenderer();
    ShellRenderer(const ShellRenderer&) = delete;
    ShellRenderer& operator=(const ShellRenderer&) = delete;

    void set_lights(std::span<const SrbfLight> lights);
    // Painted absorption (one row per cluster of the style, any number of samples along t), or null:
    // σa from the settings everywhere. Throws coif::Error::parameter if the cluster count differs.
    void set_absorption(const AbsorptionMap* map);
    // A character's body (models/character.h), turned by `orientation` (the hair's: the body is in its strands' file
    // frame), or null: none. It shadows the hair in every draw (voxelized into the shadow grid: voxelize_body, within the
    // hair's box), and draw() and render() draw it opaque behind and between the hair's fragments (online/body_pass.h);
    // draw_frame does not draw it (the host draws its own scene and passes its depth). Keeps no reference to `body`.
    // regrid false: the body is not voxelized now, because the caller gives a new shadow grid next (set_shadow_grid,
    // which voxelizes it; online/scene/hair_motion.h, once per frame).
    void set_body(const BodyMesh* body, const glm::mat3& orientation = glm::mat3(1.0f), bool regrid = true);
    // Draws the body (set_body; none: nothing, returns 0) seen through `view`, lit by `lights` (world space), opaque over
    // the framebuffer bound for drawing, width × height at its origin; returns its depth texture, to pass to draw_frame as
    // the scene's depth (DepthTest::less_equal) with FrameTarget::over (coif view does). draw() and render() do this
    // themselves.
    std::uint32_t draw_body(const FrameView& view, int width, int height, std::span<const SrbfLight> lights);
    bool has_body() const;
    // Moves every cluster rigidly (motion: online/scene/hair_motion.h, online/hair_renderer.h's bone poses): transforms[c]
    // takes cluster c from where it was cooked to where it is now, in the shells' space (a rotation and a translation).
    // The instances and lighting samples are placed anew from their cooked copies; the grid's strands
    // (CookedShells::shadow_source) are moved with their clusters and voxelized again with the body (set_body) into a new
    // shadow grid; the shadows and the lighting pass follow on the next draw. A hair cooked without its grid's strands
    // keeps its grid (give one with set_shadow_grid). The SATF look-ups stay: a cluster that moves rigidly keeps its
    // density. Throws coif::Error::parameter for a count other than the clusters' or a transform that is not rigid.
    void set_cluster_transforms(std::span<const glm::mat4> transforms);
    struct MoveTimings {  // of the last set_cluster_transforms, wall-clock milliseconds
        double placement_ms = 0;    // the instances and lighting samples placed and uploaded
        double shadow_grid_ms = 0;  // the strands moved, voxelized with the body, uploaded
    };
    const MoveTimings& move_timings() const { return move_timings_; }
    // Replaces the hair's shadow grid (e.g. voxelized from the moved strands); a body (set_body) is voxelized into it anew.
    void set_shadow_grid(DensityGrid grid);
    // Draws into the bound framebuffer (cleared to the background first). `floor` draws the same
    // shells in the same order with a trivial shader (the floor of `coif bench render`).
    void draw(const Camera& camera, const ShellSettings& settings, bool floor = false);
    // Draws into the framebuffer bound for drawing as a host's frame wants it (online/hair_renderer.h is the host-facing
    // form): seen with `view` and `projection` (any), lit by `lights` (world space), within target.viewport, clearing
    // nothing; with target.over the hair is blended over what is there, and with a scene depth texture the fragments
    // behind the scene are discarded. `instances`: world-from-hair transforms (rotation, translation, uniform scale;
    // empty: the identity), all composited together (the exact compositing sorts the fragments of every instance).
    // Each instance keeps its own lights turned into the hair's space and their shadows, rerun only when they change.
    // Throws coif::Error::parameter for a bad setting, viewport or transform.
    void draw_frame(const glm::mat4& view, const glm::mat4& projection, std::span<const SrbfLight> lights,
                    const ShellSettings& settings, const FrameTarget& target, std::span<const glm::mat4> instances = {});
    // Renders into an offscreen target of the camera's size and returns the linear RGBA image; the exact and weighted
    // compositings with samples > 1 average f² frames, f = round(√samples), shifted to the pixel centres of
    // an f-times finer grid (supersampling with a box filter, at one frame's memory). The lighting pass runs for the
    // first frame only: the others have the same eye, lights and settings (timings().lighting_wall_ms is that pass). An exact frame that
    // overflows its fragment storage is drawn again with the storage grown; one that still overflows (the GPU's
    // storage-block limit) is drawn in tiles (timings().tiles), and a tile that overflows throws coif::Error::parameter:
    // never an image with holes.
    Image render(const Camera& camera, const ShellSettings& settings);
    // Every shell fragment of this view (the exact compositing's lists, single sample; `settings`'
    // compositing and samples are ignored), drawn again with more storage if the first try overflowed.
    // `resolved`, if given, receives the GPU resolve of the same lists (Compositing::exact at 1 sample).
    FragmentCapture capture_fragments(const Camera& camera, const ShellSettings& settings, Image* resolved = nullptr);
    // The fragment lists' figures of the last draw with Compositing::exact (zero before any).
    FragmentListStats fragment_list_stats() const;
    // Holds the exact compositing's fragment storage to `nodes` (tests: render()'s tiles without a huge image).
    void limit_fragment_storage(std::uint64_t nodes);

    const ShellStats& stats() const { return stats_; }
    // OwnClusterDepth of the hair as it stands (its samples and shadow grid move together), measured on each call:
    // one march across every lighting sample, for whoever reports it (coif render), not at every set_hair.
    OwnClusterDepth own_cluster_depth() const;
    // The RMS tangent spread (radians) the lighting uses with `settings`: settings.tangent_spread when ≥ 0, else
    // the RMS of the style's measured tilts, stats().tangent_spread.
    float tangent_spread(const ShellSettings& settings) const {
        return settings.tangent_spread >= 0.0f ? settings.tangent_spread : stats_.tangent_spread;
    }
    // The fibre radius the shadows between clusters count with `settings`: settings.fiber_radius when > 0, else
    // stats().auto_fiber_radius.
    float fiber_radius(const ShellSettings& settings) const {
        return settings.fiber_radius > 0.0f ? settings.fiber_radius : stats_.auto_fiber_radius;
    }
    // The lighting pass's output of the last draw: per cluster, per lighting row, the 27 sums
    // (C_0, C_1, S_1, …, C_4, S_4, RGB each) — for tests against the CPU evaluator. The rows the pass did not light
    // (ShellSettings::lighting_step, lod_lighting) hold what they held before.
    std::vector<float> read_lighting() const;
    // Each fibre tangent's sums alone to the second harmonic, in luminance and on C_0's scale, per cluster and lighting
    // row (as read_lighting): lum(C_0), lum(C_1), lum(S_1), lum(C_2), lum(S_2), each a vec4 of the four tangents.
    std::vector<std::array<glm::vec4, 5>> read_tangent_harmonics() const;
    // The lights' hot spot per cluster and lighting row (as read_lighting): Σ_j h_j w_j, which the other sums leave out
    // (ShellSettings::hot_spot; zero without it).
    std::vector<glm::vec3> read_hot_spot() const;
    // The lights that the lighting pass of the last draw lit at each sample it lit (ShellSettings::light_cull skips
    // some; ShellTimings::lighting_step and the clusters' levels of detail say which samples were lit, shell_passes.h
    // lit_samples): cluster by cluster, along each.
    std::vector<int> read_lights_lit() const;
    double mean_lights_lit() const;  // their mean (0 when none was lit)
    int lighting_rows() const;
    // The shadow pass's output of the last draw that ran it: (T̃, n) per lighting sample (cluster-major,
    // as lighting_sample) and light.
    std::vector<glm::vec2> read_shadows() const;
    // The same pass's own cluster's depth toward the hair's inside per lighting sample (shaders/gl/shell_shadow.comp
    // inner_depth): weight · fibres per radius across the cluster toward the hair's outside · that direction.
    std::vector<glm::vec3> read_inner_depths() const;
    // Key light m's shadow volume (ShellSettings::key_lights) as the last draw made it: the fibres met toward the light
    // per voxel (x fastest), its dimensions, the shells' space → texture coordinates map and the light's index; empty
    // values when there is no such key light.
    struct KeyVolume {
        std::vector<float> fibres;
        glm::ivec3 dims{0};
        glm::mat4 frame{1.0f};
        int light = -1;
    };
    KeyVolume read_key_volume(int m) const;
    // The lighting samples (world position, tangent, frame normal r0) in cluster-major order.
    std::vector<glm::vec3> lighting_sample(std::size_t index) const;
    const ShellTimings& timings() const { return timings_; }
    // Forgets the levels of detail drawn so far (ShellSettings::lod_pixels' hysteresis): the next frame picks them as
    // render() does, as if nothing had been drawn before. A viewer calls it when the view comes to rest, so that its
    // still picture is coif render's.
    void forget_detail();
    // The CPU-side preparation the GPU copy was made from (online/shells/prepared_shells.h).
    const PreparedShells& prepared() const;
    // Bounds of the placed outer layers (world, oriented).
    glm::vec3 bounds_min() const { return bounds_min_; }
    glm::vec3 bounds_max() const { return bounds_max_; }

private:
    void passes(const FrameView& view, const ShellDraw& d, const ShellSettings& s, bool floor);
    void finish_frame(const ShellSettings& s, bool floor);
    // draw()'s frame of any view: cleared to the background, drawn, finished (width × height at the origin).
    void draw_view(const FrameView& view, int width, int height, glm::vec2 jitter, const ShellSettings& s, bool floor);
    Image render_tiles(const Camera& camera, const ShellSettings& settings);  // render()'s frame beyond the storage
    void upload_grid();  // the shadow grid with the body in it (set_body, set_shadow_grid), and its figures in stats_
    struct Impl;
    std::unique_ptr<Impl> impl_;
    ShellStats stats_;
    ShellTimings timings_;
    MoveTimings move_timings_;
    glm::vec3 bounds_min_{0}, bounds_max_{0};
};

// One scattering term of `coif render --aovs` (shells/shell_settings.h scattering_aovs): the render of aov.with, less
// that of aov.without where it has one, in RGB (the two have the same coverage, so alpha is kept).
Image render_aov(ShellRenderer& renderer, const Camera& camera, const ScatteringAov& aov);

}  // namespace coif::gl
