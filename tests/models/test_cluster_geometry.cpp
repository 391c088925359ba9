// Geometry of a hair cluster (004 §3.2): B-splines, the generalized cylinder with its
// rotation-minimizing frame, HSV volumes, sectors and layer meshes — checked against closed forms.
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>

#include "models/bspline.h"
#include "models/generalized_cylinder.h"
#include "models/generalized_disk.h"

namespace coif {
namespace {

constexpr double kPi = std::numbers::pi;

Spline1 constant(double c) { return Spline1({c}); }

// A straight cylinder along −y from the origin, length L (collinear control points).
GeneralizedCylinder straight(double L, Spline1 a, Spline1 b, Spline1 theta) {
    return GeneralizedCylinder(Spline3({{0, 0, 0}, {0, -L / 3, 0}, {0, -2 * L / 3, 0}, {0, -L, 0}}), std::move(a),
                               std::move(b), std::move(theta));
}

// A helix of radius R and pitch 2πc per turn, `turns` turns, fitted by a 40-point cubic B-spline.
Spline3 helix(double R, double c, double turns) {
    std::vector<double> x;
    std::vector<glm::dvec3> y;
    for (int i = 0; i <= 400; ++i) {
        const double s = i / 400.0, a = 2 * kPi * turns * s;
        x.push_back(s);
        y.push_back({R * std::cos(a), -c * a, R * std::sin(a)});
    }
    return fit_bspline(x, y, 40, 0.0);
}

TEST(BSpline, ClampedEndsAndDerivatives) {
    const Spline3 s({{0, 0, 0}, {1, 2, 0}, {3, 1, 1}, {4, 0, 2}, {6, 1, 0}});
    // Clamped knots: the curve interpolates its end control points (to rounding).
    EXPECT_LT(glm::length(s(0.0) - glm::dvec3(0, 0, 0)), 1e-14);
    EXPECT_LT(glm::length(s(1.0) - glm::dvec3(6, 1, 0)), 1e-14);
    // First and second derivatives against central differences (h = 1e-5: truncation ~h², rounding
    // ~1e-16/h² for the second derivative, so 1e-6 and 1e-3 relative).
    for (double x : {0.1, 0.33, 0.5, 0.77, 0.9}) {
        const double h = 1e-5;
        const auto e = s.evaluate(x, 2);
        const glm::dvec3 d1 = (s(x + h) - s(x - h)) / (2 * h), d2 = (s(x + h) - 2.0 * s(x) + s(x - h)) / (h * h);
        EXPECT_LT(glm::length(e[1] - d1), 1e-6 * glm::length(e[1])) << x;
        EXPECT_LT(glm::length(e[2] - d2), 1e-3 * (1 + glm::length(e[2]))) << x;
    }
    // Fewer control points lower the degree: 1 → constant, 2 → line.
    EXPECT_DOUBLE_EQ(Spline1({2.5})(0.3), 2.5);
    EXPECT_NEAR(Spline1({1.0, 3.0})(0.25), 1.5, 1e-15);
}

TEST(BSpline, LeastSquaresReproducesACubic) {
    // A cubic polynomial lies in the space of a clamped cubic spline: the fit must be exact (1e-9,
    // conditioning of the normal equations with 200 samples).
    std::vector<double> x, y;
    for (int i = 0; i <= 200; ++i) {
        const double t = i / 200.0;
        x.push_back(t);
        y.push_back(1 - 2 * t + 3 * t * t - 4 * t * t * t);
    }
    const Spline1 s = fit_bspline(x, y, 7, 0.0);
    for (double t = 0; t <= 1.0; t += 0.05) EXPECT_NEAR(s(t), 1 - 2 * t + 3 * t * t - 4 * t * t * t, 1e-9) << t;
}

TEST(GeneralizedCylinder, ParameterIsRelativeArcLength) {
    const GeneralizedCylinder c(helix(2.0, 0.5, 1.5), constant(0.3), constant(0.2), constant(0.0));
    // Chord sums over 20000 steps converge to the arc length with error ~ L·(κ h)²/24 ≈ 1e-9.
    double acc = 0;
    glm::dvec3 prev = c.position(0);
    for (int i = 1; i <= 20000; ++i) {
        const glm::dvec3 p = c.position(i / 20000.0);
        acc += glm::length(p - prev);
        prev = p;
        if (i % 4000 == 0) {
            EXPECT_NEAR(acc / c.length(), i / 20000.0, 1e-7) << i;
        }
    }
    const double R = 2.0, pitch = 0.5, angle = 2 * kPi * 1.5;
    // The fitted spline's length differs from the exact helix by the fit error (~1e-5 relative).
    EXPECT_NEAR(c.length(), angle * std::sqrt(R * R + pitch * pitch), 1e-4 * c.length());
}

TEST(GeneralizedCylinder, HelixFrameIsOrthonormalAndRotationMinimizing) {
    const GeneralizedCylinder c(helix(2.0, 0.5, 2.0), constant(0.3), constant(0.2), constant(0.0));
    double worst_ortho = 0, worst_twist = 0;
    const double h = 1e-4;
    for (int i = 1; i < 2000; ++i) {
        const double t = i / 2000.0;
        const Frame f = c.frame(t);
        worst_ortho = std::max({worst_ortho, std::abs(glm::length(f.normal) - 1), std::abs(glm::length(f.binormal) - 1),
                                std::abs(glm::dot(f.normal, f.tangent)), std::abs(glm::dot(f.binormal, f.tangent)),
                                std::abs(glm::dot(f.normal, f.binormal)),
                                glm::length(glm::cross(f.tangent, f.normal) - f.binormal)});
        EXPECT_LT(glm::length(f.tangent - c.tangent(t)), 1e-12);
        // Twist rate about the tangent, per unit length: (dn/ds)·b by central differences of the frame
        // as implemented (difference error ~ (hL)²|n'''| ≈ 1e-7 here).
        const glm::dvec3 dn = (c.frame(t + h).normal - c.frame(t - h).normal) / (2 * h * c.length());
        worst_twist = std::max(worst_twist, std::abs(glm::dot(dn, f.binormal)));
    }
    std::printf("helix frame: orthonormality error %.2e, twist rate %.2e rad per unit length\n", worst_ortho, worst_twist);
    EXPECT_LT(worst_ortho, 1e-12);
    EXPECT_LT(worst_twist, 1e-4);  // the bound for a frame without θ
}

TEST(GeneralizedCylinder, PartialDerivativesMatchFiniteDifferences) {
    const GeneralizedCylinder c(helix(2.0, 0.5, 1.0), Spline1({0.3, 0.5, 0.2, 0.25}), Spline1({0.15, 0.2, 0.1}),
                                Spline1({0.0, 1.0, 2.5, 3.0}));
    const double h = 1e-5;
    for (double t : {0.1, 0.37, 0.5, 0.81}) {
        for (double v : {0.3, 1.0}) {
            for (double u : {0.2, 2.0, 4.5}) {
                const SurfacePoint p = c.surface(t, v, u);
                const glm::dvec3 dt = (c.point(t + h, v, u) - c.point(t - h, v, u)) / (2 * h);
                const glm::dvec3 dv = (c.point(t, v + h, u) - c.point(t, v - h, u)) / (2 * h);
                const glm::dvec3 du = (c.point(t, v, u + h) - c.point(t, v, u - h)) / (2 * h);
                // Central differences: truncation ~h²·|P'''| ≈ 1e-8 relative; the frame's
                // double-reflection interpolation adds a fourth-order error ~1e-9.
                EXPECT_LT(glm::length(p.d_dt - dt), 1e-6 * glm::length(p.d_dt)) << t << " " << v << " " << u;
                EXPECT_LT(glm::length(p.d_dv - dv), 1e-7 * glm::length(p.d_dv));
                EXPECT_LT(glm::length(p.d_du - du), 1e-7 * glm::length(p.d_du));
            }
        }
    }
}

TEST(GeneralizedCylinder, LocateInvertsTheSurface) {
    // Curvature radius of the helix (≈2.1) is far above the envelope (≤0.5), so every interior point
    // has one nearest normal plane.
    const GeneralizedCylinder c(helix(2.0, 0.5, 1.0), Spline1({0.3, 0.5, 0.2, 0.25}), Spline1({0.15, 0.2, 0.1}),
                                Spline1({0.0, 1.0, 2.5, 3.0}));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0, 1);
    for (int n = 0; n < 200; ++n) {
        const double t = 0.02 + 0.96 * U(rng), v = 0.05 + 0.9 * U(rng), u = 2 * kPi * U(rng);
        const CylinderCoordinates q = c.locate(c.point(t, v, u));
        EXPECT_NEAR(q.t, t, 1e-8);
        EXPECT_NEAR(q.v, v, 1e-7);
        EXPECT_NEAR(std::remainder(q.u - u, 2 * kPi), 0.0, 1e-6);
        EXPECT_TRUE(q.inside());
        EXPECT_EQ(c.distance_outside(c.point(t, v, u)), 0.0);
    }
    // Outside: a point at distance d from the ellipse along its in-plane normal is d away (the
    // distance is measured in the point's normal plane; 1e-7 from locate's tolerance).
    for (double d : {0.01, 0.1, 0.4}) {
        const SurfacePoint p = c.surface(0.5, 1.0, 1.0);
        const glm::dvec3 T = c.tangent(0.5), n = p.normal() - glm::dot(p.normal(), T) * T;
        EXPECT_NEAR(c.distance_outside(p.position + d * glm::normalize(n)), d, 1e-7) << d;
    }
}

TEST(GeneralizedCylinder, PointEllipseDistanceMatchesBruteForce) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(-3, 3);
    for (int n = 0; n < 100; ++n) {
        const double y0 = U(rng), y1 = U(rng);
        double best = 1e9;
        for (int k = 0; k < 200000; ++k) {
            const double a = 2 * kPi * k / 200000;
            best = std::min(best, std::hypot(2.0 * std::cos(a) - y0, 0.7 * std::sin(a) - y1));
        }
        // Brute force resolves the ellipse to ~(2π·2/200000)²/8 ≈ 5e-10.
        EXPECT_NEAR(point_ellipse_distance(2.0, 0.7, y0, y1), best, 1e-8) << y0 << " " << y1;
    }
}

TEST(GeneralizedDisk, StraightEllipticCylinderVolumesSumToPiABLength) {
    const double L = 7.0, A = 2.0, B = 0.5;
    DiskLayout layout;
    layout.core_radius = 0.25;
    layout.layers = 3;
    layout.s_t = 5;
    layout.s_u = 6;
    for (const Spline1& theta : {constant(0.0), Spline1({0.0, 3.0})}) {  // with and without twist
        const GeneralizedCylinder c = straight(L, constant(A), constant(B), theta);
        double shells = 0;
        for (const Hsv& h : hsv_index(layout)) shells += hsv_volume(c, layout, h.i, h.layer, h.k);
        const double core = core_volume(c, layout);
        // |det J| = L·A·B·v exactly, which 4-point Gauss integrates exactly: rounding only (1e-12).
        std::printf("straight cylinder: shells %.12f + core %.12f vs πAB·L %.12f\n", shells, core, kPi * A * B * L);
        EXPECT_NEAR(shells + core, kPi * A * B * L, 1e-12 * kPi * A * B * L);
        EXPECT_NEAR(core, kPi * A * B * L * 0.0625, 1e-12 * kPi * A * B * L);
    }
    // A tapered cylinder: A(t) = 2 − t, B(t) = 1 − 0.5 t: V = πL ∫(2 − t)(1 − t/2) dt = πL·(7/6).
    const GeneralizedCylinder tapered = straight(L, Spline1({2.0, 1.0}), Spline1({1.0, 0.5}), constant(0.4));
    double total = core_volume(tapered, layout);
    for (const Hsv& h : hsv_index(layout)) total += hsv_volume(tapered, layout, h.i, h.layer, h.k);
    EXPECT_NEAR(total, kPi * L * 7.0 / 6.0, 1e-12 * total);
}

TEST(GeneralizedDisk, HsvIndexPointsToItsTwoSectors) {
    DiskLayout layout;
    layout.layers = 3;
    layout.s_t = 4;
    layout.s_u = 5;
    const std::vector<Hsv> hsvs = hsv_index(layout);
    ASSERT_EQ(hsvs.size(), layout.hsv_count());
    EXPECT_EQ(layout.sector_count(), 5u * 3 * 5);
    for (const Hsv& h : hsvs) {
        const SectorRef top = sector_ref(layout, h.top), bottom = sector_ref(layout, h.bottom);
        EXPECT_EQ(top.plane, h.i);
        EXPECT_EQ(bottom.plane, h.i + 1);
        EXPECT_EQ(top.layer, h.layer);
        EXPECT_EQ(bottom.layer, h.layer);
        EXPECT_EQ(top.sector, h.k);
        EXPECT_EQ(bottom.sector, h.k);
    }
}

TEST(GeneralizedDisk, SectorExtentsOfACircularCylinder) {
    // Circle of radius R: a sector's width is the arc (2π/s_u)·R·v_mid, its depth R·Δv (exact to rounding).
    const double R = 1.5;
    DiskLayout layout;
    const GeneralizedCylinder c = straight(4.0, constant(R), constant(R), constant(0.0));
    const SectorShape s = sector_shape(c, layout, 2, 1, 3);
    const double vm = 0.5 * (layout.layer_v(1) + layout.layer_v(2));
    EXPECT_NEAR(s.width, 2 * kPi / layout.s_u * R * vm, 1e-12);
    EXPECT_NEAR(s.depth, R * (layout.layer_v(2) - layout.layer_v(1)), 1e-12);
}

TEST(GeneralizedDisk, MeshNormalsAgreeWithSurfaceDerivatives) {
    const GeneralizedCylinder c(helix(2.0, 0.5, 1.0), Spline1({0.3, 0.5, 0.2, 0.25}), Spline1({0.15, 0.2, 0.1}),
                                Spline1({0.0, 1.0, 2.5, 3.0}));
    DiskLayout layout;
    double worst = 0, worst_face = 1;
    for (int j = 0; j < layout.layers; ++j) {
        const LayerMesh m = layer_mesh(c, layout, j);
        ASSERT_EQ(m.position.size(), static_cast<std::size_t>(m.rows * m.columns));
        const double h = 1e-5;
        for (int r = 0; r < m.rows; r += 3)
            for (int q = 0; q < m.columns; ++q) {
                const std::size_t id = static_cast<std::size_t>(r * m.columns + q);
                const double t = m.texcoord[id].y, u = 2 * kPi * m.texcoord[id].x;
                const double t0 = std::max(t - h, 0.0), t1 = std::min(t + h, 1.0);
                const glm::dvec3 dt = (c.point(t1, m.v, u) - c.point(t0, m.v, u)) / (t1 - t0);
                const glm::dvec3 du = (c.point(t, m.v, u + h) - c.point(t, m.v, u - h)) / (2 * h);
                // The outward normal is ∂P/∂u × ∂P/∂t = −(∂P/∂t × ∂P/∂u) (frame convention in the header).
                const glm::dvec3 expected = -glm::normalize(glm::cross(dt, du));
                worst = std::max(worst, 1 - glm::dot(glm::dvec3(m.normal[id]), expected));
                // Outward: the normal points away from the axis.
                EXPECT_GT(glm::dot(glm::dvec3(m.normal[id]), glm::dvec3(m.position[id]) - c.position(t)), 0.0);
            }
        // Triangles wind counter-clockwise seen from outside.
        for (std::size_t tri = 0; tri < m.indices.size(); tri += 3) {
            const glm::vec3 a = m.position[m.indices[tri]], b = m.position[m.indices[tri + 1]], d = m.position[m.indices[tri + 2]];
            const glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
            worst_face = std::min(worst_face, static_cast<double>(glm::dot(n, m.normal[m.indices[tri]])));
        }
    }
    std::printf("mesh normals: worst 1 - cos(angle) = %.2e; worst face·vertex normal = %.3f\n", worst, worst_face);
    // float storage of the normal (~1e-7) and one-sided differences at t = 0, 1 (~h).
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(worst_face, 0.5);
}

}  // namespace
}  // namespace coif
