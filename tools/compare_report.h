#pragma once
// One home for how a comparison (models/core/image_metrics.h) is reported: its JSON, its table rows and
// the thresholds (gates) that set `coif compare`'s exit status. `coif compare` and `coif bench quality` use it.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/core/image_metrics.h"

namespace coif::cli {

// A number for JSON: "inf"/"-inf" for infinities, null for NaN.
nlohmann::json metric_json(double v);

// Every metric of a comparison: PSNR/SSIM/FLIP (linear, tone-mapped, tone-mapped over all pixels) and the
// appearance metrics.
nlohmann::json compare_json(const CompareResult& r);
// The appearance metrics alone.
nlohmann::json appearance_json(const AppearanceMetrics& m);

// Thresholds on a comparison; an unset one is not checked. Ranges are closed intervals.
struct CompareGates {
    std::optional<double> min_iou, min_blurred_psnr_db, max_flip;
    std::vector<double> detail_range, radiance_range;  // empty, or {lo, hi}; radiance: every channel
    bool any() const;
    // Throws coif::Error for a bound that is NaN, or a range that is not {lo ≤ hi}.
    void validate() const;
};

struct GateResult {
    std::string name, bound;
    double value = 0;
    bool pass = true;
};
std::vector<GateResult> check_gates(const CompareGates& gates, const CompareResult& r);
nlohmann::json gates_json(const std::vector<GateResult>& results);

// "R G B" of three numbers, each as format_metric writes it ("n/a" for NaN).
std::string format_rgb(const double v[3], int decimals);

}  // namespace coif::cli
