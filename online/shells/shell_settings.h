#pragma once
// The shell renderer's settings (online/shell_renderer.h): the hair's scattering parameters, how the shells
// are shaded and composited, and the parameters file that `coif render --params` reads. GL-free.
#include <glm/glm.hpp>
#include <string>

#include "shaders/lighting.h"

namespace coif::gl {

inline constexpr int kMaxShellNeighbours = 4;  // records per sector kept for the GPU

// How the shells are composited (see the header comment; docs/renderer.md decision 4).
enum class Compositing { sorted, unsorted, exact };
const char* compositing_name(Compositing c);
// "sorted" | "unsorted" | "exact"; anything else throws coif::Error(file, place, …).
Compositing parse_compositing(const std::string& text, const std::string& file, const std::string& place);

struct ShellSettings {
    shading::HairParams hair = shading::default_hair_params();
    shading::LightingConfig config = shading::default_config(4);
    int lobes = 7;                  // bit 0 R, bit 1 TT, bit 2 TRT
    bool multiple = true;           // dual-scattering multiple scattering (shaders/lighting/srbf_shadowed.glsl)
    bool shadows = true;            // shadows between clusters (T̃, n per lighting sample and light)
    bool own_cluster_shadow = true; // shadow rays start on the cluster's axis, through its own fibres (false: outside it)
    float kappa_between = -1.0f;    // κ of the shadow pass (opacity per unit density per λ of path); < 0: the database's
    float d_f = 0.7f;               // Zinke's forward-scattering density factor d_f
    float kappa_shadow = 0.5f;      // 004 eq. 12 κ_shadow (per unit of summed α)
    int neighbours = 2;             // records blended per sector on the GPU, 1..kMaxShellNeighbours
    int fourier_order = 2;          // harmonics of re in θl used, 1..4 (the db stores 4; 2: 53 dB against 4, a third fewer fetches; docs/renderer.md)
    glm::vec3 background{0.05f, 0.05f, 0.06f};  // linear RGB behind the hair
    int samples = 4;                // per pixel: MSAA samples (sorted, unsorted); exact: render() averages round(√samples)² shifted frames
    Compositing compositing = Compositing::exact;  // decision 4 (docs/renderer.md)
    int debug = 0;                  // 0 shaded, 1 α only, 2 unlit re·τ, 3 lighting C_0 · α (no re), 4 shadow AOV
    // Decision 3's reference: every light evaluated per fragment (its own T, V and radial axis, re at each
    // light's own azimuth; shadows interpolated between lighting samples) instead of the per-sample Fourier
    // sums. ~40× the shading cost: for error figures (docs/renderer.md), not for frames.
    bool lighting_per_fragment = false;
    bool timed = false;             // glFinish around each pass and wall-clock timings (benchmarks; see ShellTimings)
};
// The supersampling of ShellRenderer::render: f × f shifted frames per image, f = round(√samples) clamped to
// 1..4, for the exact compositing (the blended modes use MSAA: 1).
int supersampling(const ShellSettings& settings);

// Reads a parameters file (JSON object; every key optional; degrees for angles):
//   {"eta", "sigma_a": [r,g,b], "alpha_R_deg", "beta_R_deg", "alpha_TT_deg", "alpha_TRT_deg",
//    "beta_TT_deg", "beta_TRT_deg", "ecc_a", "w_c_deg", "delta_eta_p", "d_b", "kappa_shadow",
//    "segments", "lobes": {"R": true, "TT": true, "TRT": true}, "multiple": true, "neighbours",
//    "debug": 0..4 (ShellSettings::debug), "compositing": "exact" | "sorted" | "unsorted", "shadows": true,
//    "own_cluster_shadow": true, "kappa_between", "d_f", "lighting_per_fragment": false,
//    "fourier_order": 1..4}
// α_R / β_R alone keep 000's links for TT and TRT; a TT/TRT key overrides its link. Validated:
// throws coif::Error naming the file and the key.
ShellSettings read_shell_settings(const std::string& path, ShellSettings base = {});

}  // namespace coif::gl
