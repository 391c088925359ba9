#pragma once
// The hair density field of one generalized sector (004 §3.3) and its density features (004 §5.2).
// GL-free and allocation-light: the offline planar ray tracer builds random sectors of this type and
// the online renderer computes their features, so both use exactly this code.
//
// Grid: the sector is the rectangle [0, width] × [0, depth] of its own coordinates (s along the track,
// r across it, r = depth the outer side; see models/generalized_disk.h). The field is stored at the
// centres of n_s × n_r equal cells, row-major in r: rho[r·n_s + s] is the value at
// ((s + ½)·width/n_s, (r + ½)·depth/n_r).
//
// Density from strands (§3.3): each strand crossing the sector's plane at x_i contributes the 2D
// Gaussian g(x) = exp(−|x − x_i|²/λ²) (DESIGN.md's convention: λ is not a standard deviation), so an
// isolated strand has peak density 1 and ∫g dA = πλ². Strands crossing outside the rectangle (in a
// neighbouring sector) still contribute their tails. ρ is dimensionless ("strand coverage"); the ray
// tracer's opacity is proportional to it (§5.1).
//
// Features (§5.2): ρ_feature = (ρ̄_st, ρ̄_s, ρ̄_t): the mean density, and the means of the density
// histograms projected on s and on the cross axis (the paper's "t", our r). Read literally the mean
// of a projected histogram is the mean density again, so the three coincide; they are implemented as
// written (paper_features) and a richer vector (rich_features) adds what the projections carry.
#include <array>
#include <cstddef>
#include <functional>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace coif {

struct SectorDensity {
    int n_s = 0, n_r = 0;
    double width = 0, depth = 0;  // world units
    std::vector<float> rho;       // n_r rows of n_s values

    float at(int s, int r) const { return rho[static_cast<std::size_t>(r) * n_s + s]; }
    double cell_area() const { return width * depth / (static_cast<double>(n_s) * n_r); }
    double mean() const;
    // ∫ρ dA by the midpoint rule (Σ ρ · cell area).
    double integral() const;
    // The same sector scaled by a similarity's factor (an instance): extents scale, ρ does not
    // (λ scales with the instance too).
    SectorDensity scaled(double factor) const;
};

// Points in sector coordinates (world units; may lie outside the rectangle). Gaussians are cut at
// kGaussianCutoff·λ, where exp(−16) ≈ 1e-7 of the peak.
inline constexpr double kGaussianCutoff = 4.0;
SectorDensity density_from_points(int n_s, int n_r, double width, double depth, std::span<const glm::dvec2> points,
                                  double lambda, double weight = 1.0);
// A density given directly: rho(s, r) with s, r relative ∈ [0, 1], sampled at cell centres.
SectorDensity density_from_function(int n_s, int n_r, double width, double depth,
                                    const std::function<double(double s, double r)>& rho);

// 004 §5.2, as written: (ρ̄_st, ρ̄_s, ρ̄_t) — all three equal the mean density (see above).
std::array<float, 3> paper_features(const SectorDensity& d);

// The richer vector. Projections h_s(s) = mean over r of ρ, h_r(r) = mean over s of ρ; centroids
// and spreads are in relative coordinates ([0, 1]; 0.5 and 1/√12 ≈ 0.289 for a uniform field; a field
// that is zero everywhere gets 0.5 and 0); bins are mean densities over quarters of each axis.
enum RichFeature : int {
    kMeanDensity = 0,
    kCentroidS,
    kSpreadS,
    kCentroidR,
    kSpreadR,
    kBinS0,  // kBinS0 .. kBinS0+3: h_s over s ∈ [0,¼), [¼,½), [½,¾), [¾,1]
    kBinR0 = kBinS0 + 4,  // kBinR0 .. kBinR0+3: h_r over r quarters (inner → outer)
    kRichFeatureCount = kBinR0 + 4
};
std::array<float, kRichFeatureCount> rich_features(const SectorDensity& d);

}  // namespace coif
