#pragma once
// The planar ray tracer (004 §5.1): the HRIR of one generalized sector — the 1D arrays α(x) and
// re(x) seen by rays confined to the sector's plane — for a view azimuth θv and light azimuths θl.
//
// Geometry (DESIGN.md "Sector coordinates"; models/sector_density.h):
//   s ∈ [0, W) along the track, r ∈ [0, H] across it, r = H the layer's OUTER surface; lengths in λ
//   (offline/sector_generator.h). s is periodic: a ray leaving a side of the sector enters the
//   neighbouring sector of the same track, which is statistically alike.
//   Azimuths are measured from the outward radial direction +r towards +s: dir(θ) = (sin θ, cos θ)
//   in (s, r). θv points from the surface TOWARDS the eye, θl TOWARDS the light, both over [0, 2π).
//   Position x ∈ [0, W) is where the eye ray crosses the outer surface r = H; it maps onto the layer
//   mesh's u across the HSV. HRIR sample j sits at x_j = (j + ½)·W/X (the box of rays in
//   [jW/X, (j+1)W/X) averaged, after smoothing).
//
// The eye ray travels along −dir(θv) through (x, H). Front views (cos θv > 0): it enters at r = H
// and leaves through r = 0 into the transparent core. Back views (cos θv < 0, seen through the core):
// it enters at r = 0 and leaves at (x, H). Either way it is accumulated front to back (004 eq. 5)
// over the part of the line inside the slab 0 ≤ r ≤ H:
//   α̂ ← α̂ + α_k (1 − α̂),   re^ ← re^ + α_k re_k (1 − α̂)   (re^ updated first, with the old α̂)
// and stops when α̂ ≥ kOpaqueAlpha or the ray has left the slab. Grazing cap: the path is at most
// grazing_cap·H long (8 H by default: reached beyond |cos θv| < 1/8, i.e. within 7.2° of grazing);
// the kept part is the one next to x (its first grazing_cap·H for front views, its last for back).
//
// Per step of length Δt (midpoint samples, Δt ≤ step_per_cell × the smaller cell side):
//   α_k  = 1 − exp(−κ ρ Δt): "proportional to density" to first order, and exact for Beer–Lambert,
//          so a uniform slab gives α̂ = 1 − exp(−κ ρ L) exactly (L the path length).
//   re_k = Phong with normal n = −∇ρ/|∇ρ| (pointing out of the strands) under light dir(θl), eye dir(θv):
//          kd·max(0, n·l) + ks·max(0, reflect(−l, n)·v)^p  (0 where n·l ≤ 0),
//          blended towards its average over all in-plane normals, kd/π + ks·c_p, where the gradient
//          is weak: weight |∇ρ|² / (|∇ρ|² + (g_0 (ρ + ρ_0))²), g_0 = gradient_floor per λ. Near a strand's
//          centre or in a uniform region the normal is meaningless; the average is what a random
//          normal gives. kd, ks, p are stored in the database header.
//   optional light attenuation: re_k × exp(−κ ∫ρ) along dir(θl) from the sample point to the slab
//          boundary (s periodic, same grazing cap): self-shadowing inside the sector.
// ρ and ∇ρ are bilinear interpolations of the cell-centred grid and of its central differences
// (periodic in s, one-sided at r = 0 and r = H, constant beyond the outermost cell centres).
// Smoothing (004 §5.1): the arrays can be convolved (periodically) with g(x) = exp(−x²/(wλ)²); the paper's
// w is 1.5. The default is 0 (no smoothing): each sample is already its box of rays' mean, and the paper's
// smoothing made the shells 15–25 % poorer in fibre detail than without it, at the same blurred PSNR against
// coif reference (docs/quality.md, "Fibre detail").
#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "models/sector_density.h"

namespace coif {

struct TracerParams {
    double kappa = 0.6;             // opacity per unit density per λ of path (an isolated strand hit
                                    // through its centre: ∫ρ dt = √π λ → α ≈ 1 − e^{−1.06} ≈ 0.65)
    double kd = 0.6, ks = 0.4;      // Phong diffuse and specular weights
    double exponent = 16;           // Phong exponent p
    bool light_attenuation = false; // self-shadowing inside the sector
    double smoothing_ratio = 0.0;   // smoothing Gaussian width / strand Gaussian width (004 §5.1: 1.5; 0 none)
    double step_per_cell = 0.5;     // Δt ≤ this × the smaller cell side
    double grazing_cap = 8.0;       // path ≤ grazing_cap · H
    double gradient_floor = 0.25;   // g_0 (per λ) of the normal's blend weight
    double gradient_rho0 = 0.05;    // ρ_0 of the same weight (keeps it defined where ρ → 0)
};
inline constexpr double kOpaqueAlpha = 0.999;  // early termination (004 §5.1: "very close to 1")
nlohmann::json to_json(const TracerParams& p);
TracerParams tracer_params_from_json(const nlohmann::json& j);  // throws coif::Error

// Average of the Phong specular lobe max(0, cos ψ)^p over a uniformly random in-plane normal:
// ψ = 2φ_n − θl − θv is then uniform, so c_p = (1/2π)∫cos^p ψ dψ over |ψ| < π/2 = Γ((p+1)/2)/(2√π Γ(p/2+1)).
double phong_specular_average(double exponent);

// The angular grids and the storage form of one HRIR record.
//   views          θv_i = 2π i / views
//   hrir_length    X samples along x
//   fourier_order  K: re(x, θv, θl) ≈ a_0 + Σ_{k=1..K} a_k cos kθl + b_k sin kθl (DESIGN.md decision 1)
//   light_samples  θl samples the tracer takes to project onto the Fourier basis (≥ 2K + 1)
// Record layout (values, row-major, x fastest), `record_values()` in all:
//   α[views][X], then re[views][2K + 1][X] with coefficient c = 0: a_0, c = 2k − 1: a_k, c = 2k: b_k.
struct AngleGrids {
    int views = 32;
    int hrir_length = 32;
    int fourier_order = 4;
    int light_samples = 48;

    int coefficients() const { return 2 * fourier_order + 1; }
    std::size_t alpha_values() const { return static_cast<std::size_t>(views) * hrir_length; }
    std::size_t record_values() const { return alpha_values() * (1 + coefficients()); }
    std::size_t alpha_offset(int view) const { return static_cast<std::size_t>(view) * hrir_length; }
    std::size_t re_offset(int view, int c) const {
        return alpha_values() + (static_cast<std::size_t>(view) * coefficients() + c) * hrir_length;
    }
};
nlohmann::json to_json(const AngleGrids& g);
AngleGrids angle_grids_from_json(const nlohmann::json& j);  // throws coif::Error

class PlanarTracer {
public:
    PlanarTracer(const SectorDensity& density, const TracerParams& params);

    // α[X] and re[n_l][X] for one view azimuth and each of the given light azimuths, smoothed.
    void trace_view(double theta_v, std::span<const double> theta_l, int hrir_length, std::span<float> alpha,
                    std::span<float> re) const;
    // The whole record in the layout of AngleGrids.
    std::vector<float> trace_record(const AngleGrids& grids) const;

    double density(double s, double r) const;
    glm::dvec2 gradient(double s, double r) const;

private:
    double bilinear(const std::vector<float>& grid, double s, double r) const;
    double transmittance_to_light(double s, double r, double theta_l) const;
    std::vector<float> transmittance_grid(double theta_l) const;
    void trace_view_impl(double theta_v, std::span<const double> theta_l, int hrir_length, std::span<float> alpha,
                         std::span<float> re, const std::vector<std::vector<float>>* shadows) const;
    void smooth(std::span<float> values, int n_rays) const;

    SectorDensity d_;
    TracerParams p_;
    std::vector<float> grad_s_, grad_r_;
    double hs_, hr_, step_, specular_average_;
};

}  // namespace coif
