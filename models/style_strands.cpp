#include "models/style_strands.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "models/core/error.h"
#include "models/core/random.h"
#include "models/core/units.h"

namespace coif {

namespace {

// Piecewise-constant inverse CDF over bins of equal width on [0, 1): returns a position in [0, 1).
double inverse_cdf(const std::vector<double>& w, double xi) {
    double total = 0;
    for (double x : w) total += x;
    if (!(total > 0)) return xi;
    double target = xi * total;
    for (std::size_t b = 0; b < w.size(); ++b) {
        if (target < w[b] || b + 1 == w.size()) {
            const double f = w[b] > 0 ? std::clamp(target / w[b], 0.0, 1.0) : 0.5;
            return (static_cast<double>(b) + f) / static_cast<double>(w.size());
        }
        target -= w[b];
    }
    return xi;
}

struct PlaneDensity {
    int rings = 0, columns = 0;
    std::vector<double> w;  // rings × columns, ρ·cell area
    double count = 0;       // strands crossing the plane
};

std::vector<PlaneDensity> plane_densities(const HairStyle& style, std::size_t prototype) {
    const Cluster& proto = style.clusters[prototype];
    const DiskLayout l = style.layout_of(prototype);
    const std::vector<SectorDensity> grids = cluster_sector_densities(*proto.shape, l, *proto.density);
    std::vector<PlaneDensity> out(static_cast<std::size_t>(l.s_t) + 1);
    for (int i = 0; i <= l.s_t; ++i) {
        PlaneDensity& p = out[static_cast<std::size_t>(i)];
        p.rings = l.layers * l.grid_r;
        p.columns = l.s_u * l.grid_s;
        p.w.assign(static_cast<std::size_t>(p.rings) * p.columns, 0.0);
        double mass = 0;
        for (int j = 0; j < l.layers; ++j)
            for (int k = 0; k < l.s_u; ++k) {
                const SectorDensity& g = grids[l.sector_index(i, j, k)];
                for (int r = 0; r < g.n_r; ++r)
                    for (int s = 0; s < g.n_s; ++s) {
                        const double m = std::max(0.0f, g.at(s, r)) * g.cell_area();
                        p.w[static_cast<std::size_t>(j * l.grid_r + r) * p.columns + (k * l.grid_s + s)] = m;
                        mass += m;
                    }
            }
        p.count = mass / (kPi * l.gaussian_width * l.gaussian_width);
    }
    if (proto.density->kind == DensitySource::Kind::Strands) {
        for (auto& p : out) p.count = 0;
        for (const StrandRun& r : proto.density->strands)
            for (std::size_t q = 0; q < r.vu.size(); ++q) out[static_cast<std::size_t>(r.first_plane) + q].count += proto.density->strand_weight;
    }
    return out;
}

glm::dvec2 sample_plane(const PlaneDensity& p, const DiskLayout& l, double xi_v, double xi_u) {
    std::vector<double> ring(static_cast<std::size_t>(p.rings), 0.0);
    for (int r = 0; r < p.rings; ++r)
        for (int c = 0; c < p.columns; ++c) ring[static_cast<std::size_t>(r)] += p.w[static_cast<std::size_t>(r) * p.columns + c];
    const double fr = inverse_cdf(ring, xi_v);
    const int r = std::min(static_cast<int>(fr * p.rings), p.rings - 1);
    std::vector<double> cols(p.w.begin() + static_cast<std::ptrdiff_t>(r) * p.columns, p.w.begin() + static_cast<std::ptrdiff_t>(r + 1) * p.columns);
    const double fu = inverse_cdf(cols, xi_u);
    return {l.core_radius + (1.0 - l.core_radius) * fr, kTwoPi * fu};
}

// A strand through (v, u) on consecutive planes first.., evaluated on the envelope and placed.
void emit(Strands& out, const Cluster& c, const DiskLayout& l, int first, const std::vector<glm::dvec2>& vu, int sub) {
    if (vu.size() < 2) return;
    std::vector<glm::vec3> pts;
    for (std::size_t q = 0; q + 1 < vu.size(); ++q) {
        const double du = std::remainder(vu[q + 1].y - vu[q].y, kTwoPi);
        for (int s = 0; s < sub || (q + 2 == vu.size() && s == sub); ++s) {
            const double w = static_cast<double>(s) / sub;
            const double t = l.plane_t(first + static_cast<int>(q)) + w / l.s_t;
            const glm::dvec3 p = c.shape->point(t, vu[q].x + w * (vu[q + 1].x - vu[q].x), vu[q].y + w * du);
            pts.emplace_back(c.placement.apply(p));
        }
    }
    out.add_strand(pts);
}

}  // namespace

struct ClusterStrandSampler::Planes {
    std::vector<PlaneDensity> planes;
    std::size_t count = 0;  // strands of a cluster of this prototype: the most crossing any plane
};

ClusterStrandSampler::ClusterStrandSampler(const HairStyle& style, const StrandSampling& options)
    : style_(style), options_(options), planes_(style.clusters.size()) {}

ClusterStrandSampler::~ClusterStrandSampler() = default;

const ClusterStrandSampler::Planes& ClusterStrandSampler::planes(std::size_t prototype) {
    std::unique_ptr<Planes>& p = planes_.at(prototype);
    if (!p) {
        p = std::make_unique<Planes>();
        p->planes = plane_densities(style_, prototype);
        double n = 0;
        for (const PlaneDensity& d : p->planes) n = std::max(n, d.count);
        p->count = static_cast<std::size_t>(std::round(n));
    }
    return *p;
}

std::size_t ClusterStrandSampler::count(std::size_t cluster) {
    const Cluster& c = style_.clusters.at(cluster);
    if (options_.from == StrandSampling::From::Density) return planes(c.prototype).count;
    if (c.density->kind != DensitySource::Kind::Strands) return 0;
    std::size_t n = 0;
    for (const StrandRun& r : c.density->strands) n += r.vu.size() >= 2;
    return n;
}

Strands ClusterStrandSampler::sample(std::size_t ci) {
    Strands out;
    out.offsets.push_back(0);
    const Cluster& c = style_.clusters.at(ci);
    const DiskLayout& l = style_.layout;
    const int sub = std::max(1, options_.points_per_hsv);
    if (options_.from == StrandSampling::From::Members) {
        if (c.density->kind == DensitySource::Kind::Strands)
            for (const StrandRun& r : c.density->strands) emit(out, c, l, r.first_plane, r.vu, sub);
        return out;
    }
    const Planes& p = planes(c.prototype);
    if (static_cast<double>(p.count) > options_.max_strands) refuse_strand_count(static_cast<double>(p.count), options_.max_strands);
    const std::vector<PlaneDensity>& planes = p.planes;
    Rng rng = seeded_rng(options_.seed, ci);
    std::uniform_real_distribution<double> U(0, 1);
    for (std::size_t j = 0; j < p.count; ++j) {
        const double xi_v = U(rng), xi_u = U(rng);
        int first = -1;
        std::vector<glm::dvec2> vu;
        for (int i = 0; i <= l.s_t; ++i) {
            const bool present = static_cast<double>(j) + 0.5 < planes[static_cast<std::size_t>(i)].count;
            if (present) {
                if (first < 0) first = i;
                vu.push_back(sample_plane(planes[static_cast<std::size_t>(i)], l, xi_v, xi_u));
            } else if (first >= 0) {
                break;
            }
        }
        emit(out, c, l, first, vu, sub);
    }
    return out;
}

void refuse_strand_count(double total, double max) {
    throw Error({}, "export", "the style's densities call for " + number_text(total) +
                                  " strands, more than the limit of " + number_text(max));
}

Strands sample_strands(const HairStyle& style, const StrandSampling& o, std::vector<std::uint32_t>* strand_cluster) {
    Strands out;
    out.offsets.push_back(0);
    if (strand_cluster) strand_cluster->clear();
    ClusterStrandSampler sampler(style, o);
    if (o.from == StrandSampling::From::Density) {
        double total = 0;
        for (std::size_t ci = 0; ci < style.clusters.size(); ++ci) total += static_cast<double>(sampler.count(ci));
        if (total > o.max_strands) refuse_strand_count(total, o.max_strands);
    }
    for (std::size_t ci = 0; ci < style.clusters.size(); ++ci) {
        const Strands one = sampler.sample(ci);
        out.add_strands(one);
        if (strand_cluster) strand_cluster->resize(out.strand_count(), static_cast<std::uint32_t>(ci));
    }
    if (out.strand_count() == 0) out.offsets.clear();
    // A style in coif's y-up frame already (kStyleAxesYUp) is not turned again by whoever orients its strands.
    out.axes_stated = style_axes_stated(style);
    return out;
}

}  // namespace coif
