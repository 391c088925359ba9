#pragma once
// The raw feature vector of a sector: the HRIR database's index terms (004 §5.2, eq. 4's ρ_feature),
// computed alike for the database's generated sectors (offline/sector_generator.h) and the renderer's
// sectors (online/), so both sides of the look-up measure a sector the same way.
//
// One raw vector per sector holds every column any feature definition uses; a definition (a
// FeatureSet, offline/sector_generator.h) picks columns. The density columns come from
// models/sector_density.h (paper_features, rich_features); two shape columns are added because the
// records depend on the sector's size in λ, which the density alone does not tell: ln(H/λ) and ln(W/H).
//   columns [0, 3)                 paper_features (ρ_st, ρ_s, ρ_t)
//   columns [3, 3 + rich count)    rich_features
//   last two                       ln(depth/λ), ln(width/depth), each argument clamped to ≥ 1e-6
#include <array>
#include <span>
#include <string>
#include <vector>

#include "models/sector_density.h"

namespace coif {

inline constexpr int kPaperColumns = 3;
inline constexpr int kShapeColumns = 2;
inline constexpr int kRawFeatureCount = kPaperColumns + kRichFeatureCount + kShapeColumns;
inline constexpr int kRichColumn0 = kPaperColumns;
inline constexpr int kShapeColumn0 = kPaperColumns + kRichFeatureCount;
inline constexpr int kMeanDensityColumn = kRichColumn0 + kMeanDensity;  // a sector's mean density ρ̄ among the raw columns
using RawFeatures = std::array<float, kRawFeatureCount>;

RawFeatures raw_sector_features(const SectorDensity& feature_grid, double depth_over_lambda, double width_over_depth);
// The look-up rows of a cluster's sectors (models/hair_style.h cluster_sector_densities, in its order): each sector's raw
// features at its own depth over λ (the style's Gaussian width) and width over depth, kRawFeatureCount floats a sector.
// What the cook looks up (online/scene/cook.h) and what `coif db coverage` measures (db/coverage.h) are these rows.
std::vector<float> sector_feature_rows(std::span<const SectorDensity> sectors, double lambda);
std::vector<std::string> raw_feature_names();  // one name per column, in column order

}  // namespace coif
