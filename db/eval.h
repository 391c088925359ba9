#pragma once
// `coif db eval`: the SATF look-up against freshly ray-traced held-out sectors (DESIGN.md "What
// counts as right"), and the study that chose the database's angular grids and storage form.
//
// Held-out sectors are drawn with the database's generator ranges from a seed no build uses
// (splitmix64(seed ^ kHeldOutSalt)), so they are not in the database. For each one, `angle_pairs`
// (θv, θl) pairs uniform over the full circles are traced directly (no grid, no Fourier series):
// that is the truth. The error of a sector is the relative L2 error pooled over its pairs and x:
//   e = ‖lookup − truth‖₂ / max(‖truth‖₂, kErrorFloor·√n)
// (the floor keeps empty or nearly black sectors from dividing by ~0: an RMS of 0.01 is the unit
// there). Reported: median and 95th percentile over the held-out sectors, for re and α, for each
// feature set × k × blend, plus the "oracle": the held-out sector's own record in the database's
// storage form — the floor that angular grids, Fourier order and half floats impose on any look-up.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "db/hrir_db.h"
#include "db/satf.h"

namespace coif {

inline constexpr double kErrorFloor = 0.01;
inline constexpr std::uint64_t kHeldOutSalt = 0x48454C444F555421ull;  // "HELDOUT!"
// The generator seed of the held-out sectors of a database built with `seed` (eval and coverage).
std::uint64_t held_out_seed(std::uint64_t seed);

struct EvalOptions {
    std::size_t held_out = 200;
    int angle_pairs = 8;
    std::vector<FeatureSet> sets{kAllFeatureSets.begin(), kAllFeatureSets.end()};
    std::vector<int> ks{1, 2, 4, 8, 16};
    std::vector<Blend> blends{Blend::InverseDistance, Blend::Gaussian};
    int threads = 0;  // worker threads, 0 = every hardware thread (models/core/parallel.h); was 1 before v0.2
};

struct ErrorStats {
    double median = 0, p95 = 0, mean = 0;
};
ErrorStats error_stats(std::vector<double> errors);

struct EvalRow {
    std::string set;  // feature set name, or "oracle"
    int k = 0;
    std::string blend;
    ErrorStats re, alpha;
};

struct EvalReport {
    std::size_t sectors = 0, held_out = 0;
    int angle_pairs = 0;
    std::vector<EvalRow> rows;  // rows[0] is the oracle
    double seconds = 0;
};
EvalReport evaluate_database(const HrirDatabase& db, const EvalOptions& options);
nlohmann::json to_json(const EvalReport& r);

// The resolution study (`coif db eval --study`): on held-out sectors, the relative L2 error (median,
// p95) of each storage choice against a direct trace, one choice varied at a time:
//   fourier_order K       re(θl) by K orders (projected from 96 samples) vs direct, at random θv
//   views Nv              θv linearly interpolated at the mid-point between two grid views
//   hrir_length X         X samples, linearly interpolated (periodic), vs 256 samples
//   half                  half-float rounding of the stored values
struct StudyRow {
    std::string quantity;
    int value = 0;
    ErrorStats re, alpha;
};
std::vector<StudyRow> resolution_study(const DbParams& params, std::size_t held_out, int threads);
nlohmann::json to_json(const std::vector<StudyRow>& rows);

}  // namespace coif
