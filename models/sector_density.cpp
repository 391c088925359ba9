#include "models/sector_density.h"

#include <algorithm>
#include <cmath>

namespace coif {

double SectorDensity::mean() const {
    double acc = 0;
    for (float v : rho) acc += v;
    return rho.empty() ? 0.0 : acc / static_cast<double>(rho.size());
}

double SectorDensity::integral() const { return mean() * width * depth; }

SectorDensity SectorDensity::scaled(double factor) const {
    SectorDensity d = *this;
    d.width *= factor;
    d.depth *= factor;
    return d;
}

SectorDensity density_from_points(int n_s, int n_r, double width, double depth, std::span<const glm::dvec2> points,
                                  double lambda, double weight) {
    SectorDensity d;
    d.n_s = n_s;
    d.n_r = n_r;
    d.width = width;
    d.depth = depth;
    d.rho.assign(static_cast<std::size_t>(n_s) * n_r, 0.0f);
    if (n_s <= 0 || n_r <= 0 || !(lambda > 0)) return d;
    const double hs = width / n_s, hr = depth / n_r, reach = kGaussianCutoff * lambda, inv = 1.0 / (lambda * lambda);
    // Separable Gaussian: exp(−(ds² + dr²)/λ²) = exp(−ds²/λ²)·exp(−dr²/λ²), one row of each per point.
    std::vector<double> gs(static_cast<std::size_t>(n_s)), gr(static_cast<std::size_t>(n_r));
    for (const glm::dvec2& x : points) {
        const int s0 = std::max(0, static_cast<int>(std::floor((x.x - reach) / hs))), s1 = std::min(n_s - 1, static_cast<int>(std::floor((x.x + reach) / hs)));
        const int r0 = std::max(0, static_cast<int>(std::floor((x.y - reach) / hr))), r1 = std::min(n_r - 1, static_cast<int>(std::floor((x.y + reach) / hr)));
        if (s0 > s1 || r0 > r1) continue;
        for (int s = s0; s <= s1; ++s) {
            const double ds = (s + 0.5) * hs - x.x;
            gs[static_cast<std::size_t>(s)] = std::exp(-ds * ds * inv);
        }
        for (int r = r0; r <= r1; ++r) {
            const double dr = (r + 0.5) * hr - x.y;
            gr[static_cast<std::size_t>(r)] = weight * std::exp(-dr * dr * inv);
        }
        for (int r = r0; r <= r1; ++r)
            for (int s = s0; s <= s1; ++s)
                d.rho[static_cast<std::size_t>(r) * n_s + s] += static_cast<float>(gr[static_cast<std::size_t>(r)] * gs[static_cast<std::size_t>(s)]);
    }
    return d;
}

SectorDensity density_from_function(int n_s, int n_r, double width, double depth,
                                    const std::function<double(double, double)>& rho) {
    SectorDensity d;
    d.n_s = n_s;
    d.n_r = n_r;
    d.width = width;
    d.depth = depth;
    d.rho.resize(static_cast<std::size_t>(std::max(n_s, 0)) * std::max(n_r, 0));
    for (int r = 0; r < n_r; ++r)
        for (int s = 0; s < n_s; ++s)
            d.rho[static_cast<std::size_t>(r) * n_s + s] = static_cast<float>(rho((s + 0.5) / n_s, (r + 0.5) / n_r));
    return d;
}

std::array<float, 3> paper_features(const SectorDensity& d) {
    // ρ̄_st: mean density. ρ̄_s, ρ̄_t: means of the projected histograms (004 §5.2), computed as written.
    std::vector<double> hs(static_cast<std::size_t>(d.n_s), 0.0), hr(static_cast<std::size_t>(d.n_r), 0.0);
    for (int r = 0; r < d.n_r; ++r)
        for (int s = 0; s < d.n_s; ++s) {
            hs[static_cast<std::size_t>(s)] += d.at(s, r) / d.n_r;
            hr[static_cast<std::size_t>(r)] += d.at(s, r) / d.n_s;
        }
    double ms = 0, mr = 0;
    for (double v : hs) ms += v;
    for (double v : hr) mr += v;
    return {static_cast<float>(d.mean()), static_cast<float>(d.n_s ? ms / d.n_s : 0.0), static_cast<float>(d.n_r ? mr / d.n_r : 0.0)};
}

namespace {

// Centroid, spread and quarter bins of a histogram h over cells of equal width on [0, 1].
void histogram_features(const std::vector<double>& h, float& centroid, float& spread, float* bins) {
    const int n = static_cast<int>(h.size());
    double mass = 0, m1 = 0, m2 = 0;
    for (int c = 0; c < n; ++c) {
        const double x = (c + 0.5) / n, w = std::max(h[static_cast<std::size_t>(c)], 0.0);
        mass += w;
        m1 += w * x;
        // Each cell spreads its mass uniformly over its width: add the within-cell variance 1/(12 n²).
        m2 += w * (x * x + 1.0 / (12.0 * n * n));
    }
    if (mass > 0) {
        centroid = static_cast<float>(m1 / mass);
        spread = static_cast<float>(std::sqrt(std::max(m2 / mass - (m1 / mass) * (m1 / mass), 0.0)));
    } else {
        centroid = 0.5f;
        spread = 0.0f;
    }
    for (int b = 0; b < 4; ++b) {
        const double lo = b / 4.0, hi = (b + 1) / 4.0;
        double acc = 0;
        for (int c = 0; c < n; ++c) {
            const double overlap = std::max(0.0, std::min(hi, (c + 1.0) / n) - std::max(lo, static_cast<double>(c) / n));
            acc += overlap * h[static_cast<std::size_t>(c)];
        }
        bins[b] = static_cast<float>(acc / 0.25);
    }
}

}  // namespace

std::array<float, kRichFeatureCount> rich_features(const SectorDensity& d) {
    std::array<float, kRichFeatureCount> f{};
    if (d.n_s <= 0 || d.n_r <= 0) return f;
    std::vector<double> hs(static_cast<std::size_t>(d.n_s), 0.0), hr(static_cast<std::size_t>(d.n_r), 0.0);
    for (int r = 0; r < d.n_r; ++r)
        for (int s = 0; s < d.n_s; ++s) {
            hs[static_cast<std::size_t>(s)] += d.at(s, r) / d.n_r;
            hr[static_cast<std::size_t>(r)] += d.at(s, r) / d.n_s;
        }
    f[kMeanDensity] = static_cast<float>(d.mean());
    histogram_features(hs, f[kCentroidS], f[kSpreadS], &f[kBinS0]);
    histogram_features(hr, f[kCentroidR], f[kSpreadR], &f[kBinR0]);
    return f;
}

}  // namespace coif
