#include "online/shells/shell_settings.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/atomic_file.h"
#include "models/core/error.h"

namespace coif::gl {

int own_cluster_variant(const ShellSettings& settings) {
    if (!settings.own_cluster_shadow) return 0;
    return settings.own_cluster_forward && settings.hair.multiple ? 2 : 1;
}

int hot_spot_variant(const ShellSettings& settings) { return own_cluster_variant(settings) != 0 ? settings.hot_spot : 0; }

std::vector<ScatteringAov> scattering_aovs(const ShellSettings& settings) {
    ShellSettings over_black = settings;
    over_black.background = glm::vec3(0.0f);
    over_black.debug = 0;
    std::vector<ScatteringAov> aovs;
    for (const shading::Lobe& lobe : shading::kLobes) {
        ShellSettings one = over_black;
        one.hair.lobes = lobe.bit;
        one.hair.multiple = false;
        aovs.push_back({lobe.name, one, std::nullopt});
    }
    ShellSettings with = over_black, without = over_black;
    with.hair.multiple = true;
    without.hair.multiple = false;
    aovs.push_back({"multiple", with, without});
    return aovs;
}

int supersampling(const ShellSettings& settings) {
    if (!draws_single_sample(settings.compositing)) return 1;
    return std::clamp(static_cast<int>(std::lround(std::sqrt(static_cast<double>(settings.samples)))), 1, 4);
}

namespace {
// Every compositing mode, in the enum's order (the parameters file's choice index is the enum's value).
constexpr Compositing kCompositings[] = {Compositing::sorted, Compositing::unsorted, Compositing::exact, Compositing::weighted,
                                         Compositing::kbuffer};
}  // namespace

const char* compositing_name(Compositing c) {
    switch (c) {
        case Compositing::sorted: return "sorted";
        case Compositing::unsorted: return "unsorted";
        case Compositing::exact: return "exact";
        case Compositing::weighted: return "weighted";
        case Compositing::kbuffer: return "kbuffer";
    }
    return "?";
}

std::vector<std::string> compositing_names() {
    std::vector<std::string> names;
    for (Compositing c : kCompositings) names.emplace_back(compositing_name(c));
    return names;
}

Compositing parse_compositing(const std::string& text, const std::string& file, const std::string& place) {
    for (Compositing c : kCompositings)
        if (text == compositing_name(c)) return c;
    throw Error(file, place, "'" + text + "' is not sorted, unsorted, exact, weighted or kbuffer");
}

const QualityPreset& quality_preset(Quality q) {
    for (const QualityPreset& p : kQualityPresets)
        if (p.quality == q) return p;
    throw Error::parameter("quality", "unknown preset");
}

std::vector<std::string> quality_names() {
    std::vector<std::string> names;
    for (const QualityPreset& p : kQualityPresets) names.emplace_back(p.name);
    return names;
}

Quality parse_quality(const std::string& text, const std::string& file, const std::string& place) {
    std::string names;
    for (const QualityPreset& p : kQualityPresets) {
        if (text == p.name) return p.quality;
        names += std::string(names.empty() ? "" : ", ") + p.name;
    }
    throw Error(file, place, "'" + text + "' is not a quality preset (" + names + ")");
}

namespace {
// The fields a preset sets (of a ShellSettings, const or not), in one place for setting and for comparing.
template <class Settings>
auto preset_choices(Settings& s) {
    return std::tie(s.compositing, s.neighbours, s.fourier_order, s.lighting_step, s.tangent_spread, s.lod_pixels, s.light_cull,
                    s.kbuffer_slots, s.fold_level, s.key_lights);
}
auto preset_choices(const QualityPreset& p) {
    return std::tuple(p.compositing, p.neighbours, p.fourier_order, p.lighting_step, p.one_tangent ? 0.0f : -1.0f, p.lod_pixels,
                      p.light_cull, p.kbuffer_slots, p.fold_level, p.key_lights);
}
}  // namespace

void apply_quality(ShellSettings& s, Quality q) { preset_choices(s) = preset_choices(quality_preset(q)); }

std::optional<Quality> quality_of(const ShellSettings& s) {
    for (const QualityPreset& p : kQualityPresets)
        if (preset_choices(s) == preset_choices(p)) return p.quality;
    return std::nullopt;
}

// ---- parameters file -------------------------------------------------------------------------------

namespace {

ParamTable<ShellSettings> make_table() {
    using S = ShellSettings;
    ParamTable<S> t = lift(shading::hair_parameter_table(), &S::hair);
    // First of the renderer's keys, so that the keys after it in the same file override its choices. Never written: a
    // file holds the choices themselves. "custom" (what the settings read back as when they match no preset) changes
    // nothing.
    Param<S> quality{"quality", ParamKind::choice, "", 0, 0, false,
                     "a preset of the choices below (compositing, neighbours, fourier_order, lighting_step, "
                     "tangent_spread_deg, lod_pixels, light_cull, kbuffer_slots, fold_level, key_lights); later keys override it",
                     {}, {}, {}, {}};
    quality.names = quality_names();
    quality.names.emplace_back("custom");
    quality.get = [](const S& s, int) {
        const std::optional<Quality> q = quality_of(s);
        return static_cast<double>(q ? static_cast<int>(*q) : static_cast<int>(std::size(kQualityPresets)));
    };
    quality.set = [](S& s, int, double v) {
        const int i = static_cast<int>(v);
        if (i >= 0 && i < static_cast<int>(std::size(kQualityPresets))) apply_quality(s, kQualityPresets[i].quality);
    };
    quality.written = [](const S&) { return false; };
    t.push_back(quality);
    t.push_back(real_param<S>("kappa_shadow", "per unit of summed alpha", 0.0, std::numeric_limits<double>::infinity(),
                              "004 eq. 12's within-cluster shadow kappa_shadow", [](auto& s) -> auto& { return s.kappa_shadow; }));
    t.push_back(int_param<S>("neighbours", 1, kMaxShellNeighbours, "records blended per sector on the GPU (1: the nearest alone)",
                             [](auto& s) -> auto& { return s.neighbours; }));
    t.push_back(int_param<S>("debug", 0, 6,
                             "0 shaded, 1 alpha only, 2 unlit re, 3 lighting C_0 alpha, 4 shadow AOV, 5 key light 0's "
                             "transmittance over the layer's slab times alpha (alpha where no key light is lit), 6 shaded with "
                             "the key lights unshadowed (what their shadow takes, beside 0)",
                             [](auto& s) -> auto& { return s.debug; }));
    Param<S> compositing{"compositing", ParamKind::choice, "", 0, 0, false,
                         "exact (per-pixel fragment lists), weighted (weighted blended, bounded memory), kbuffer (the nearest kbuffer_slots "
                         "fragments exact, the rest weighted blended; bounded memory), sorted (clusters back to front) or unsorted",
                         {}, {}, {}, {}};
    compositing.names = compositing_names();
    compositing.get = [](const S& s, int) { return static_cast<double>(s.compositing); };
    compositing.set = [](S& s, int, double v) { s.compositing = static_cast<Compositing>(static_cast<int>(v)); };
    t.push_back(compositing);
    t.push_back(bool_param<S>("shadows", "shadows between clusters", [](auto& s) -> auto& { return s.shadows; }));
    t.push_back(bool_param<S>("own_cluster_shadow", "the own cluster shades each fibre by its side toward the light",
                              [](auto& s) -> auto& { return s.own_cluster_shadow; }));
    t.push_back(bool_param<S>("own_cluster_forward",
                              "with own_cluster_shadow and multiple scattering, the light the own cluster's fibres scatter "
                              "forward reaches the fibres behind them (false: the unscattered light only)",
                              [](auto& s) -> auto& { return s.own_cluster_forward; }));
    t.push_back(bool_param<S>("shadow_neighbours",
                              "shadows between clusters start at the own cluster's narrow half-axis, counting the "
                              "neighbours that overlap its ellipse (false: where the ray leaves the ellipse)",
                              [](auto& s) -> auto& { return s.shadow_neighbours; }));
    t.push_back(real_param<S>("shadow_outward", "share of the cluster's radius", 0.0, 1.0,
                              "shadows between clusters start this far from each cluster's axis toward the hair's outside, "
                              "where the camera sees its fibres (0: at the axis)",
                              [](auto& s) -> auto& { return s.shadow_outward; }));
    t.push_back(real_param<S>("own_cluster_inner", "share of the grid's count", 0.0, 4.0,
                              "with own_cluster_shadow and shadows, each cluster's side toward the hair's inside takes at "
                              "least this share of the shadow grid's fibres across the cluster as its own shadow (0: the "
                              "layers' coverage alone)",
                              [](auto& s) -> auto& { return s.own_cluster_inner; }));
    Param<S> spread = real_param<S>("tangent_spread_deg", "deg", 0.0, 60.0,
                                    "RMS spread of fibre tangents about the cluster axes, lit as a ring of tangents (0: one; absent: the style's, measured)",
                                    [](auto& s) -> auto& { return s.tangent_spread; });
    spread.written = [](const S& s) { return s.tangent_spread >= 0.0f; };
    t.push_back(spread);
    t.push_back(bool_param<S>("tilt_per_strip",
                              "with four fibre tangents, each strip of a sector lit as one fibre at one of them (false: "
                              "every fibre at their mean)",
                              [](auto& s) -> auto& { return s.tilt_per_strip; }));
    t.push_back(bool_param<S>("sector_per_strip",
                              "each strip of a sector takes the records of one of its HSV's two sectors, drawn against "
                              "the position along t (false: both, mixed by it)",
                              [](auto& s) -> auto& { return s.sector_per_strip; }));
    Param<S> radius = real_param<S>("fiber_radius", "scene units", 0.0, 100.0,
                                    "radius of the fibres the shadows between clusters count (0 or absent: coif reference's "
                                    "auto radius, 1e-3 of the strands' bounding-box diagonal)",
                                    [](auto& s) -> auto& { return s.fiber_radius; });
    radius.written = [](const S& s) { return s.fiber_radius > 0.0f; };
    t.push_back(radius);
    t.push_back(bool_param<S>("lighting_per_fragment", "every light per fragment (decision 3's reference; ~40x slower)",
                              [](auto& s) -> auto& { return s.lighting_per_fragment; }));
    t.push_back(int_param<S>("fourier_order", 0, 4,
                             "harmonics of re in theta_l used (0: re's light-independent mean a0 alone, no dependence on "
                             "the light's azimuth about the cluster)",
                             [](auto& s) -> auto& { return s.fourier_order; }));
    t.push_back(int_param<S>("lighting_step", 1, 32,
                             "light every k-th lighting sample along a cluster, interpolate between (must divide the "
                             "samples' intervals: 1, 2, 4 ... for the default mesh)",
                             [](auto& s) -> auto& { return s.lighting_step; }));
    t.push_back(real_param<S>("lod_pixels", "px", 0.0, 1024.0,
                              "level of detail: draw each cluster with the coarsest mesh whose triangles' edges project "
                              "within this many pixels (0: full meshes)",
                              [](auto& s) -> auto& { return s.lod_pixels; }));
    t.push_back(int_param<S>("fold_level", 0, 3,
                             "clusters at this level of detail or coarser draw their layers in pairs, each pair from "
                             "its outer layer's mesh (3: never)",
                             [](auto& s) -> auto& { return s.fold_level; }));
    t.push_back(int_param<S>("kbuffer_slots", 1, kMaxKBufferSlots,
                             "kbuffer compositing: the nearest fragments of each pixel composited exactly",
                             [](auto& s) -> auto& { return s.kbuffer_slots; }));
    t.push_back(real_param<S>("light_cull", "of each lighting sample's light", 0.0, 0.5,
                              "skip, per lighting sample, the dimmest lights whose estimated share of its light sums to "
                              "at most this fraction (0: every light)",
                              [](auto& s) -> auto& { return s.light_cull; }));
    t.push_back(int_param<S>("key_lights", 0, kMaxKeyLights,
                             "the brightest lights lit apart, each with the shadow from the shells' own vertices toward it (a "
                             "volume per light made from a finer grid of the strands; 0: every light through the "
                             "lighting sums)",
                             [](auto& s) -> auto& { return s.key_lights; }));
    t.push_back(bool_param<S>("key_re_mean",
                              "the key lights light the records with re's mean (false: re at the light's azimuth about the "
                              "cluster)",
                              [](auto& s) -> auto& { return s.key_re_mean; }));
    t.push_back(real_param<S>("key_toward_camera", "voxels of the key lights' grid", 0.0, 8.0,
                              "each layer's points where a key light's shadow is read move this far toward the camera (0: "
                              "the layer's slab itself)",
                              [](auto& s) -> auto& { return s.key_toward_camera; }));
    t.push_back(real_param<S>("key_toward_light", "voxels of the key lights' grid", 0.0, 8.0,
                              "a key light's shadow is read this far toward the light from each of those points",
                              [](auto& s) -> auto& { return s.key_toward_light; }));
    t.push_back(int_param<S>("hot_spot", 0, 8,
                             "with own_cluster_shadow, the share max(0, l.v)^hot_spot of each light but the key lights (v "
                             "toward the camera) is lit past the own cluster's shadow, with re's mean (0: none)",
                             [](auto& s) -> auto& { return s.hot_spot; }));
    return t;
}

}  // namespace

const ParamTable<ShellSettings>& shell_settings_table() {
    static const ParamTable<ShellSettings> table = make_table();
    return table;
}

ShellSettings read_shell_settings(const std::string& path, ShellSettings s) {
    return shell_settings_from_json(read_json_file(path), path, s);
}

ShellSettings shell_settings_from_json(const nlohmann::json& j, const std::string& path, ShellSettings s) {
    read_params(j, s, shell_settings_table(), path);
    try {  // the keys one by one are in range; together they must make a valid hair (e.g. β_TRT = 2 β_R)
        shading::validate(s.hair, "the hair parameters");
    } catch (const Error& e) {
        throw Error(path, e.place(), e.problem());
    }
    return s;
}

nlohmann::ordered_json shell_settings_json(const ShellSettings& settings) {
    return write_params(settings, shell_settings_table());
}

void write_shell_settings(const std::string& path, const ShellSettings& settings) {
    write_file_atomic(path, shell_settings_json(settings).dump(2) + "\n");
}

}  // namespace coif::gl
