#pragma once
// Fitting N SRBF lights to an environment map (000 eq. 1, following Tsai & Shih 2006 / Ren et al. 2010):
//
//   minimise  Σ_p ΔΩ_p |Σ_j L_j G(ω_p; ω_j, λ_j) − L(ω_p)|²      over L_j ≥ 0 (RGB), ω_j ∈ S², λ_j ∈ [λmin, λmax]
//
// p runs over the pixels of the map downsampled to fit_width × fit_width/2 (solid-angle box filter, so the
// energy is unchanged), ΔΩ_p is the pixel's solid angle. The solver is Ceres (Levenberg–Marquardt, dense
// normal equations, ω_j on ceres::SphereManifold<3>, bounds on L_j and λ_j), with analytic derivatives.
// Initialisation: weighted spherical k-means (k-means++ seeding from `seed`) of the pixels' luminous
// energy Y_p ΔΩ_p; each cluster gives ω_j (its energy-weighted mean direction), λ_j (its angular spread)
// and L_j (its energy / ∫G); a first Ceres pass then solves for the L_j alone with ω_j, λ_j held.
// Deterministic: the same map, settings and seed give bit-identical lights (single-threaded solve,
// portable random numbers).
//
// Errors reported (always on the full-resolution map, and also on the fit grid):
//   relative L2 error  = sqrt(Σ_p ΔΩ_p |fit − map|² / Σ_p ΔΩ_p |map|²)     (sum over RGB)
//   energy error       = (Σ_j Y(L_j) ∫G_j − ∫Y dω) / ∫Y dω                 (signed; per channel as well)
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "offline/envmap.h"
#include "offline/srbf_lights.h"

namespace coif {

// Default fit grid width: 64 × 32 pixels (5.6° each, 3 × 3 sub-samples) keeps an N = 40 fit at seconds on one core; see
// `coif env fit --fit-width` and the downsampling study in the issue 7 report.
inline constexpr int kDefaultSrbfFitWidth = 64;
// Sub-samples per fit-grid pixel side. The model is box-filtered like the map; with the spacing of the
// sub-samples as the smallest λ, the sub-sample sum integrates every admissible lobe to < 1e-4
// (Poisson summation: error ~ e^{−π²λ²/Δ²} = e^{−π²} at λ = Δ).
inline constexpr int kDefaultSrbfSupersampling = 3;
inline constexpr int kMaxSrbfSupersampling = 8;
// Largest bandwidth fitted: at λ = 4 an SRBF falls only to e^{-1/4} = 0.78 at the antipode, i.e. it is
// already a near-constant ambient term; larger λ only make the problem ill-conditioned.
inline constexpr double kDefaultSrbfLambdaMax = 4.0;

struct SrbfFitSettings {
    int lights = 40;                       // N, 1..kMaxSrbfLights
    std::uint64_t seed = 1;                // k-means++ seeding
    int fit_width = kDefaultSrbfFitWidth;  // map downsampled to fit_width × fit_width/2 (≤ map width)
    int supersampling = kDefaultSrbfSupersampling;  // s: the model is averaged over s × s points per pixel
    double lambda_min = 0;                 // 0: one sub-sample spacing, π / (s · fit_width/2)
    double lambda_max = kDefaultSrbfLambdaMax;
    int max_iterations = 100;              // Levenberg–Marquardt iterations of the full solve
    int kmeans_iterations = 20;            // Lloyd iterations of the initial clustering
};

struct SrbfFitResult {
    std::vector<SrbfLight> lights;         // sorted by decreasing energy
    SrbfFitRecord record;                  // settings used, iterations, errors, time
};

// Called after every solver iteration with (iteration, max_iterations) for a progress bar.
using SrbfFitProgress = std::function<void(int iteration, int max_iterations)>;

// Throws coif::Error (parameter errors) for N outside 1..kMaxSrbfLights or above the number of fit-grid
// pixels / 4, fit_width odd or outside kMinEnvMapWidth..map width, or a bad λ range.
SrbfFitResult fit_srbf_lights(const EnvMap& map, const SrbfFitSettings& settings,
                              const SrbfFitProgress& progress = {});

// An environment file's SRBF lights: a lights JSON (as `coif env fit` writes it), else an equirectangular map
// (offline/envmap.h) fitted with `settings`, reporting to `progress`. Throws coif::Error as the reader or the fit.
std::vector<SrbfLight> environment_lights(const std::filesystem::path& file, const SrbfFitSettings& settings = {},
                                          const SrbfFitProgress& progress = {});

struct SrbfFitError {
    double relative_l2 = 0;
    double energy = 0;                     // luminance, signed
    glm::dvec3 energy_rgb{0.0};
};
// The two errors of the header comment, of `lights` against `map` at the map's own resolution.
SrbfFitError measure_srbf_fit(const EnvMap& map, std::span<const SrbfLight> lights);

// The lights rendered as a width × width/2 equirectangular map (pixel centres).
EnvMap render_srbf_lights(std::span<const SrbfLight> lights, int width);

}  // namespace coif
