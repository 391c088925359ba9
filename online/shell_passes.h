#pragma once
// The shell renderer's GPU half (online/shell_renderer.h is the facade): the GPU copy of a prepared hairstyle
// and the passes that draw it, each with its own programs and uniforms.
//   ShellGpu      the buffers and textures of online/shells/prepared_shells.h, record_atlas.h and shadow_grid.h,
//                 the lights and their shadows, the lighting pass's output, the painted absorption;
//   ShadowPass    T̃, n per lighting sample and light, marched through the density grid (decision 5,
//                 shaders/gl/shell_shadow.comp); run only when the lights or the fibre radius change;
//   LightingPass  the SRBF lighting per lighting sample folded into the 9 Fourier sums of decision 1
//                 (shaders/gl/shell_lighting.comp);
//   ShellsPass    every cluster's layers, blended (sorted, unsorted) or appended to the fragment lists and
//                 resolved (exact; online/fragment_lists.h), with the shading compiled per variant.
#include <array>
#include <chrono>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "models/core/camera.h"
#include "models/absorption_map.h"
#include "online/fragment_lists.h"
#include "online/frame.h"
#include "online/gl.h"
#include "online/lighting_uniforms.h"
#include "online/shells/prepared_shells.h"
#include "online/shells/record_atlas.h"
#include "online/shells/shadow_grid.h"
#include "online/shells/shell_lod.h"
#include "online/shells/shell_settings.h"
#include "online/weighted_blend.h"

namespace coif::gl {

// Wall-clock milliseconds since t0 (the passes' timings, ShellSettings::timed).
inline double wall_ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// RGBA texels per lighting sample: the 27 floats C_k, S_k, V, the own cluster's stretch and the lights lit in 8, then each
// fibre tangent's lum(C_0), then the fibres' forward loss 1 − ā_f, then each tangent's lum(C_1), lum(S_1), lum(C_2),
// lum(S_2), then three per key light (its light unshadowed, its forward-scattered light, its forward loss)
// (shaders/gl/shell_lighting.comp; the shaders' LIGHTING_TEXELS).
inline constexpr int kLightingTexels = 16 + 3 * kMaxKeyLights;
// The lights' hot spot (ShellSettings::hot_spot): its RGB sum, then each fibre tangent's share in luminance (the
// shaders' LIGHTING_HOT_TEXEL and the one after it).
inline constexpr int kHotSpotTexel = 14 + 3 * kMaxKeyLights;
// The most lights the lighting pass culls per sample (ShellSettings::light_cull): it keeps each light's estimate and
// the lights kept in arrays of the light count, per sample; with more lights it lights every one.
inline constexpr int kMaxCulledLights = 128;
inline constexpr int kShadowRays = 7;      // rays per SRBF lobe in the shadow pass (7 equal shares of its energy)
// Texture units: 0 the record atlas, 1 the lighting sums, 2 … 1 + kLutCount the lighting tables, then the painted
// absorption, then the host scene's depth (shaders/gl/scene_depth.glsl).
inline constexpr int kSceneDepthUnit = 3 + shading::kLutCount;

// The lighting pass's sums of `clusters` clusters of `rows` lighting samples (ShellGpu::lighting), cleared to 0: a
// sample the pass skips (lit_samples) holds a finite value, which a bilinear read beside a lit one weighs by 0.
Texture make_lighting_texture(int rows, std::size_t clusters);

// The key lights of ShellSettings::key_lights and their shadow volumes (KeyLightPass): the brightest lights
// (key_light_indices), each lit apart with the fibres met toward it from each vertex of the shells (each fragment on the
// per-fragment path), read from a volume aligned with the light, instead of through the lighting pass's sums with the
// shadow of the cluster's axis.
struct KeyLightVolumes {
    int count = 0;
    std::array<int, kMaxKeyLights> index{};           // in the lights buffer
    std::array<glm::vec4, kMaxKeyLights> light{};     // unit direction toward the light, λ
    std::array<glm::mat4, kMaxKeyLights> frame{};     // shells' space → the volume's texture coordinates
    std::array<Texture, kMaxKeyLights> volume;        // R16F: the fibres met toward the light (n, with the body's depth)
    std::array<glm::ivec3, kMaxKeyLights> dims{};
    // What they were made from: the lights, the fine grid, the fibres' diameter, the count asked for.
    bool valid = false;
    std::uint64_t lights_stamp = 0, grid_stamp = 0;
    float width = 0.0f;
    int wanted = 0;
};

// The `count` lights of most energy, |lum(L_j)| ∫G_j dω (shaders/envmap.glsl srbf_integral), brightest first; ties by
// index. Throws coif::Error::parameter unless 0 ≤ count ≤ kMaxKeyLights.
std::vector<int> key_light_indices(std::span<const SrbfLight> lights, int count);

struct ShellGpu {
    // Needs a current GL 4.5 context; throws coif::Error if the atlas exceeds the GPU's texture size.
    ShellGpu(const PreparedShells& shells, const RecordAtlas& atlas, const DensityGrid& grid, const std::string& db_path);

    DiskLayout layout;
    // The layer meshes at each level of detail (online/shells/shell_lod.h): their ranges in `indices`, and the outer
    // layers' longest edges.
    std::vector<std::vector<std::array<MeshRange, kLodLevels>>> lod_ranges;  // [slot][layer][level]
    std::vector<std::array<float, kLodLevels>> lod_edge;                     // [slot][level], prototype coordinates
    VertexArray vao;
    Buffer vertices, indices, cluster_ids, instances, sectors, samples;
    std::size_t sample_count = 0, clusters = 0;
    int lighting_rows = 0;
    Texture atlas;  // RGBA8 (online/shells/record_atlas.h)
    int atlas_width = 1, atlas_height = 1, tiles_per_row = 1, views = 0, hrir_length = 0;
    std::array<glm::vec4, kAtlasParts> atlas_lo{}, atlas_scale{};
    float re_norm = 1;
    Texture density, density_off;  // the shadow grid's M: RGBA32F (xx, yy, zz, xy), RG32F (xz, yz); zero outside
    glm::vec3 grid_origin{0.0f}, grid_extent{0.0f};
    float voxel = 1;
    Texture lighting;  // RGBA32F, lighting_rows × clusters · kLightingTexels: the lighting pass's sums
    // shaders/gl/srbf_lights.glsl lights; (T̃, n) per sample and light, then per sample the own cluster's depth toward
    // the hair's inside as two vec2 (shaders/gl/shell_shadow.comp inner_depth)
    Buffer lights, shadows;
    int light_count = 0;
    std::vector<SrbfLight> light_values;  // what `lights` holds
    Texture absorption;  // RGBA32F σa per (lighting row, cluster), when absorption_on
    bool absorption_on = false;
    Texture body;        // R8 on the shadow grid: a character's body as an occluder (voxelize_body), when body_on
    bool body_on = false;
    // The fine grid of the key lights' shadow volumes (kKeyLightGridSize; set_key_grid), the same M as `density`.
    Texture key_density, key_density_off;
    glm::vec3 key_grid_origin{0.0f}, key_grid_extent{0.0f};
    float key_voxel = 1;
    std::uint64_t grid_stamp = 0;  // changed by set_grid, set_body and set_key_grid
    KeyLightVolumes key_lights;     // with the lights: swapped with them per instance (online/shell_renderer.cpp)
    // Changed by set_lights and set_absorption, each to a number never used before: what the lighting pass's sums
    // were made from (LightingKey).
    std::uint64_t lights_stamp = 0, absorption_stamp = 0;
    std::uint64_t geometry_stamp = 0;  // changed by set_placement: the clusters moved

    // New placements of the clusters: their instances and lighting samples (the counts of the constructor's).
    void set_placement(std::span<const ShellInstance> instances, std::span<const LightingSample> samples);
    void set_lights(std::span<const SrbfLight> lights);
    void set_absorption(const AbsorptionMap* map);
    // Uploads the shadow grid (the constructor's, or one extended to hold a body).
    void set_grid(const DensityGrid& grid);
    // The body's voxels on the shadow grid (voxelize_body), or empty: no body.
    void set_body(const std::vector<std::uint8_t>& occupancy, glm::ivec3 dims);
    // Uploads the key lights' fine grid.
    void set_key_grid(const DensityGrid& grid);
};

// The key lights that the passes light apart for settings `s`: with shadows on, gpu.key_lights' count when they were
// made for s.key_lights (KeyLightPass::run), else 0.
int key_lights(const ShellGpu& gpu, const ShellSettings& s);

// The key lights' shadow volumes (shaders/gl/shell_key_light.comp): for each of the `count` brightest lights, the fibres
// met from every point toward its centre direction, through the fine grid (ShellGpu::set_key_grid) and the body, on a
// grid aligned with the light with the fine grid's voxel (at most kKeyLightVolumeMax voxels along each axis).
// Remade only when the lights, the grids, the fibres' diameter or the count change; returns its wall time in ms (0 when
// it kept them).
inline constexpr int kKeyLightVolumeMax = 192;
class KeyLightPass {
public:
    double run(ShellGpu& gpu, int count, float fibre_width);

private:
    Program program_{{"shaders/gl/shell_key_light.comp"}};
    std::unique_ptr<Program> with_body_;
};

class ShadowPass {
public:
    // Writes gpu.shadows; returns its wall time in ms (glFinish before and after: it runs only when the lights
    // change, so the synchronisation costs nothing per frame, and llvmpipe's timer queries miss this dispatch).
    // fibre_width: the fibres' diameter 2r, so that τ = 2r ∫ projected length density is the fibres met. Rays
    // start outside the own cluster: its share is each fragment's own (shaders/lighting/own_cluster.glsl).
    // lit_step: the lighting pass's step along each cluster's samples (lit_rows): only those samples are marched, and
    // the ones between get their neighbours' linear interpolation (a second, cheap dispatch).
    // narrow_start: rays start at most the own cluster's narrow half-axis out (ShellSettings::shadow_neighbours).
    // outward: the share of the cluster's radius the rays start from its axis toward the hair's outside
    // (ShellSettings::shadow_outward). inner: also write each sample's own cluster's depth toward the hair's inside after
    // the (T̃, n) (ShellGpu::shadows; ShellSettings::own_cluster_inner), else zeros there.
    double run(const ShellGpu& gpu, float fibre_width, int lit_step = 1, bool narrow_start = false, float outward = 0.0f,
               bool inner = false) const;

private:
    Program program_{{"shaders/gl/shell_shadow.comp"}};
    mutable std::unique_ptr<Program> fill_;       // the second dispatch of a step > 1 (made on first use)
    mutable std::unique_ptr<Program> with_body_;  // the variant that also marches a body (made on first use)
};

// What a lighting pass's sums are a function of: the hair's parameters, the settings the pass reads, the eye (in the
// shells' space), the lights and the painted absorption (their stamps); the shadows are the lights' (the renderer
// clears the key when the shadow pass reruns). Equal keys give bit-identical sums.
struct LightingKey {
    bool valid = false;
    shading::HairParameters hair;
    bool shadows = false;
    float own_inner = 0.0f;  // ShellSettings::own_cluster_inner where own_cluster_shadow, else 0
    float tangent_spread = 0.0f;
    int step = 1;
    float light_cull = 0.0f;
    int key_lights = 0;
    int hot_spot = 0;  // hot_spot_variant
    glm::vec3 eye{0.0f};
    std::uint64_t lights_stamp = 0, absorption_stamp = 0, geometry_stamp = 0;
    std::vector<int> strides;  // per cluster: every strides-th of its rows lit (lit_strides: its level of detail's)
};

// The lighting samples lit per cluster when every `step`-th of its `rows` is (ShellSettings::lighting_step): the first,
// every step-th after it, and the last. Throws coif::Error::parameter unless step divides rows - 1.
int lit_rows(int rows, int step);
// Per cluster, the stride along t of its mesh at its level of detail (shells/shell_lod.h lod_row_stride; 1 without
// `levels`): the rows its vertices read the lighting sums at.
std::vector<int> lit_strides(const ShellGpu& gpu, std::span<const int> levels);
// The samples the lighting pass lights, as (cluster, k) for the k-th of the cluster's lit_rows(rows, step): those on its
// stride, and the last.
std::vector<glm::ivec2> lit_samples(int rows, int step, std::span<const int> strides);

class LightingPass {
public:
    // Writes gpu.lighting for `eye` (in the shells' space), unless `key` says that it holds the sums of these
    // inputs already (and s.reuse_lighting): then it returns false and does nothing. `key` becomes these inputs'.
    // `levels`: the clusters' levels of detail, when the shells read the sums per vertex (ShellSettings::lod_lighting):
    // only the samples their meshes read are lit (lit_samples); empty lights every one.
    bool run(const ShellGpu& gpu, const ShellSettings& s, const glm::vec3& eye, LightingKey& key,
             std::span<const int> levels = {});
    // The uniforms and bindings that the lighting pass and the per-fragment lighting reference
    // (ShellSettings::lighting_per_fragment) read: the tables, the parameters, the lights, their shadows, σa.
    void bind_inputs(const Program& program, const ShellGpu& gpu, const ShellSettings& s) const;
    // The lighting module's tables alone, on units 2 … 1 + kLutCount (the shells read lut_own_cluster).
    void bind_tables(const Program& program) const;

    // The SHELL_TANGENTS define of the programs that light fibres (shell_light.glsl): 1 when s.tangent_spread is 0.
    static std::string tangents_define(const ShellSettings& s);
    // The lighting's compile-time variant: srbf_variant_defines of the settings' hair and the tangents_define.
    static std::vector<std::string> variant_defines(const ShellSettings& s);
    // Whether the shells light each strip of a sector at one fibre tangent (ShellSettings::tilt_per_strip, with four).
    static bool tilt_pick(const ShellSettings& s);

private:
    std::map<std::string, std::unique_ptr<Program>> programs_;  // by variant_defines, made on first use
    LightingTextures tables_;  // the lighting module's tables (online/lighting_uniforms.h)
};

// One draw of the shells within a frame (ShellsPass::draw): the target, and for the exact and weighted compositings,
// whether this draw begins the frame's fragment lists (or weighted sums) and whether it ends them (resolves them into the
// target); several draws (the instances of the hair) between share one set and so composite with each other.
struct ShellDraw {
    FrameTarget target;
    bool first = true, last = true;
    float distance_scale = 1.0f;  // world units per unit of the shells' space (the instance's scale)
    glm::vec2 jitter{0.0f};       // sub-pixel shift of the image, pixels (x right, y down)
    // The clusters' levels of detail (ShellSettings::lod_pixels): `levels`, the hysteresis state of this hair instance
    // (null: the pass's own), picked anew from this view (follow), picked as if nothing had been drawn before (fresh:
    // ShellRenderer::render's first frame, so that an image does not depend on what was drawn before it), or drawn as
    // they are (hold: render()'s other frames and tiles, so that all its frames draw the same meshes).
    enum class Detail { follow, fresh, hold };
    Detail detail = Detail::follow;
    std::vector<int>* levels = nullptr;
    // The k-buffer compositing draws every instance of a frame twice: first their depths into its slots (depth), then
    // shaded (shade); `first` begins the frame in the depth pass and `last` resolves it in the shading pass. The other
    // compositings draw once (all).
    enum class Phase { all, depth, shade };
    Phase phase = Phase::all;
};

class ShellsPass {
public:
    // Draws the shells seen from `view` into the framebuffer bound for drawing (exact compositing: into the fragment
    // lists; weighted: into the weighted sums; either resolved into that framebuffer by the draw marked `last`).
    // `floor`: the same shells in the same order with a trivial shader (coif bench render's floor). Returns the
    // resolve's wall time in ms with s.timed and exact or weighted compositing, else 0.
    double draw(const ShellGpu& gpu, const PreparedShells& shells, const FrameView& view, const ShellDraw& d,
                const ShellSettings& s, bool floor, const LightingPass& lighting);
    // The exact compositing's lists (made on first use), or null before.
    FragmentLists* lists() const { return lists_.get(); }
    // The exact compositing's lists, made now if they were not.
    FragmentLists& make_lists();
    // Clusters drawn by the last draw (those in the view, with ShellSettings::cull).
    std::size_t clusters_drawn() const { return drawn_; }
    // Of those, how many at each level of detail (ShellSettings::lod_pixels), and the triangles drawn (both faces).
    const std::array<std::size_t, kLodLevels>& clusters_at_level() const { return at_level_; }
    std::size_t triangles_drawn() const { return triangles_; }
    void forget_levels() { level_.clear(); }
    // The clusters' levels of detail for draw `d` (its ShellDraw::levels, or the pass's own): picked from `view` as
    // d.detail says (held in the k-buffer's shading pass), or all 0 without a level of detail. draw() calls it; a caller
    // that needs the levels before drawing (the lighting pass) calls it first and draws with Detail::hold.
    std::vector<int>& choose_levels(const ShellGpu& gpu, const PreparedShells& shells, const FrameView& view,
                                    const ShellDraw& d, const ShellSettings& s, bool floor_only);
    // Where the shells read the lighting pass's sums (SHELL_LIGHTING, shaders/gl/shell_shade.glsl): 2 every light per
    // fragment, 1 per vertex (the lighting rows are the mesh rows), 0 per fragment between the rows.
    static int lighting_read(const ShellSettings& s, int lighting_rows, const DiskLayout& layout);
    // What the pass keeps of the shells it drew (their prototypes' boxes, the levels of detail): forgotten when the
    // renderer is given another hair (ShellRenderer::set_hair), whose meshes may differ with the same counts.
    void forget_shells() {
        prototype_boxes_.clear();
        level_.clear();
    }

private:
    // level_ for a frame seen from `view`, `height` pixels high, each cluster's box `boxes` (ShellSettings::lod_pixels).
    void pick_levels(const ShellGpu& gpu, const PreparedShells& shells, const FrameView& view, std::span<const ClusterBox> boxes,
                     int height, float budget_px, std::vector<int>& levels) const;
    // `fold`: the program that draws two layers from the outer one's mesh (ShellSettings::fold_level).
    // `keys`: the key lights lit apart, with their shadow volumes (key_lights).
    const Program& shading_program(Compositing mode, const ShellSettings& s, int lighting_rows, const DiskLayout& layout,
                                   DepthTest depth, int keys, bool fold = false);
    Program floor_{{"shaders/gl/shell.vert", "shaders/gl/shell_floor.frag"}};
    std::map<std::string, std::unique_ptr<Program>> depth_programs_;  // the k-buffer's depth pass, by its defines
    std::map<std::string, std::unique_ptr<Program>> programs_;  // one per compile-time variant, made on first use
    std::unique_ptr<FragmentLists> lists_;
    std::unique_ptr<WeightedBlend> weighted_;  // the weighted compositing's targets (made on first use)
    GLint target_framebuffer_ = 0;  // the exact and weighted compositings': bound when their first draw began
    std::size_t drawn_ = 0, triangles_ = 0;
    std::array<std::size_t, kLodLevels> at_level_{};
    // Each cluster's level of detail, drawn last (pick_lod's hysteresis), when a draw brings no state of its own
    // (ShellDraw::levels). A draw without level of detail (the floor, lod_pixels 0) draws level 0 and keeps these.
    std::vector<int> level_;
    std::vector<PrototypeBox> prototype_boxes_;  // of the shells drawn (their meshes do not change), made on first use
};

}  // namespace coif::gl
