#pragma once
// The SATF look-up (004 eq. 4): SATF(β, v, l) = HRIR(ρ_feature(β), θv(β), θl(β)).
//
//   1. features → the k nearest database records in the normalised feature space (z-scores of the
//      chosen feature set's columns, statistics stored in the database), by an exact FLANN k-d tree
//      (KDTreeSingleIndex: deterministic, exact — the randomized forests are neither);
//   2. blending of the k records: inverse-distance weights w_i ∝ 1 / (d_i + ε)^p, or Gaussian weights
//      w_i ∝ exp(−(d_i / d_k)²) with d_k the k-th distance; chosen by `coif db eval` (docs/db.md);
//   3. angles: linear interpolation between the two nearest view azimuths of the grid (periodic), and
//      the θl Fourier series evaluated exactly (offline/planar_tracer.h, AngleGrids). re is clamped
//      to ≥ 0 and α to [0, 1] after blending.
//
// DESIGN.md decision 2: a static hairstyle's densities do not change per frame, so the renderer calls
// `match_all` once per hairstyle (one SectorMatch per sector) and per frame only interpolates the
// angles — on the CPU with `evaluate`, or in a shader from HrirDatabase::record_bytes() uploaded as is.
//
// Saved index "<db>.<set>.flann": FLANN's own serialisation (saveIndex/loadIndex) behind a small
// header binding it to the database:
//   "COIFFLNN", uint32 version 1, uint32 feature set (0 paper, 1 paper+shape, 2 rich, 3 rich+shape),
//   uint64 database checksum, uint64 rows, uint32 columns, uint32 0, uint64 XXH3 of the FLANN bytes,
//   then the FLANN bytes. A saved index of another database, or a corrupt one, is refused
//   (coif::Error); `SatfIndex::open` then falls back to building the index.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

#include "db/hrir_db.h"
#include "models/sector_features.h"

namespace coif {

inline constexpr int kMaxNeighbours = 32;
enum class Blend { InverseDistance, Gaussian };
std::string blend_name(Blend b);
Blend blend_from_name(const std::string& name);  // "idw" or "gauss"; throws coif::Error::parameter

// Defaults chosen by `coif db eval` (docs/db.md): rich+shape features, k = 8, inverse distance —
// the lowest median re error on 4k sectors (0.249 vs 0.324 for k = 1; the paper's features: 0.38).
struct SatfOptions {
    FeatureSet set = FeatureSet::RichShape;
    int k = 8;
    Blend blend = Blend::InverseDistance;
    double idw_power = 2.0;
    double idw_epsilon = 1e-3;  // in normalised feature units: an exact match takes (almost) all weight
};

// The nearest records of one sector and their weights (summing to 1).
struct SectorMatch {
    int k = 0;
    std::array<std::uint32_t, kMaxNeighbours> id{};
    std::array<float, kMaxNeighbours> weight{};
    std::array<float, kMaxNeighbours> distance{};
};

class SatfIndex {
public:
    // Loads "<db>.<set>.flann" if it is present and matches the database, else builds the index.
    static SatfIndex open(const HrirDatabase& db, const SatfOptions& options);
    // Builds the index in memory.
    SatfIndex(const HrirDatabase& db, const SatfOptions& options);
    SatfIndex(SatfIndex&&) noexcept;
    ~SatfIndex();

    static std::filesystem::path saved_path(const HrirDatabase& db, FeatureSet set);
    void save(const std::filesystem::path& path) const;  // atomically
    // Replaces the index by the saved one; throws coif::Error if it is of another database or corrupt.
    void load(const std::filesystem::path& path);

    const HrirDatabase& database() const { return *db_; }
    const SatfOptions& options() const { return opt_; }

    SectorMatch match(std::span<const float> raw_features) const;
    // The batched form: rows of kRawFeatureCount raw features → one match per row.
    std::vector<SectorMatch> match_all(std::span<const float> raw_feature_rows) const;

    // re[X], α[X] at (θv, θl) for a match (radians, any range).
    void evaluate(const SectorMatch& m, double theta_v, double theta_l, std::span<float> re, std::span<float> alpha) const;
    // The blended Fourier coefficients of re at θv, [2K+1][X] (for the many-light closed form).
    void coefficients(const SectorMatch& m, double theta_v, std::span<float> coefficients) const;

private:
    struct Impl;
    const HrirDatabase* db_;
    SatfOptions opt_;
    std::unique_ptr<Impl> impl_;
};

// Evaluates a decoded record (AngleGrids layout) at (θv, θl): what one neighbour contributes.
void evaluate_record(const AngleGrids& g, std::span<const float> record, double theta_v, double theta_l,
                     std::span<float> re, std::span<float> alpha);

}  // namespace coif
