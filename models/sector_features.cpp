#include "models/sector_features.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace coif {

std::vector<float> sector_feature_rows(std::span<const SectorDensity> sectors, double lambda) {
    std::vector<float> rows;
    rows.reserve(sectors.size() * kRawFeatureCount);
    for (const SectorDensity& d : sectors) {
        const double depth = std::max(d.depth, 1e-12);
        const RawFeatures f = raw_sector_features(d, depth / lambda, d.width / depth);
        rows.insert(rows.end(), f.begin(), f.end());
    }
    return rows;
}

RawFeatures raw_sector_features(const SectorDensity& feature_grid, double depth_over_lambda, double width_over_depth) {
    RawFeatures f{};
    const auto paper = paper_features(feature_grid);
    const auto rich = rich_features(feature_grid);
    static_assert(std::tuple_size_v<std::decay_t<decltype(paper)>> == kPaperColumns);
    std::copy(paper.begin(), paper.end(), f.begin());
    std::copy(rich.begin(), rich.end(), f.begin() + kRichColumn0);
    f[kShapeColumn0] = static_cast<float>(std::log(std::max(depth_over_lambda, 1e-6)));
    f[kShapeColumn0 + 1] = static_cast<float>(std::log(std::max(width_over_depth, 1e-6)));
    return f;
}

std::vector<std::string> raw_feature_names() {
    std::vector<std::string> names = {"paper_rho_st", "paper_rho_s", "paper_rho_t", "mean_density", "centroid_s",
                                      "spread_s",     "centroid_r",  "spread_r"};
    for (int i = 0; i < 4; ++i) names.push_back("bin_s" + std::to_string(i));
    for (int i = 0; i < 4; ++i) names.push_back("bin_r" + std::to_string(i));
    names.push_back("ln_depth_over_lambda");
    names.push_back("ln_width_over_depth");
    return names;
}

}  // namespace coif
