// The planar ray tracer (offline/planar_tracer.h): physics limits and symmetry.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "offline/planar_tracer.h"
#include "offline/sector_generator.h"

namespace {

using coif::PlanarTracer;
using coif::SectorDensity;
using coif::TracerParams;
constexpr double kDeg = std::numbers::pi / 180.0;

SectorDensity uniform(double rho, double W, double H, int n_s = 12, int n_r = 9) {
    return coif::density_from_function(n_s, n_r, W, H, [rho](double, double) { return rho; });
}

TEST(PlanarTracer, EmptySectorIsTransparentAndBlack) {
    // No density: every α_k is exactly 0 and nothing is accumulated, so the tolerance is 0.
    const PlanarTracer t(uniform(0.0, 5, 3), TracerParams{});
    const int X = 16;
    const double lights[3] = {0.0, 1.0, 4.0};
    std::vector<float> a(X), re(3 * X);
    for (double tv : {0.0, 0.7, 2.0, 3.1, 4.5}) {
        t.trace_view(tv, lights, X, a, re);
        for (float v : a) EXPECT_EQ(v, 0.0f);
        for (float v : re) EXPECT_EQ(v, 0.0f);
    }
    const auto rec = t.trace_record(coif::AngleGrids{8, 8, 2, 8});
    for (float v : rec) EXPECT_EQ(v, 0.0f);
}

TEST(PlanarTracer, UniformSlabFollowsBeerLambert) {
    // A constant field: bilinear interpolation and smoothing keep it constant and the per-step
    // α = 1 − exp(−κρΔt) composes exactly, so α = 1 − exp(−κρL) up to float rounding (1e-5).
    // The path is L = H/|cos θv| up to the grazing cap of 8 H (|cos θv| < 1/8).
    TracerParams p;
    const double rho = 0.3, H = 3.0;
    const PlanarTracer t(uniform(rho, 5.0, H), p);
    const int X = 10;
    const double light[1] = {0.0};
    std::vector<float> a(X), re(X);
    for (double deg : {0.0, 20.0, 45.0, 70.0, 85.0, 110.0, 180.0, 200.0, 300.0}) {
        const double c = std::abs(std::cos(deg * kDeg));
        const double L = c * p.grazing_cap * H > H ? H / c : p.grazing_cap * H;
        const double expected = std::min(1.0 - std::exp(-p.kappa * rho * L), 1.0);
        t.trace_view(deg * kDeg, light, X, a, re);
        for (float v : a) {
            if (expected < coif::kOpaqueAlpha) EXPECT_NEAR(v, expected, 1e-5) << "θv = " << deg << "°";
            else EXPECT_GE(v, coif::kOpaqueAlpha - 1e-6);  // early termination stops just past 0.999
        }
        // No gradient: every sample reflects the normal-averaged Phong value, so re = average × α.
        const double average = p.kd / std::numbers::pi + p.ks * coif::phong_specular_average(p.exponent);
        for (int x = 0; x < X; ++x) EXPECT_NEAR(re[static_cast<std::size_t>(x)], average * a[static_cast<std::size_t>(x)], 1e-5);
    }
}

TEST(PlanarTracer, SpecularAverageMatchesQuadrature) {
    // c_p = (1/2π)∫ max(0, cos ψ)^p dψ; midpoint rule with 20000 nodes is exact to ~1e-9.
    for (double p : {1.0, 4.0, 16.0, 50.0}) {
        double sum = 0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            const double psi = -std::numbers::pi + (i + 0.5) * 2 * std::numbers::pi / n;
            sum += std::pow(std::max(0.0, std::cos(psi)), p);
        }
        EXPECT_NEAR(coif::phong_specular_average(p), sum / n, 1e-7);
    }
}

TEST(PlanarTracer, MirroredSectorUnderMirroredAnglesGivesMirroredArrays) {
    // s → W − s mirrors the grid (cell i → n_s − 1 − i), θ → −θ mirrors every direction, so ray q sees
    // exactly what ray n − 1 − q saw: arrays reversed in x. Only the summation order of floats
    // differs: tolerance 1e-5.
    std::uint64_t index = 0;
    while (coif::generate_sector(coif::SectorRanges{}, 7, index).params.strands < 5) ++index;  // a non-trivial sector
    const coif::SectorSample s = coif::generate_sector(coif::SectorRanges{}, 7, index);
    SectorDensity m = s.trace_grid;
    for (int r = 0; r < m.n_r; ++r)
        for (int i = 0; i < m.n_s; ++i) m.rho[static_cast<std::size_t>(r) * m.n_s + i] = s.trace_grid.at(m.n_s - 1 - i, r);
    for (bool shadows : {false, true}) {
        TracerParams p;
        p.light_attenuation = shadows;
        const PlanarTracer a(s.trace_grid, p), b(m, p);
        const int X = 12;
        const double l1[2] = {0.4, 2.5}, l2[2] = {-0.4, -2.5};
        std::vector<float> a1(X), r1(2 * X), a2(X), r2(2 * X);
        for (double tv : {0.3, 1.4, 2.9, 4.0}) {
            a.trace_view(tv, l1, X, a1, r1);
            b.trace_view(-tv, l2, X, a2, r2);
            for (int x = 0; x < X; ++x) {
                EXPECT_NEAR(a1[static_cast<std::size_t>(x)], a2[static_cast<std::size_t>(X - 1 - x)], 1e-5);
                for (int j = 0; j < 2; ++j)
                    EXPECT_NEAR(r1[static_cast<std::size_t>(j * X + x)], r2[static_cast<std::size_t>(j * X + X - 1 - x)], 1e-5);
            }
        }
    }
}

TEST(PlanarTracer, LightAttenuationOnlyDarkens) {
    // Self-shadowing multiplies each sample's reflectance by a transmittance ≤ 1: re can only drop,
    // α is unchanged (exactly: the same path is traced).
    const coif::SectorSample s = coif::generate_sector(coif::SectorRanges{}, 11, 5);
    TracerParams off, on;
    on.light_attenuation = true;
    const PlanarTracer a(s.trace_grid, off), b(s.trace_grid, on);
    const int X = 8;
    const double l[1] = {0.8};
    std::vector<float> a1(X), r1(X), a2(X), r2(X);
    a.trace_view(0.2, l, X, a1, r1);
    b.trace_view(0.2, l, X, a2, r2);
    for (int x = 0; x < X; ++x) {
        EXPECT_EQ(a1[static_cast<std::size_t>(x)], a2[static_cast<std::size_t>(x)]);
        EXPECT_LE(r2[static_cast<std::size_t>(x)], r1[static_cast<std::size_t>(x)] + 1e-7f);
    }
}

}  // namespace
