#pragma once
// The shell renderer's settings (online/shell_renderer.h): the hair's scattering parameters, how the shells
// are shaded and composited, and the parameters file that `coif render --params` (and `coif reference
// --params`, `coif bench *`) read. GL-free.
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "models/core/camera.h"
#include "models/core/param_table.h"
#include "shaders/hair_parameters.h"

namespace coif::gl {

inline constexpr int kMaxShellNeighbours = 4;  // records per sector kept for the GPU
inline constexpr int kMaxKBufferSlots = 16;    // ShellSettings::kbuffer_slots
inline constexpr int kMaxKeyLights = 4;        // ShellSettings::key_lights

// How the shells are composited (docs/renderer.md decision 4): sorted (clusters back to front, blended), unsorted (blended
// in the style's order), exact (per-pixel fragment lists, sorted), weighted (weighted blended order-independent
// transparency: bounded memory, online/weighted_blend.h), kbuffer (the nearest ShellSettings::kbuffer_slots fragments of
// each pixel composited exactly, the ones behind them weighted-blended: bounded memory). New modes go at the end: the
// enum's value is the parameters table's choice index.
enum class Compositing { sorted, unsorted, exact, weighted, kbuffer };
const char* compositing_name(Compositing c);
std::vector<std::string> compositing_names();  // every mode's, in the enum's order (command lines' choices)
// "sorted" | "unsorted" | "exact" | "weighted" | "kbuffer"; anything else throws coif::Error(file, place, …).
Compositing parse_compositing(const std::string& text, const std::string& file, const std::string& place);

struct ShellSettings {
    shading::HairParameters hair;   // the scattering parameters (shaders/hair_parameters.h)
    bool shadows = true;            // shadows between clusters (T̃, n per lighting sample and light)
    // The own cluster shades each of its fibres by the fibre's side toward the light (shaders/lighting/own_cluster.glsl;
    // false: not at all). Shadows between clusters start outside the own cluster either way.
    bool own_cluster_shadow = true;
    // With own_cluster_shadow, the light that the own cluster's fibres scatter forward reaches the fibres behind them, as
    // between clusters (shaders/lighting/own_cluster.glsl own_cluster_forward_series; false: the unscattered light only).
    // It is multiple scattering, so it goes with it: off where hair.multiple is false (own_cluster_variant).
    bool own_cluster_forward = true;
    // The shadows between clusters start at most the own cluster's narrow half-axis out (times the ray's stretch), so
    // that they count the neighbouring clusters whose fibres overlap its ellipse (false: where the ray leaves the
    // ellipse; shaders/gl/shell_shadow.comp).
    bool shadow_neighbours = true;
    // The shadows between clusters are taken on the cluster's outer side, where the camera sees its fibres: each lighting
    // sample's rays start this share of the cluster's radius from its axis toward the hair's outside (down the strands'
    // density gradient, across the axis), not at the axis (0). At the crown, a light that grazes the hair crosses far
    // fewer fibres on the way to the outermost ones than on the way to the axis (docs/quality.md, "The shadows on the
    // cluster's outer side"; shaders/gl/shell_shadow.comp).
    // 1 by the sweeps with the records' thinning and the lights' hot spot (docs/quality.md, "The records thinned to their
    // sectors' density, and the lights' hot spot").
    float shadow_outward = 1.0f;
    // With own_cluster_shadow and shadows, the own cluster's side toward the hair's inside is shaded through the whole
    // cluster as the shadow grid counts it: its optical depth per radius is at least this share of the grid's fibres
    // across the cluster toward the hair's outside (shaders/gl/shell_shadow.comp inner_depth, weighed by how clearly the
    // hair has an outside there and by the cosine of the fragment's side to the inside), where the records' coverage
    // Σ ᾱ undercounts a cluster that light from outside crosses whole. 0: Σ ᾱ alone on every side, the image before it.
    // 2 by the sweeps (docs/quality.md, "The cluster's side toward the hair's inside": 1 to 4 measured).
    float own_cluster_inner = 2.0f;
    // Radius (scene units) of the fibres that the shadows between clusters count (online/shells/shadow_grid.h);
    // 0: coif reference's auto radius of the same strands (models/strands.h auto_fiber_radius), so that both
    // renderers' fibres block the same light.
    float fiber_radius = 0.0f;
    // 004 eq. 12's κ_shadow (per unit of summed α): the own cluster's optical depth per unit of its layers' Σ ᾱ,
    // toward each light with own_cluster_shadow (1: the small-α limit of Beer–Lambert; docs/quality.md measures
    // 0.5–2), from outside only without it.
    float kappa_shadow = 1.0f;
    // The fibres' tangents about their cluster's axis (shaders/lighting/fibre_tangents.glsl): < 0, the style's
    // own tilts, measured from its strands at every lighting sample (ShellStats::tangent_spread is their RMS);
    // > 0, a ring of this RMS angle (radians) instead; 0 lights every fibre as if it lay along the axis.
    float tangent_spread = -1.0f;
    // With four tangents (tangent_spread ≠ 0), each strip of a sector (16 across it) is lit as one fibre at one of them,
    // drawn by a stable hash, instead of every fibre at their mean: the highlights' fibre-to-fibre contrast
    // (shaders/gl/shell_shade.glsl SHELL_TILT_PICK; docs/quality.md, "One tangent per strip").
    bool tilt_per_strip = true;
    // Each of those strips takes the records of one of its HSV's two sectors, the bottom one where γ (the position along
    // t across the HSV) passes a stable hash's threshold, instead of both sectors' records mixed by γ (004 eq. 7), which
    // averages two fibre patterns into a fainter one; it reads one sector's records instead of two
    // (shaders/gl/shell_shade.glsl SHELL_SECTOR_PICK; docs/quality.md, "One sector's records per strip").
    bool sector_per_strip = true;
    // Records blended per sector on the GPU, 1..kMaxShellNeighbours: 1 draws the nearest record alone, which keeps its
    // fibres' contrast; docs/quality.md ("Fibre detail") chose it by the detail ratio and the blurred PSNR against coif
    // reference.
    int neighbours = 1;
    int fourier_order = 2;          // harmonics of re in θl used, 0..4 (the db stores 4; 2: 53 dB against 4, a third fewer fetches; docs/renderer.md;
                                    // 0: a0 alone, docs/quality.md "re's dependence on the light is the tracer's Phong")
    glm::vec3 background = kDefaultBackground;  // linear RGB behind the hair
    int samples = 4;                // per pixel: MSAA samples (sorted, unsorted); exact, weighted: render() averages round(√samples)² shifted frames
    Compositing compositing = Compositing::exact;  // decision 4 (docs/renderer.md)
    int debug = 0;                  // 0 shaded, 1 α only, 2 unlit re·τ, 3 lighting C_0 · α (no re), 4 shadow AOV,
                                    // 5 key light 0's transmittance over the layer's slab · α (1 · α without one),
                                    // 6 shaded with the key lights' volumes read as empty: their light unshadowed
    // Decision 3's reference: every light evaluated per fragment (its own T, V and radial axis, re at each
    // light's own azimuth; shadows interpolated between lighting samples) instead of the per-sample Fourier
    // sums. ~40× the shading cost: for error figures (docs/renderer.md), not for frames.
    bool lighting_per_fragment = false;
    bool timed = false;             // glFinish around each pass and wall-clock timings (benchmarks; see ShellTimings)
    // Skip the clusters whose bounding box lies outside the view (ShellTimings::clusters_drawn counts the others):
    // the image is the same; false draws every cluster (for tests).
    bool cull = true;
    // Keep the lighting pass's sums while nothing they depend on changed (the eye, the lights, the hair's parameters,
    // the painted absorption: online/shell_passes.h LightingKey), so a still view costs no lighting pass: bit-identical
    // to lighting again. false lights every frame (benchmarks: the cost of a frame whose view moved).
    bool reuse_lighting = true;
    // The lighting pass lights every k-th lighting sample along each cluster (the first and the last among them) and the
    // shells interpolate between those, k the largest step up to lighting_step that the style's curvature allows
    // (online/shells/prepared_shells.h lighting_step_within; a curled style keeps every sample): 1 lights all (4 per HSV
    // with the mesh rows), 2 half, 4 a quarter. It must divide the samples' intervals (32 for the default style's mesh).
    // docs/renderer.md ("Quality presets") measures the cost and the error.
    int lighting_step = 2;
    // Level of detail of the tessellation (online/shells/shell_lod.h): each cluster is drawn at the coarsest of
    // kLodLevels meshes whose longest triangle edge projects within this many pixels (with hysteresis); 0 draws the
    // full meshes. docs/renderer.md ("Level of detail") measures the cost and the error.
    float lod_pixels = 24.0f;
    // With a level of detail, the lighting pass lights only the samples that a cluster's mesh at its level reads (every
    // 2nd or 4th row along t, as the level joins them, when the sums are read per vertex): the image is the same. false
    // lights every sample whatever the levels (tests).
    bool lod_lighting = true;
    // The layer count's level of detail: clusters drawn at this level of detail or a coarser one draw their layers in
    // pairs, each pair from its outer layer's mesh, the fragment shading both layers with their own records (the inner
    // one where the view ray meets it) and compositing them (shell_shade.glsl SHELL_FOLD): half the triangles and
    // fragments. 3 (kLodLevels): never. With the weighted and k-buffer compositings only: in the exact lists a pair at one
    // depth moves the inner layer in front of other clusters' fibres that lie between the two (3 % darker seen from
    // behind). docs/renderer.md ("Level of detail") measures the cost and the error.
    int fold_level = 3;
    // Lights left out per lighting sample (shaders/gl/shell_lighting.comp): each light's share of the sample's light is
    // estimated by its power times what reaches the sample (T̃ and the forward-scattered share of the shadow pass), and
    // the dimmest lights whose estimates sum to at most this fraction of the sample's total are skipped; 0 lights every
    // light, and so do more than 128 lights (online/shell_passes.h kMaxCulledLights). docs/renderer.md ("Lights culled
    // per lighting sample") measures the cost and the error.
    float light_cull = 0.05f;
    // With own_cluster_shadow, each light but the key lights is split by h = max(0, l · v)^hot_spot (v toward the camera):
    // the share h is lit past the own cluster's factor with re's mean, the rest through it as before. Where a light
    // stands behind the camera, the fibres the camera sees through a cluster's gaps are lit through the same gaps, which
    // eq. 12's factor takes as independent of the view (shaders/gl/shell_lighting.comp SHELL_HOT_SPOT). 0: no split.
    // 4 by the detail ratio and the blurred PSNR against the reference, the sweeps alike (docs/quality.md, "The records
    // thinned to their sectors' density, and the lights' hot spot").
    int hot_spot = 4;
    // The brightest lights (by |lum(L_j)| times their solid angle), up to 4, lit with their own shadow: the fibres met
    // from each vertex of the shells toward the light (from each fragment with lighting_per_fragment), read from a
    // volume aligned with the light and made from a finer grid of the strands (online/shell_passes.h KeyLightPass),
    // instead of through the lighting pass's sums with the shadow marched from the cluster's axis and the own cluster's
    // factor. The rest stay in the sums. 0: none. The
    // volume follows the light's centre direction alone, where the shadow pass spreads 7 rays over its lobe: a wide
    // light's soft shadow is drawn as a narrow one's.
    // docs/quality.md ("Key lights") measures the image and the cost. A preset's choice: 1 but at `low`.
    int key_lights = 1;
    // The key lights light the records with re's mean a0 (false: re at the light's in-plane azimuth, whose dependence is
    // the database tracer's Phong shading: docs/quality.md, "re's dependence on the light is the tracer's Phong"): the
    // single-light sweep's 35 of 78 in the band with re's azimuth, 68 with its mean.
    bool key_re_mean = true;
    // Where a key light's shadow is read: each layer's slab points moved this many voxels of the key lights' fine grid
    // toward the camera (the side of the slab whose fibres the camera sees) and the volume read this many voxels toward
    // the light (the fibres a point's own slab puts between it and the light are its own cluster's, which the records'
    // coverage already shades). Both 0: at the slab's points. 1.3 and 0.65 by the sweeps (docs/quality.md, "The shadows
    // on the cluster's outer side" and "The records thinned to their sectors' density, and the lights' hot spot").
    float key_toward_camera = 1.3f;
    float key_toward_light = 0.65f;
    // The k-buffer compositing's slots per pixel (Compositing::kbuffer, online/weighted_blend.h): its k nearest fragments
    // are composited exactly, 1..kMaxKBufferSlots. docs/renderer.md ("Decision 4") measures the cost and the error.
    int kbuffer_slots = 8;
};
// Quality presets (issue 18): named sets of the choices that trade the image against time. `full` is the reference of
// the others: every lighting sample, the nearest record per sector, re to its second harmonic, the fibres' measured tangents,
// exact compositing. docs/renderer.md ("Quality presets") has each one's frame time and its error against full; the
// default (kDefaultQuality, ShellSettings' own values) is the fastest within blurred PSNR ≥ 35 dB, detail ratio in
// [0.9, 1.1] and radiance ratio in [0.97, 1.03] of full.
enum class Quality { low, medium, high, full };
struct QualityPreset {
    Quality quality;
    const char* name;
    const char* summary;  // in words, for --help
    Compositing compositing;
    int neighbours, fourier_order, lighting_step;
    bool one_tangent;  // light every fibre along its cluster's axis (tangent_spread 0) instead of the measured tilts
    float lod_pixels;  // ShellSettings::lod_pixels
    float light_cull;  // ShellSettings::light_cull
    int kbuffer_slots; // ShellSettings::kbuffer_slots (with the k-buffer compositing)
    int fold_level;    // ShellSettings::fold_level
    int key_lights;    // ShellSettings::key_lights
};
inline constexpr QualityPreset kQualityPresets[] = {
    {Quality::low, "low", "weighted blended compositing (bounded memory), one record per sector, re's first harmonic, a "
                          "quarter of the lighting samples where the clusters are smooth, fibres lit along the axis, "
                          "coarse meshes, layers drawn in pairs, the dimmest lights carrying 20 % of each sample's light skipped "
                          "(previews, dragging)",
     Compositing::weighted, 1, 1, 4, true, 48.0f, 0.2f, 8, 0, 0},
    {Quality::medium, "medium",
     "k-buffer compositing (the nearest 4 fragments of each pixel exact; bounded memory), one record per sector, re's "
     "first harmonic, a quarter of the lighting samples where the clusters are smooth, coarser meshes, layers drawn in "
     "pairs, the dimmest lights carrying 10 % of each sample's light skipped, the brightest light lit apart with its "
     "own shadow from each vertex",
     Compositing::kbuffer, 1, 1, 4, false, 32.0f, 0.1f, 4, 0, 1},
    {Quality::high, "high",
     "exact compositing, one record per sector, half the lighting samples where the clusters are smooth, meshes "
     "coarsened where they are small on screen, the dimmest lights carrying 5 % of each sample's light skipped, the "
     "brightest light lit apart with its own shadow from each vertex (the default)",
     Compositing::exact, 1, 2, 2, false, 24.0f, 0.05f, 8, 3, 1},
    {Quality::full, "full", "exact compositing, one record per sector, every lighting sample, full meshes, every light, the "
                            "brightest light lit apart with its own shadow from each vertex: the reference of the others",
     Compositing::exact, 1, 2, 1, false, 0.0f, 0.0f, 8, 3, 1},
};
inline constexpr Quality kDefaultQuality = Quality::high;
const QualityPreset& quality_preset(Quality q);
// The presets' names, in kQualityPresets' order (the command lines' and the parameters file's choices).
std::vector<std::string> quality_names();
// The preset named `text`; anything else throws coif::Error(file, place, …) listing the names.
Quality parse_quality(const std::string& text, const std::string& file, const std::string& place);
// Sets the preset's choices in `settings` (its other fields, the hair's among them, stay).
void apply_quality(ShellSettings& settings, Quality q);
// The preset whose choices `settings` has, if any.
std::optional<Quality> quality_of(const ShellSettings& settings);

// Whether a compositing draws into single-sample targets of its own (exact's lists, weighted's sums), which
// ShellRenderer::render antialiases by supersampling; the blended modes draw into the frame and use its MSAA.
inline bool draws_single_sample(Compositing c) {
    return c == Compositing::exact || c == Compositing::weighted || c == Compositing::kbuffer;
}
// The supersampling of ShellRenderer::render: f × f shifted frames per image, f = round(√samples) clamped to
// 1..4, for the exact and weighted compositings (the blended modes use MSAA: 1).
int supersampling(const ShellSettings& settings);

// `coif render --aovs`: each scattering term of `settings`' image alone, over black. A term is the render of `with`
// less that of `without` where it has one (online/shell_renderer.h render_aov; the coverage is the same): each lobe
// is its single scattering alone, and `multiple` is all that multiple scattering adds to the lobes (the dual
// scattering and the own cluster's forward-scattered light, which scatters the lobes' light: own_cluster_variant).
// So the terms add up to the image over black, up to each lobe's own max(·, 0) clamp.
struct ScatteringAov {
    std::string name;
    ShellSettings with;
    std::optional<ShellSettings> without;
};
std::vector<ScatteringAov> scattering_aovs(const ShellSettings& settings);

// The own cluster's shadow as the shells' shading takes it (shaders/gl/shell_shade.glsl SHELL_OWN): 0 none
// (own_cluster_shadow false), 2 with the light that its fibres scatter forward (own_cluster_forward, with multiple
// scattering on), 1 the unscattered light only. `coif reference --max-depth 1` has no forward-scattered light either.
int own_cluster_variant(const ShellSettings& settings);
// The lights' hot spot as the shells take it (ShellSettings::hot_spot; SHELL_HOT_SPOT): its exponent with the own
// cluster's shadow, which it is lit past, else 0.
int hot_spot_variant(const ShellSettings& settings);

// The parameters file: one JSON object, every key optional, read through shell_settings_table(): the hair's
// keys (shading::hair_parameter_table(), shaders/hair_parameters.h: eta, sigma_a, alpha_R_deg, …; degrees
// for angles), then the renderer's (kappa_shadow, neighbours, compositing, …). `coif render --help` lists
// every key with its meaning and range (params_help). Unknown keys, wrong types and out-of-range values
// throw coif::Error naming the file and the JSON path ("JSON /neighbours"); the hair is then validated as a
// whole (shading::validate). background, samples and timed are not in the file.
const ParamTable<ShellSettings>& shell_settings_table();  // the hair keys (lifted), then the renderer's
ShellSettings read_shell_settings(const std::string& path, ShellSettings base = {});
// The same from a parsed object (e.g. the defaults inside a hair asset, online/shells/hair_asset.h); `path` names
// its file in errors.
ShellSettings shell_settings_from_json(const nlohmann::json& j, const std::string& path, ShellSettings base = {});
// The file of `settings` (every key of the table; fiber_radius only when set, TT/TRT angles only where
// they differ from their links): read_shell_settings of it gives `settings` back, bar background, samples
// and timed. write_shell_settings writes it atomically.
nlohmann::ordered_json shell_settings_json(const ShellSettings& settings);
void write_shell_settings(const std::string& path, const ShellSettings& settings);

}  // namespace coif::gl
