#pragma once
// The error tables of issue 6: every approximation of the SRBF lighting against the exact reference
// (shaders/marschner_reference.h). Used by tests/shading and `coif lighting check`.
//
// Error of one configuration: relative error of the RGB sum, |Σ_c approx_c - Σ_c ref_c| / Σ_c ref_c.
// Statistics over configurations are weighted by energy: configuration i weighs
//   w_i = Σ_c ref_c / ∫G_j dω
// (the response per unit light energy), so that configurations whose reference is ~0 (a light far
// from every lobe) do not dominate with meaningless relative errors, and a sharp light counts as
// much as a broad one of the same energy. The weighted median/p95 are the values below which half /
// 95 % of the total weight lies. Unweighted figures (and the max) are printed beside them, over the
// configurations whose weight is at least 1 % of the mean.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "shaders/lighting.h"

namespace coif::shading::check {

// One random configuration in the ranges: light direction uniform on the sphere, λ log-uniform
// in [0.05, 2], view uniform on the sphere, η ∈ [1.4, 1.8], σa ∈ [0, 3]³, α_R ∈ [-10°, 0°],
// β_R ∈ [2°, 15°] with 000's links, a ∈ [0.85, 1.15], w_c ∈ [0.05, 0.3].
struct Config {
    HairParams params;
    float theta_o, phi_o, theta_j, phi_j, lambda_j;
    float sigma_f2;  // multiple scattering only: U[0, 0.05] rad²
};
std::vector<Config> random_configs(int count, std::uint64_t seed);

struct Stats {
    double median = 0, p95 = 0, max = 0;          // energy-weighted quantiles, max over all
    double median_unweighted = 0, p95_unweighted = 0;
    int count = 0;
};
Stats error_stats(const std::vector<double>& errors, const std::vector<double>& weights);

struct SingleRow {
    std::string variant;  // "improved" or "paper"
    int segments;
    Stats stats;
};

// Per-light single scattering vs brute force. `progress` (may be empty) is called once per config.
std::vector<SingleRow> check_single(const std::vector<Config>& configs, const std::vector<int>& segments,
                                    const std::function<void()>& progress = {});

// One approximation on its own, on a grid.
struct ApproxRow {
    std::string name;
    std::string metric;   // what max/rms measure
    double max = 0, rms = 0;
    int samples = 0;
};
std::vector<ApproxRow> check_approximations(const std::function<void()>& progress = {});

struct MultipleRow {
    std::string term;  // "global", "local", "global + d_b local"
    Stats stats;
};
// Multiple scattering vs brute-force dual scattering over `param_sets` random parameter sets with
// `per_set` random light/view configurations each (m = 4, default config).
std::vector<MultipleRow> check_multiple(int param_sets, int per_set, std::uint64_t seed,
                                        const std::function<void()>& progress = {});

// Texture look-ups per light (counted through the CPU back end) for single and multiple scattering.
struct CostRow {
    std::string what;
    double fetches_per_light = 0;
};
std::vector<CostRow> count_fetches(int segments);

}  // namespace coif::shading::check
