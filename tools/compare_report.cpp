#include "tools/compare_report.h"

#include <cmath>
#include <cstdio>

#include "models/core/error.h"

namespace coif::cli {

nlohmann::json metric_json(double v) {
    if (std::isnan(v)) return nullptr;
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return v;
}

namespace {

nlohmann::json metric_set_json(const MetricSet& m) {
    return {{"psnr_db", metric_json(m.psnr_db)}, {"ssim", metric_json(m.ssim)}, {"flip_mean", metric_json(m.flip)}};
}

nlohmann::json rgb_json(const double v[3]) { return nlohmann::json::array({metric_json(v[0]), metric_json(v[1]), metric_json(v[2])}); }

std::string format_range(const std::vector<double>& r) {
    std::string s = "[";  // appends, not operator+ chains: GCC 12 warns falsely (-Wrestrict) on those
    s.append(format_metric(r[0], 3)).append(", ").append(format_metric(r[1], 3)).append("]");
    return s;
}

std::string bound(const char* op, double v, int decimals) {
    std::string s = op;
    s.append(" ").append(format_metric(v, decimals));
    return s;
}

std::string in_range(const std::vector<double>& r) {
    std::string s = "in ";
    s.append(format_range(r));
    return s;
}

// The radiance ratio by region: null when not asked for; else its box and rows of regions from the top.
nlohmann::json regions_json(const RegionRatios& g) {
    if (g.n == 0) return nullptr;
    nlohmann::json rows = nlohmann::json::array();
    for (int row = 0; row < g.n; ++row) {
        nlohmann::json cells = nlohmann::json::array();
        for (int col = 0; col < g.n; ++col) {
            const RegionRatio& r = g.cells[static_cast<std::size_t>(row) * g.n + col];
            cells.push_back({{"pixels", r.pixels}, {"radiance_ratio", rgb_json(r.radiance_ratio)}});
        }
        rows.push_back(cells);
    }
    return {{"n", g.n}, {"box", {g.x0, g.y0, g.x1, g.y1}}, {"rows", rows}};
}

}  // namespace

nlohmann::json appearance_json(const AppearanceMetrics& m) {
    return {{"regions", regions_json(m.regions)},
            {"mask_pixels", {{"a", m.pixels_a}, {"b", m.pixels_b}, {"both", m.pixels_both}, {"either", m.pixels_either}}},
            {"mask_iou", metric_json(m.mask_iou)},
            {"radiance_a", rgb_json(m.radiance_a)},
            {"radiance_b", rgb_json(m.radiance_b)},
            {"radiance_ratio", rgb_json(m.radiance_ratio)},
            {"radiance_warning", m.radiance_warning.empty() ? nlohmann::json(nullptr) : nlohmann::json(m.radiance_warning)},
            {"blur_sigma_px", m.blur_sigma},
            {"blurred_psnr_db", metric_json(m.blurred_psnr_db)},
            {"blurred_ssim", metric_json(m.blurred_ssim)},
            {"detail_sigma_px", kDetailSigma},
            {"detail_a", metric_json(m.detail_a)},
            {"detail_b", metric_json(m.detail_b)},
            {"detail_ratio", metric_json(m.detail_ratio)}};
}

nlohmann::json compare_json(const CompareResult& r) {
    return {{"width", r.width},
            {"height", r.height},
            {"mask", {{"rule", r.mask.rule}, {"pixels", r.mask.count}}},
            {"linear_peak", r.linear_peak},
            {"hdr_flip_exposures", {{"start", r.hdr_exposures.start}, {"stop", r.hdr_exposures.stop}, {"count", r.hdr_exposures.count}}},
            {"linear", metric_set_json(r.linear)},
            {"tone_mapped", metric_set_json(r.tone_mapped)},
            {"tone_mapped_all_pixels", metric_set_json(r.tone_mapped_all)},
            {"appearance", appearance_json(r.appearance)}};
}

bool CompareGates::any() const {
    return min_iou || min_blurred_psnr_db || max_flip || !detail_range.empty() || !radiance_range.empty();
}

void CompareGates::validate() const {
    const auto finite = [](const std::optional<double>& v, const char* option) {
        if (v && std::isnan(*v)) throw Error::parameter(option, "must be a number, not NaN");
    };
    finite(min_iou, "option --min-iou");
    finite(min_blurred_psnr_db, "option --min-blurred-psnr");
    finite(max_flip, "option --max-flip");
    const auto range = [](const std::vector<double>& r, const char* option) {
        if (r.empty()) return;
        if (r.size() != 2 || !std::isfinite(r[0]) || !std::isfinite(r[1]) || r[0] > r[1])
            throw Error::parameter(option, "must be two finite numbers LO HI with LO <= HI");
    };
    range(detail_range, "option --detail-range");
    range(radiance_range, "option --radiance-range");
}

std::vector<GateResult> check_gates(const CompareGates& g, const CompareResult& r) {
    std::vector<GateResult> out;
    const AppearanceMetrics& m = r.appearance;
    // NaN (an undefined metric) fails every gate on it: a gate that cannot be checked must not pass.
    if (g.min_iou) out.push_back({"mask IoU", bound(">=", *g.min_iou, 3), m.mask_iou, m.mask_iou >= *g.min_iou});
    if (g.min_blurred_psnr_db)
        out.push_back({"blurred PSNR (dB)", bound(">=", *g.min_blurred_psnr_db, 2), m.blurred_psnr_db,
                       m.blurred_psnr_db >= *g.min_blurred_psnr_db});
    if (g.max_flip)
        out.push_back({"mean FLIP (tone-mapped)", bound("<=", *g.max_flip, 4), r.tone_mapped.flip, r.tone_mapped.flip <= *g.max_flip});
    if (!g.detail_range.empty())
        out.push_back({"detail ratio", in_range(g.detail_range), m.detail_ratio,
                       m.detail_ratio >= g.detail_range[0] && m.detail_ratio <= g.detail_range[1]});
    if (!g.radiance_range.empty()) {
        static const char* const kNames[3] = {"radiance ratio R", "radiance ratio G", "radiance ratio B"};
        for (int c = 0; c < 3; ++c)
            out.push_back({kNames[c], in_range(g.radiance_range), m.radiance_ratio[c],
                           m.radiance_ratio[c] >= g.radiance_range[0] && m.radiance_ratio[c] <= g.radiance_range[1]});
    }
    return out;
}

nlohmann::json gates_json(const std::vector<GateResult>& results) {
    nlohmann::json a = nlohmann::json::array();
    for (const GateResult& g : results) a.push_back({{"metric", g.name}, {"bound", g.bound}, {"value", metric_json(g.value)}, {"pass", g.pass}});
    return a;
}

std::string format_rgb(const double v[3], int decimals) {
    std::string s;
    for (int c = 0; c < 3; ++c) {
        if (c) s += ' ';
        s += format_metric(v[c], decimals);  // "n/a" for NaN
    }
    return s;
}

}  // namespace coif::cli
