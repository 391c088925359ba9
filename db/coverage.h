#pragma once
// Coverage of a database against real hairstyles (`coif db coverage`): does the database's feature
// distribution hold the sectors the renderer will ask for?
//
// A style's sectors get exactly the database's raw feature vector (offline/sector_generator.h
// raw_sector_features): the density columns from the sector's grid (models/hair_style.h
// cluster_sector_densities, world units; the density ρ and the relative features are unit-free) and
// the shape columns ln(H/λ), ln(W/H) with λ the style's own gaussian_width (layout). An instance's
// sectors are its prototype's scaled by the placement, λ included, so in λ units they are the
// prototype's: each prototype is computed once and its rows repeated for every member, i.e. the rows
// are the sectors the renderer draws.
//
// Reported per raw column: the database's 1st/99th percentiles and range, the style's range and
// median, and the share of style sectors below p1 / above p99 (a database drawn from the right
// ranges has ≈ 1 % on each side). And the distance from each style sector to its nearest record in
// the normalised feature space of the look-up (z-scores with the database's statistics, one feature
// set's columns), against the same for held-out random sectors of the database's own generator
// (db/eval.h held_out_seed: not in the database) — the distance a sector from the generator's
// distribution typically has. Style distances far above the held-out ones mean the look-up
// extrapolates. And the density match: each non-empty style sector's mean density ρ̄ over that of its nearest
// record. The records' α and re are traced at the record's own density (the planar tracer's opacity is proportional to
// ρ, 004 §5.1), so a ratio far from 1 means the shells draw that sector with the coverage of a sparser or denser one;
// docs/quality.md, "The records' density against their sectors'", measures what it does to the image.
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "db/eval.h"
#include "db/hrir_db.h"
#include "db/satf.h"
#include "models/hair_style.h"
#include "models/sector_features.h"

namespace coif {

// The raw features of every sector of every cluster of `style`, rows of kRawFeatureCount, clusters
// in order, each cluster's sectors in layout.sector_index order (the batched SATF input).
std::vector<float> style_sector_features(const HairStyle& style);

struct CoverageOptions {
    FeatureSet set = FeatureSet::RichShape;  // the look-up's default (db/satf.h)
    std::size_t held_out = 1000;             // random sectors for the reference distances
    double empty_density = 1e-3;             // mean ρ below this counts as an empty sector
};

struct ColumnCoverage {
    std::string name;
    double db_min = 0, db_p01 = 0, db_p99 = 0, db_max = 0;
    double style_min = 0, style_p01 = 0, style_median = 0, style_p99 = 0, style_max = 0;
    double below = 0, above = 0;  // shares of style sectors below db_p01 / above db_p99
};

struct CoverageReport {
    std::string style, set;
    std::size_t db_sectors = 0, style_sectors = 0, held_out = 0;
    double style_empty = 0, db_empty = 0;  // shares of empty sectors
    std::vector<ColumnCoverage> columns;   // every raw column
    ErrorStats style_distance, held_out_distance;  // nearest-record distances (median, p95, mean)
    double style_beyond_held_out_p95 = 0;  // share of style sectors farther than the held-out p95
    double style_beyond_held_out_p95_nonempty = 0;  // the same among non-empty style sectors
    // ρ̄ of each non-empty style sector over ρ̄ of its nearest record (a record with ρ̄ below empty_density counts as
    // outside): quantiles, and the share outside [1/2, 2]. All 0 when the style has no non-empty sector.
    struct DensityMatch {
        std::size_t sectors = 0;
        double p10 = 0, median = 0, p90 = 0;
        double outside_half_to_double = 0;
    } density_ratio;
};

// The raw features of held-out sectors 0..n-1 of the database's generator (features only, no tracing).
std::vector<float> held_out_sector_features(const DbParams& params, std::size_t n);

// `held_out_rows`: held_out_sector_features(db.params(), options.held_out), computed once for many
// styles. Throws coif::Error if the database is a shard or empty, or a row set is empty.
CoverageReport database_coverage(const HrirDatabase& db, std::span<const float> style_rows, std::span<const float> held_out_rows,
                                 const CoverageOptions& options);
nlohmann::json to_json(const CoverageReport& r);

}  // namespace coif
