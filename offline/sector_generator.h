#pragma once
// Random generalized sectors β (004 §5): the samples the HRIR database is built from.
//
// Units: every length of a generated sector is in units of the strand Gaussian width λ (λ = 1),
// because the planar ray tracer's records depend only on the sector's shape measured in λ
// (its opacity coefficient κ is per λ, see offline/planar_tracer.h). The renderer measures its
// sectors (models/generalized_disk.h: width, depth) in world units and divides by its own λ
// (DiskLayout::gaussian_width) before asking the database.
//
// Sector coordinates (DESIGN.md, models/sector_density.h): s ∈ [0, W) along the track, r ∈ [0, H]
// across it, r = H the layer's outer surface. Strands are placed with s periodic (a strand near
// s = 0 also puts its tail into s ≈ W), matching the tracer, which treats s as periodic.
//
// A sample is drawn from a seed derived from (global seed, sector index) only — never from a
// shared stream — so any contiguous range of indices can be generated on its own (sharded builds,
// DESIGN.md "Beyond one machine"). The random numbers use only integer arithmetic plus std::log,
// std::sqrt, std::cos (Box–Muller): builds on machines with the same C library are byte-identical.
//
// The parameters a sample varies (the ranges below, each a named constant with its reason):
//   H/λ            the layer's radial thickness (depth) in λ
//   W/H            aspect of the sector (track arc length over depth)
//   coverage c     mean strand coverage n·πλ² (n strands per unit area; c = 1 ≈ strands one λ apart)
//   clumping       fraction of the strands gathered in clumps (Gaussian blobs of width σ_clump)
//   radial bias    strand density ∝ 1 + b·(2r/H − 1): b > 0 denser outside, b < 0 denser inside
//   hole           with probability p_hole, an empty disc cut out of the sector
//   empty          with probability p_empty, no strands at all (sparse regions of real styles)
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/generalized_disk.h"
#include "models/sector_density.h"

namespace coif {

// splitmix64 (Steele, Lea, Flood 2014): the seed of sector i is mix(mix(global) ^ mix(i + salt)).
std::uint64_t splitmix64(std::uint64_t x);
std::uint64_t sector_seed(std::uint64_t global_seed, std::uint64_t index);

// xoshiro256** (Blackman, Vigna 2018) seeded by splitmix64: a small, fully specified generator.
class SectorRng {
public:
    explicit SectorRng(std::uint64_t seed);
    std::uint64_t next();
    double uniform();                              // [0, 1), 53 bits
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    double log_uniform(double lo, double hi);      // log-uniform on [lo, hi], lo > 0
    double normal();                               // Box–Muller, one value per call
    std::uint64_t poisson(double mean);            // Knuth for mean ≤ 30, rounded normal above

private:
    std::array<std::uint64_t, 4> s_{};
};

struct SectorRanges {
    // 1.5 ≤ H/λ ≤ 8: DiskLayout's default shell (4 layers over v ∈ [0.2, 1]) on clusters of radius
    // 0.25–2 cm with λ = 0.05 cm gives H = 0.2·R/λ ∈ [1, 8]; thinner layers hold less than one strand Gaussian.
    double depth_min = 1.5, depth_max = 8.0;
    // 0.5 ≤ W/H ≤ 5: track arc 2π·R·v_mid/s_u over the layer depth for s_u = 8, v_mid ∈ [0.3, 0.9].
    double aspect_min = 0.5, aspect_max = 5.0;
    // Coverage n·πλ² from 0.1 (a few stray strands) to 3 (strands ~0.6 λ apart, a dense layer).
    double coverage_min = 0.1, coverage_max = 3.0;
    double empty_probability = 0.03;
    double clumping_max = 0.9;                            // fraction of strands in clumps
    double clump_width_min = 0.5, clump_width_max = 3.0;  // σ of a clump, in λ
    double radial_bias_max = 0.8;                         // |b| ≤ 0.8 keeps the pdf positive
    double hole_probability = 0.25;
    double hole_radius_min = 0.15, hole_radius_max = 0.4;  // relative to min(W, H)
    // Ray-tracing grid: cells of at most λ / kTraceCellsPerLambda, between these counts per side.
    int trace_cells_per_lambda = 3;
    int trace_cells_min = 8, trace_cells_max = 96;
    // Feature grid: the renderer's own density grid (DiskLayout::grid_s × grid_r), so the features of
    // a database sector are computed exactly as the renderer computes those of its sectors.
    int feature_grid_s = DiskLayout{}.grid_s, feature_grid_r = DiskLayout{}.grid_r;
};
nlohmann::json to_json(const SectorRanges& r);
SectorRanges sector_ranges_from_json(const nlohmann::json& j);  // throws coif::Error on a bad field

// The parameters one sample drew (printed by `coif db inspect`, and the coverage report).
struct SectorParams {
    double depth = 1, width = 1;  // H, W in λ
    double coverage = 0;
    double clumping = 0, clump_width = 1, radial_bias = 0;
    bool hole = false;
    double hole_s = 0, hole_r = 0, hole_radius = 0;
    std::size_t strands = 0;
};
nlohmann::json to_json(const SectorParams& p);

struct SectorSample {
    SectorParams params;
    std::vector<glm::dvec2> strands;  // strand crossings (s, r) in λ, s ∈ [0, W), r ∈ [0, H]
    SectorDensity trace_grid;         // fine grid for the ray tracer (λ = 1)
    SectorDensity feature_grid;       // the renderer's grid, for the features
};

SectorSample generate_sector(const SectorRanges& ranges, std::uint64_t global_seed, std::uint64_t index);

// The density of strand crossings on an n_s × n_r grid over W × H (λ = 1), periodic in s.
SectorDensity periodic_density(int n_s, int n_r, double width, double depth, const std::vector<glm::dvec2>& strands);

// ---- Features: the database's index terms (004 §5.2, eq. 4's ρ_feature) -------------------------
// One raw vector per sector holds every column any feature definition uses; a definition picks
// columns. The density columns come from models/ (paper_features, rich_features: one source of
// truth with the renderer); two shape columns are added because the records depend on the
// sector's size in λ, which the density alone does not tell: ln(H/λ) and ln(W/H).
inline constexpr int kPaperColumns = 3;
inline constexpr int kShapeColumns = 2;
inline constexpr int kRawFeatureCount = kPaperColumns + kRichFeatureCount + kShapeColumns;
inline constexpr int kRichColumn0 = kPaperColumns;
inline constexpr int kShapeColumn0 = kPaperColumns + kRichFeatureCount;
using RawFeatures = std::array<float, kRawFeatureCount>;

RawFeatures raw_sector_features(const SectorDensity& feature_grid, double depth_over_lambda, double width_over_depth);
std::vector<std::string> raw_feature_names();

enum class FeatureSet { Paper, PaperShape, Rich, RichShape };
inline constexpr std::array<FeatureSet, 4> kAllFeatureSets{FeatureSet::Paper, FeatureSet::PaperShape, FeatureSet::Rich,
                                                           FeatureSet::RichShape};
std::string feature_set_name(FeatureSet set);
FeatureSet feature_set_from_name(const std::string& name);  // throws coif::Error::parameter
std::vector<int> feature_columns(FeatureSet set);

}  // namespace coif
