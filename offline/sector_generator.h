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
// s = 0 also puts its tail into s ≈ W) on the tracing grid, matching the tracer, which treats s as
// periodic; the feature grid is not periodic, as the renderer's sectors are not.
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
//   band           with probability p_band, strands only in a band of the track and of the depth
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/core/random.h"
#include "models/generalized_disk.h"
#include "models/sector_density.h"
#include "models/sector_features.h"  // RawFeatures, raw_sector_features: shared with the renderer

namespace coif {

// The seed of sector i is splitmix64(splitmix64(global) ^ splitmix64(i + salt)) (models/core/random.h);
// a sample draws from a Xoshiro256 seeded with it.
std::uint64_t sector_seed(std::uint64_t global_seed, std::uint64_t index);

struct SectorRanges {
    // The ranges were set by `coif db coverage` against the fitted real styles (docs/db.md, "Coverage"):
    // the harolongo fit (64 clusters, λ = 0.0985) has H/λ 1.38–12.7, W/H 0.52–7.9 and mean density up
    // to 4.3 between its 1st and 99th percentiles; the first ranges (H/λ 1.5–8, W/H 0.5–5, coverage
    // 0.1–3, no band) left 4.4 %, 21 % and 2.8 % of its sectors above the database's 99th percentile.
    // 1.25 ≤ H/λ ≤ 13: layers thinner than ~1 λ hold less than one strand Gaussian.
    double depth_min = 1.25, depth_max = 13.0;
    // 0.5 ≤ W/H ≤ 8.5: track arc over layer depth; elongated ellipses (a ≫ b) give the long tail.
    double aspect_min = 0.5, aspect_max = 8.5;
    // Coverage n·πλ² from 0.1 (a few stray strands) to 5 (strands ~0.8 λ apart, a dense layer).
    double coverage_min = 0.1, coverage_max = 5.0;
    double empty_probability = 0.03;
    double clumping_max = 0.9;                            // fraction of strands in clumps
    double clump_width_min = 0.5, clump_width_max = 3.0;  // σ of a clump, in λ
    double radial_bias_max = 0.8;                         // |b| ≤ 0.8 keeps the pdf positive
    double hole_probability = 0.25;
    double hole_radius_min = 0.15, hole_radius_max = 0.4;  // relative to min(W, H)
    // Partial fill: real sectors are often filled in part (a cluster's strands end inside the layer, or
    // one or two strands sit near an edge), which puts the density centroid near an edge (centroid_s
    // and centroid_r of the harolongo fit reach 0.06 and 0.94; without the band 15–16 % of its sectors
    // fell outside the database's 1–99 % range on each side). With probability p_band the strands are
    // confined to a band: the fraction f_s of the track (periodic, at a random start) and the fraction
    // f_r of the depth on the inner or the outer side, f_s, f_r uniform in [band_min, band_max].
    // p_band = 0 draws nothing, so files written before the band existed regenerate the same sectors.
    double band_probability = 0.35;
    double band_fraction_min = 0.15, band_fraction_max = 1.0;
    // Ray-tracing grid: cells of at most λ / kTraceCellsPerLambda, between these counts per side.
    int trace_cells_per_lambda = 3;
    int trace_cells_min = 8, trace_cells_max = 96;
    // Feature grid: the renderer's own density grid (DiskLayout::grid_s × grid_r), so the features of
    // a database sector are computed exactly as the renderer computes those of its sectors.
    int feature_grid_s = DiskLayout{}.grid_s, feature_grid_r = DiskLayout{}.grid_r;
    // false: the feature grid is not periodic (SectorSample::feature_grid); files written before this field
    // existed had a periodic one and read back as true.
    bool feature_grid_periodic = false;
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
    bool band = false;
    double band_s0 = 0, band_s = 1, band_r = 1;  // start (λ) and fraction along s; fraction along r
    bool band_outer = false;                      // the r band is on the outer (r = H) side
    std::size_t strands = 0;
};
nlohmann::json to_json(const SectorParams& p);

struct SectorSample {
    SectorParams params;
    std::vector<glm::dvec2> strands;  // strand crossings (s, r) in λ, s ∈ [0, W), r ∈ [0, H]
    SectorDensity trace_grid;         // fine grid for the ray tracer (λ = 1)
    // The renderer's grid, for the features. Not periodic (unlike trace_grid): the renderer's sectors are
    // not, and a strand near an edge must move the centroid there as it does in a real sector (coverage
    // of the harolongo fit: 5.7 % → 2.1 % of its sectors beyond the held-out p95 nearest-record distance).
    SectorDensity feature_grid;
};

SectorSample generate_sector(const SectorRanges& ranges, std::uint64_t global_seed, std::uint64_t index);

// The density of strand crossings on an n_s × n_r grid over W × H (λ = 1), periodic in s.
SectorDensity periodic_density(int n_s, int n_r, double width, double depth, const std::vector<glm::dvec2>& strands);

// ---- Feature sets: which columns of the raw feature vector (models/sector_features.h) index the database

enum class FeatureSet { Paper, PaperShape, Rich, RichShape };
inline constexpr std::array<FeatureSet, 4> kAllFeatureSets{FeatureSet::Paper, FeatureSet::PaperShape, FeatureSet::Rich,
                                                           FeatureSet::RichShape};
std::string feature_set_name(FeatureSet set);
FeatureSet feature_set_from_name(const std::string& name);  // throws coif::Error::parameter
std::vector<int> feature_columns(FeatureSet set);

}  // namespace coif
