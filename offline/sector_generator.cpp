#include "offline/sector_generator.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "models/core/json_field.h"
#include "models/core/units.h"

namespace coif {

std::uint64_t sector_seed(std::uint64_t global_seed, std::uint64_t index) {
    constexpr std::uint64_t kIndexSalt = 0x5EC7042D15C0FFEEull;  // keeps seed 0, index 0 away from 0
    return splitmix64(splitmix64(global_seed) ^ splitmix64(index + kIndexSalt));
}

nlohmann::json to_json(const SectorRanges& r) {
    return {{"units", "lengths in the strand Gaussian width lambda"},
            {"depth_over_lambda", {r.depth_min, r.depth_max}},
            {"width_over_depth", {r.aspect_min, r.aspect_max}},
            {"coverage", {r.coverage_min, r.coverage_max}},
            {"empty_probability", r.empty_probability},
            {"clumping_max", r.clumping_max},
            {"clump_width", {r.clump_width_min, r.clump_width_max}},
            {"radial_bias_max", r.radial_bias_max},
            {"hole_probability", r.hole_probability},
            {"hole_radius", {r.hole_radius_min, r.hole_radius_max}},
            {"band_probability", r.band_probability},
            {"band_fraction", {r.band_fraction_min, r.band_fraction_max}},
            {"trace_cells_per_lambda", r.trace_cells_per_lambda},
            {"trace_cells", {r.trace_cells_min, r.trace_cells_max}},
            {"feature_grid", {r.feature_grid_s, r.feature_grid_r}},
            {"feature_grid_periodic", r.feature_grid_periodic}};
}

namespace {


void pair_field(const nlohmann::json& j, const char* key, double& lo, double& hi) {
    const auto v = json_field<std::array<double, 2>>(j, key, "JSON /generator");
    lo = v[0];
    hi = v[1];
}

}  // namespace

SectorRanges sector_ranges_from_json(const nlohmann::json& j) {
    SectorRanges r;
    pair_field(j, "depth_over_lambda", r.depth_min, r.depth_max);
    pair_field(j, "width_over_depth", r.aspect_min, r.aspect_max);
    pair_field(j, "coverage", r.coverage_min, r.coverage_max);
    r.empty_probability = json_field<double>(j, "empty_probability", "JSON /generator");
    r.clumping_max = json_field<double>(j, "clumping_max", "JSON /generator");
    pair_field(j, "clump_width", r.clump_width_min, r.clump_width_max);
    r.radial_bias_max = json_field<double>(j, "radial_bias_max", "JSON /generator");
    r.hole_probability = json_field<double>(j, "hole_probability", "JSON /generator");
    pair_field(j, "hole_radius", r.hole_radius_min, r.hole_radius_max);
    // Absent in files written before the band existed: those were built without it.
    r.band_probability = j.contains("band_probability") ? json_field<double>(j, "band_probability", "JSON /generator") : 0.0;
    if (j.contains("band_fraction")) pair_field(j, "band_fraction", r.band_fraction_min, r.band_fraction_max);
    r.trace_cells_per_lambda = json_field<int>(j, "trace_cells_per_lambda", "JSON /generator");
    const auto cells = json_field<std::array<int, 2>>(j, "trace_cells", "JSON /generator");
    r.trace_cells_min = cells[0];
    r.trace_cells_max = cells[1];
    const auto fg = json_field<std::array<int, 2>>(j, "feature_grid", "JSON /generator");
    r.feature_grid_s = fg[0];
    r.feature_grid_r = fg[1];
    r.feature_grid_periodic = j.contains("feature_grid_periodic") ? json_field<bool>(j, "feature_grid_periodic", "JSON /generator") : true;
    const bool ok = r.depth_min > 0 && r.depth_max >= r.depth_min && r.aspect_min > 0 && r.aspect_max >= r.aspect_min &&
                    r.coverage_min > 0 && r.coverage_max >= r.coverage_min && r.trace_cells_per_lambda > 0 &&
                    r.band_probability >= 0 && r.band_probability <= 1 && r.band_fraction_min > 0 &&
                    r.band_fraction_max >= r.band_fraction_min && r.band_fraction_max <= 1 &&
                    r.trace_cells_min >= 2 && r.trace_cells_max >= r.trace_cells_min && r.trace_cells_max <= kMaxGridCells &&
                    r.feature_grid_s > 0 && r.feature_grid_r > 0 && r.feature_grid_s <= kMaxGridCells &&
                    r.feature_grid_r <= kMaxGridCells;
    if (!ok) throw Error({}, "JSON /generator", "a range is empty, negative or too large");
    return r;
}

nlohmann::json to_json(const SectorParams& p) {
    return {{"depth_over_lambda", p.depth}, {"width_over_lambda", p.width}, {"coverage", p.coverage},
            {"clumping", p.clumping},       {"clump_width", p.clump_width},  {"radial_bias", p.radial_bias},
            {"hole", p.hole},               {"hole_s", p.hole_s},            {"hole_r", p.hole_r},
            {"hole_radius", p.hole_radius}, {"band", p.band},                {"band_s0", p.band_s0},
            {"band_s", p.band_s},           {"band_r", p.band_r},            {"band_outer", p.band_outer},
            {"strands", p.strands}};
}

SectorDensity periodic_density(int n_s, int n_r, double width, double depth, const std::vector<glm::dvec2>& strands) {
    // Copies at s ± W of the strands whose Gaussian reaches over the seam make the field periodic in s.
    const double reach = kGaussianCutoff;  // λ = 1
    std::vector<glm::dvec2> points;
    points.reserve(strands.size() + 16);
    for (const glm::dvec2& x : strands) {
        points.push_back(x);
        if (x.x < reach) points.emplace_back(x.x + width, x.y);
        if (x.x > width - reach) points.emplace_back(x.x - width, x.y);
    }
    return density_from_points(n_s, n_r, width, depth, points, 1.0);
}

SectorSample generate_sector(const SectorRanges& g, std::uint64_t global_seed, std::uint64_t index) {
    Xoshiro256 rng(sector_seed(global_seed, index));
    SectorSample out;
    SectorParams& p = out.params;
    // Every draw happens in a fixed order whatever the branch, so one parameter never shifts the others.
    p.depth = rng.log_uniform(g.depth_min, g.depth_max);
    p.width = p.depth * rng.log_uniform(g.aspect_min, g.aspect_max);
    const bool empty = rng.uniform() < g.empty_probability;
    p.coverage = rng.log_uniform(g.coverage_min, g.coverage_max);
    p.clumping = rng.uniform(0.0, g.clumping_max);
    p.clump_width = rng.uniform(g.clump_width_min, g.clump_width_max);
    p.radial_bias = rng.uniform(-g.radial_bias_max, g.radial_bias_max);
    p.hole = rng.uniform() < g.hole_probability;
    p.hole_s = rng.uniform(0.0, p.width);
    p.hole_r = rng.uniform(0.0, p.depth);
    p.hole_radius = rng.uniform(g.hole_radius_min, g.hole_radius_max) * std::min(p.width, p.depth);
    if (g.band_probability > 0) {  // a parameter, not a random outcome: the draw order stays fixed per build
        p.band = rng.uniform() < g.band_probability;
        p.band_s0 = rng.uniform(0.0, p.width);
        p.band_s = rng.uniform(g.band_fraction_min, g.band_fraction_max);
        p.band_r = rng.uniform(g.band_fraction_min, g.band_fraction_max);
        p.band_outer = rng.uniform() < 0.5;
        if (!p.band) p.band_s = p.band_r = 1;
    }
    if (empty) p.coverage = 0;

    const double area = p.width * p.depth;
    const std::uint64_t n = rng.poisson(p.coverage * area / kPi);
    // Clump centres: about one per (3 σ_clump)² of area, at least one.
    const std::uint64_t n_clumps = 1 + rng.poisson(area / (9.0 * p.clump_width * p.clump_width));
    std::vector<glm::dvec2> centres;
    for (std::uint64_t c = 0; c < n_clumps; ++c) centres.emplace_back(rng.uniform(0.0, p.width), rng.uniform(0.0, p.depth));

    // Radial position with pdf ∝ 1 + b(2r/H − 1) on [0, H], by inverting its CDF.
    const auto radial = [&](double u) {
        const double b = p.radial_bias;
        if (std::abs(b) < 1e-9) return u * p.depth;
        // x = r/H: (1 − b)x + b x² = u  →  x = (−(1 − b) + sqrt((1 − b)² + 4 b u)) / (2b)
        const double x = (-(1 - b) + std::sqrt((1 - b) * (1 - b) + 4 * b * u)) / (2 * b);
        return std::clamp(x, 0.0, 1.0) * p.depth;
    };
    for (std::uint64_t i = 0; i < n; ++i) {
        const bool in_clump = rng.uniform() < p.clumping;
        const double u1 = rng.uniform(), u2 = rng.uniform(), n1 = rng.normal(), n2 = rng.normal();
        const auto c = static_cast<std::size_t>(rng.next() % n_clumps);
        glm::dvec2 x;
        if (in_clump) {
            x = centres[c] + p.clump_width * glm::dvec2(n1, n2);
            if (x.y < 0 || x.y > p.depth) x.y = radial(u2);  // a clump does not leave its layer
        } else {
            x = {u1 * p.width, radial(u2)};
        }
        const auto wrap = [&](double s) {
            s = std::fmod(s, p.width);
            return s < 0 ? s + p.width : s;
        };
        x.x = wrap(x.x);
        if (p.band) {  // squeeze the whole layout into the band (clumps and radial bias keep their shape)
            x.x = wrap(p.band_s0 + p.band_s * x.x);
            x.y = p.band_r * x.y + (p.band_outer ? (1 - p.band_r) * p.depth : 0.0);
        }
        if (p.hole) {
            double ds = std::abs(x.x - p.hole_s);
            ds = std::min(ds, p.width - ds);
            if (ds * ds + (x.y - p.hole_r) * (x.y - p.hole_r) < p.hole_radius * p.hole_radius) continue;
        }
        out.strands.push_back(x);
    }
    p.strands = out.strands.size();

    const auto cells = [&](double extent) {
        return std::clamp(static_cast<int>(std::ceil(extent * g.trace_cells_per_lambda)), g.trace_cells_min, g.trace_cells_max);
    };
    out.trace_grid = periodic_density(cells(p.width), cells(p.depth), p.width, p.depth, out.strands);
    out.feature_grid = g.feature_grid_periodic
                           ? periodic_density(g.feature_grid_s, g.feature_grid_r, p.width, p.depth, out.strands)
                           : density_from_points(g.feature_grid_s, g.feature_grid_r, p.width, p.depth, out.strands, 1.0);
    return out;
}

std::string feature_set_name(FeatureSet set) {
    switch (set) {
        case FeatureSet::Paper: return "paper";
        case FeatureSet::PaperShape: return "paper+shape";
        case FeatureSet::Rich: return "rich";
        case FeatureSet::RichShape: return "rich+shape";
    }
    return "?";
}

FeatureSet feature_set_from_name(const std::string& name) {
    for (FeatureSet s : kAllFeatureSets)
        if (feature_set_name(s) == name) return s;
    throw Error::parameter("feature set '" + name + "'", "unknown; use paper, paper+shape, rich or rich+shape");
}

std::vector<int> feature_columns(FeatureSet set) {
    std::vector<int> c;
    const bool paper = set == FeatureSet::Paper || set == FeatureSet::PaperShape;
    const bool shape = set == FeatureSet::PaperShape || set == FeatureSet::RichShape;
    if (paper)
        for (int i = 0; i < kPaperColumns; ++i) c.push_back(i);
    else
        for (int i = 0; i < kRichFeatureCount; ++i) c.push_back(kRichColumn0 + i);
    if (shape)
        for (int i = 0; i < kShapeColumns; ++i) c.push_back(kShapeColumn0 + i);
    return c;
}

}  // namespace coif
