#include "db/coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "models/sector_features.h"

namespace coif {

std::vector<float> style_sector_features(const HairStyle& style) {
    const DiskLayout& layout = style.layout;
    const double lambda = layout.gaussian_width;
    // One block of rows per prototype, shared by its instances (identical in λ units).
    std::vector<std::vector<float>> prototype_rows(style.clusters.size());
    std::vector<float> rows;
    rows.reserve(style.clusters.size() * layout.sector_count() * kRawFeatureCount);
    for (const Cluster& c : style.clusters) {
        std::vector<float>& block = prototype_rows[c.prototype];
        if (block.empty()) {
            const Cluster& proto = style.clusters[c.prototype];
            block = sector_feature_rows(cluster_sector_densities(*proto.shape, style.layout_of(c.prototype), *proto.density), lambda);
        }
        rows.insert(rows.end(), block.begin(), block.end());
    }
    return rows;
}

std::vector<float> held_out_sector_features(const DbParams& params, std::size_t n) {
    std::vector<float> rows;
    rows.reserve(n * kRawFeatureCount);
    for (std::size_t i = 0; i < n; ++i) {
        const SectorSample s = generate_sector(params.generator, held_out_seed(params.seed), i);
        const RawFeatures f = raw_sector_features(s.feature_grid, s.params.depth, s.params.width / s.params.depth);
        rows.insert(rows.end(), f.begin(), f.end());
    }
    return rows;
}

namespace {

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// The q-quantile of sorted values (nearest rank, as error_stats).
double quantile(const std::vector<float>& sorted, double q) {
    return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1) + 0.5))];
}

std::vector<float> column(std::span<const float> rows, int c) {
    std::vector<float> v;
    v.reserve(rows.size() / kRawFeatureCount);
    for (std::size_t i = static_cast<std::size_t>(c); i < rows.size(); i += kRawFeatureCount) v.push_back(rows[i]);
    std::sort(v.begin(), v.end());
    return v;
}

std::vector<double> nearest_distances(const std::vector<SectorMatch>& matches) {
    std::vector<double> d;
    d.reserve(matches.size());
    for (const SectorMatch& m : matches) d.push_back(m.distance[0]);
    return d;
}

// The ratios of mean density, style sector over its nearest record, of the non-empty style sectors.
CoverageReport::DensityMatch density_match(const HrirDatabase& db, std::span<const float> style_rows,
                                           const std::vector<SectorMatch>& matches, double empty_density) {
    std::vector<float> ratio;
    std::size_t outside = 0;
    for (std::size_t i = 0; i < matches.size(); ++i) {
        const double style = style_rows[i * kRawFeatureCount + kMeanDensityColumn];
        if (style < empty_density) continue;
        const double record = db.features(matches[i].id[0])[kMeanDensityColumn];
        const double r = record >= empty_density ? style / record : std::numeric_limits<double>::infinity();
        ratio.push_back(static_cast<float>(r));
        outside += r < 0.5 || r > 2.0 ? 1 : 0;
    }
    CoverageReport::DensityMatch m;
    if (ratio.empty()) return m;
    std::sort(ratio.begin(), ratio.end());
    m.sectors = ratio.size();
    m.p10 = quantile(ratio, 0.1);
    m.median = quantile(ratio, 0.5);
    m.p90 = quantile(ratio, 0.9);
    m.outside_half_to_double = static_cast<double>(outside) / static_cast<double>(ratio.size());
    return m;
}

double empty_share(std::span<const float> rows, double threshold) {
    std::size_t n = 0;
    for (std::size_t i = kMeanDensityColumn; i < rows.size(); i += kRawFeatureCount) n += rows[i] < threshold ? 1 : 0;
    return static_cast<double>(n) / static_cast<double>(rows.size() / kRawFeatureCount);
}

}  // namespace

CoverageReport database_coverage(const HrirDatabase& db, std::span<const float> style_rows, std::span<const float> held_out_rows,
                                 const CoverageOptions& o) {
    if (style_rows.empty() || style_rows.size() % kRawFeatureCount != 0)
        throw Error::parameter("coverage", "the style has no sectors");
    if (held_out_rows.empty() || held_out_rows.size() % kRawFeatureCount != 0)
        throw Error::parameter("--held-out", "must be at least 1");
    SatfOptions so;
    so.set = o.set;
    so.k = 1;
    const SatfIndex index(db, so);  // refuses shards and empty databases

    CoverageReport r;
    r.set = feature_set_name(o.set);
    r.db_sectors = db.size();
    r.style_sectors = style_rows.size() / kRawFeatureCount;
    r.held_out = held_out_rows.size() / kRawFeatureCount;
    const std::span<const float> db_rows = db.all_features();
    r.db_empty = empty_share(db_rows, o.empty_density);
    r.style_empty = empty_share(style_rows, o.empty_density);
    const auto names = raw_feature_names();
    for (int c = 0; c < kRawFeatureCount; ++c) {
        const std::vector<float> d = column(db_rows, c), s = column(style_rows, c);
        ColumnCoverage cc;
        cc.name = names[static_cast<std::size_t>(c)];
        cc.db_min = d.front();
        cc.db_max = d.back();
        cc.db_p01 = quantile(d, 0.01);
        cc.db_p99 = quantile(d, 0.99);
        cc.style_min = s.front();
        cc.style_max = s.back();
        cc.style_p01 = quantile(s, 0.01);
        cc.style_median = quantile(s, 0.5);
        cc.style_p99 = quantile(s, 0.99);
        const auto below = std::lower_bound(s.begin(), s.end(), static_cast<float>(cc.db_p01)) - s.begin();
        const auto above = s.end() - std::upper_bound(s.begin(), s.end(), static_cast<float>(cc.db_p99));
        cc.below = static_cast<double>(below) / static_cast<double>(s.size());
        cc.above = static_cast<double>(above) / static_cast<double>(s.size());
        r.columns.push_back(cc);
    }

    const std::vector<SectorMatch> style_matches = index.match_all(style_rows);
    const std::vector<double> sd = nearest_distances(style_matches), hd = nearest_distances(index.match_all(held_out_rows));
    r.style_distance = error_stats(sd);
    r.held_out_distance = error_stats(hd);
    std::size_t beyond = 0, nonempty = 0, nonempty_beyond = 0;
    for (std::size_t i = 0; i < sd.size(); ++i) {
        const bool far = sd[i] > r.held_out_distance.p95;
        beyond += far ? 1 : 0;
        if (style_rows[i * kRawFeatureCount + kMeanDensityColumn] >= o.empty_density) {
            ++nonempty;
            nonempty_beyond += far ? 1 : 0;
        }
    }
    r.style_beyond_held_out_p95 = static_cast<double>(beyond) / static_cast<double>(sd.size());
    r.style_beyond_held_out_p95_nonempty = nonempty ? static_cast<double>(nonempty_beyond) / static_cast<double>(nonempty) : 0.0;
    r.density_ratio = density_match(db, style_rows, style_matches, o.empty_density);
    return r;
}

nlohmann::json to_json(const CoverageReport& r) {
    nlohmann::json cols = nlohmann::json::array();
    for (const ColumnCoverage& c : r.columns)
        cols.push_back({{"name", c.name},
                        {"db", {{"min", c.db_min}, {"p01", c.db_p01}, {"p99", c.db_p99}, {"max", c.db_max}}},
                        {"style", {{"min", c.style_min}, {"p01", c.style_p01}, {"median", c.style_median}, {"p99", c.style_p99}, {"max", c.style_max}}},
                        {"share_below_db_p01", c.below},
                        {"share_above_db_p99", c.above}});
    const auto stats = [](const ErrorStats& s) { return nlohmann::json{{"median", s.median}, {"p95", s.p95}, {"mean", s.mean}}; };
    return {{"style", r.style},
            {"feature_set", r.set},
            {"database_sectors", r.db_sectors},
            {"style_sectors", r.style_sectors},
            {"held_out_sectors", r.held_out},
            {"empty_share", {{"style", r.style_empty}, {"database", r.db_empty}}},
            {"columns", cols},
            {"nearest_record_distance", {{"style", stats(r.style_distance)}, {"held_out", stats(r.held_out_distance)}}},
            {"style_share_beyond_held_out_p95", r.style_beyond_held_out_p95},
            {"style_share_beyond_held_out_p95_nonempty", r.style_beyond_held_out_p95_nonempty},
            // JSON has no infinity: a ratio against an empty record is written as null.
            {"density_ratio",
             {{"sectors", r.density_ratio.sectors},
              {"p10", finite_or_null(r.density_ratio.p10)},
              {"median", finite_or_null(r.density_ratio.median)},
              {"p90", finite_or_null(r.density_ratio.p90)},
              {"share_outside_half_to_double", r.density_ratio.outside_half_to_double}}}};
}

}  // namespace coif
