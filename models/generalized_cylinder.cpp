#include "models/generalized_cylinder.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "models/core/units.h"

namespace coif {

namespace {

// 5-point Gauss–Legendre on [0, 1].
constexpr double kGaussX[5] = {0.04691007703066800, 0.23076534494715845, 0.5, 0.76923465505284155, 0.95308992296933200};
constexpr double kGaussW[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444, 0.23931433524968324,
                               0.11846344252809454};

glm::dvec3 perpendicular_unit(const glm::dvec3& v, const glm::dvec3& t) {
    return glm::normalize(v - glm::dot(v, t) * t);
}

}  // namespace

glm::dvec3 SurfacePoint::normal() const {
    const glm::dvec3 c = glm::cross(d_du, d_dt);
    const double l = glm::length(c);
    if (l > 0) return c / l;
    const double r = glm::length(d_dv);
    return r > 0 ? d_dv / r : glm::dvec3(0);
}

GeneralizedCylinder::GeneralizedCylinder(Spline3 trajectory, Spline1 a, Spline1 b, Spline1 theta)
    : trajectory_(std::move(trajectory)), a_(std::move(a)), b_(std::move(b)), theta_(std::move(theta)) {
    if (trajectory_.empty() || a_.empty() || b_.empty() || theta_.empty())
        throw std::invalid_argument("generalized cylinder: a spline has no control points");
    // Arc length s(τ) on a fine uniform τ grid (5-point Gauss per interval), then τ(t) at uniform t
    // by inverting it (Newton inside the bracketing interval).
    constexpr int kTauGrid = 4 * kArcTable;
    std::vector<double> s(kTauGrid + 1, 0.0);
    const auto speed = [&](double tau) { return glm::length(trajectory_.derivative(tau)); };
    for (int j = 0; j < kTauGrid; ++j) {
        double acc = 0;
        for (int g = 0; g < 5; ++g) acc += kGaussW[g] * speed((j + kGaussX[g]) / kTauGrid);
        s[j + 1] = s[j] + acc / kTauGrid;
    }
    length_ = s.back();
    if (!(length_ > 0) || !std::isfinite(length_))
        throw std::invalid_argument("generalized cylinder: the trajectory has zero or non-finite length");
    tau_of_t_.resize(kArcTable + 1);
    dtau_dt_.resize(kArcTable + 1);
    int j = 0;
    for (int k = 0; k <= kArcTable; ++k) {
        const double target = length_ * k / kArcTable;
        while (j < kTauGrid - 1 && s[j + 1] < target) ++j;
        const double t0 = static_cast<double>(j) / kTauGrid, t1 = static_cast<double>(j + 1) / kTauGrid;
        double tau = t0 + (t1 - t0) * std::clamp((target - s[j]) / std::max(s[j + 1] - s[j], 1e-300), 0.0, 1.0);
        for (int it = 0; it < 4; ++it) {
            double acc = 0;  // s(τ) − s(t0) by Gauss on [t0, τ]
            for (int g = 0; g < 5; ++g) acc += kGaussW[g] * speed(t0 + (tau - t0) * kGaussX[g]);
            const double f = s[j] + acc * (tau - t0) - target;
            const double d = speed(tau);
            if (d <= 0) break;
            tau = std::clamp(tau - f / d, t0, t1);
        }
        if (k == 0) tau = 0;
        if (k == kArcTable) tau = 1;
        tau_of_t_[k] = tau;
        const double sp = speed(tau);
        dtau_dt_[k] = sp > 0 ? length_ / sp : 0.0;
    }
    // Rotation-minimizing frame by double reflection (Wang et al. 2008, Algorithm "double reflection").
    node_position_.resize(kFrameTable + 1);
    node_frame_.resize(kFrameTable + 1);
    for (int k = 0; k <= kFrameTable; ++k) node_position_[k] = position(static_cast<double>(k) / kFrameTable);
    Frame f0;
    f0.tangent = tangent(0.0);
    const glm::dvec3 hint = std::abs(f0.tangent.z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
    f0.normal = perpendicular_unit(hint, f0.tangent);
    f0.binormal = glm::cross(f0.tangent, f0.normal);
    node_frame_[0] = f0;
    for (int k = 1; k <= kFrameTable; ++k) {
        const double t = static_cast<double>(k) / kFrameTable;
        node_frame_[k] = frame_with_tangent(t, node_position_[k], tangent(t));
    }
}

double GeneralizedCylinder::tau(double t) const {
    t = std::clamp(t, 0.0, 1.0);
    const double x = t * kArcTable;
    const int k = std::min(static_cast<int>(x), kArcTable - 1);
    const double h = 1.0 / kArcTable, w = x - k;
    // Cubic Hermite with the exact node derivatives dτ/dt = L / |T'(τ)|.
    const double w2 = w * w, w3 = w2 * w;
    const double h00 = 2 * w3 - 3 * w2 + 1, h10 = w3 - 2 * w2 + w, h01 = -2 * w3 + 3 * w2, h11 = w3 - w2;
    return h00 * tau_of_t_[k] + h10 * h * dtau_dt_[k] + h01 * tau_of_t_[k + 1] + h11 * h * dtau_dt_[k + 1];
}

glm::dvec3 GeneralizedCylinder::position(double t) const { return trajectory_(tau(t)); }

glm::dvec3 GeneralizedCylinder::tangent(double t) const {
    const double tu = tau(t);
    glm::dvec3 d = trajectory_.derivative(tu);
    double l = glm::length(d);
    if (!(l > 0)) {  // a cusp of the control polygon: fall back to a nearby chord
        d = trajectory_(std::min(tu + 1e-6, 1.0)) - trajectory_(std::max(tu - 1e-6, 0.0));
        l = glm::length(d);
    }
    return d / l;
}

glm::dvec3 GeneralizedCylinder::unit_tangent_derivative(double t) const {
    const double tu = tau(t);
    const auto e = trajectory_.evaluate(tu, 2);
    const double sp = glm::length(e[1]);
    if (!(sp > 0)) return glm::dvec3(0);
    const glm::dvec3 th = e[1] / sp;
    const glm::dvec3 dth_dtau = (e[2] - glm::dot(e[2], th) * th) / sp;
    return dth_dtau * (length_ / sp);
}

Frame GeneralizedCylinder::frame_with_tangent(double t, const glm::dvec3& x, const glm::dvec3& tangent) const {
    // One double-reflection step from the preceding table node to (x, tangent).
    const int k = std::clamp(static_cast<int>(std::floor(t * kFrameTable)), 0, kFrameTable);
    const int from = (static_cast<double>(k) / kFrameTable >= t && k > 0) ? k - 1 : k;
    const Frame& f = node_frame_[from];
    Frame out;
    out.tangent = tangent;
    const glm::dvec3 v1 = x - node_position_[from];
    const double c1 = glm::dot(v1, v1);
    glm::dvec3 rL = f.normal, tL = f.tangent;
    if (c1 > 0) {
        rL = f.normal - (2.0 / c1) * glm::dot(v1, f.normal) * v1;
        tL = f.tangent - (2.0 / c1) * glm::dot(v1, f.tangent) * v1;
    }
    const glm::dvec3 v2 = tangent - tL;
    const double c2 = glm::dot(v2, v2);
    glm::dvec3 r = c2 > 0 ? rL - (2.0 / c2) * glm::dot(v2, rL) * v2 : rL;
    r = perpendicular_unit(r, tangent);  // removes rounding drift only
    out.normal = r;
    out.binormal = glm::cross(tangent, r);
    return out;
}

Frame GeneralizedCylinder::frame(double t) const {
    t = std::clamp(t, 0.0, 1.0);
    const double x = t * kFrameTable;
    const int k = static_cast<int>(std::round(x));
    if (std::abs(x - k) < 1e-12) return node_frame_[k];
    return frame_with_tangent(t, position(t), tangent(t));
}

std::array<glm::dvec3, 2> GeneralizedCylinder::ellipse_axes(double t) const {
    const Frame f = frame(t);
    const double th = theta_(t), c = std::cos(th), s = std::sin(th);
    return {c * f.normal + s * f.binormal, -s * f.normal + c * f.binormal};
}

SurfacePoint GeneralizedCylinder::surface(double t, double v, double u) const {
    t = std::clamp(t, 0.0, 1.0);
    const Frame f = frame(t);
    const auto A = a_.evaluate(t, 1), B = b_.evaluate(t, 1), th = theta_.evaluate(t, 1);
    const double c = std::cos(th[0]), s = std::sin(th[0]);
    const glm::dvec3 e1 = c * f.normal + s * f.binormal, e2 = -s * f.normal + c * f.binormal;
    // Rotation-minimizing frame: n' and b' are parallel to T̂ (n' = −(T̂'·n) T̂), so
    // e1' = θ' e2 − (T̂'·e1) T̂ and e2' = −θ' e1 − (T̂'·e2) T̂.
    const glm::dvec3 dT = unit_tangent_derivative(t);
    const glm::dvec3 de1 = th[1] * e2 - glm::dot(dT, e1) * f.tangent;
    const glm::dvec3 de2 = -th[1] * e1 - glm::dot(dT, e2) * f.tangent;
    const double cu = std::cos(u), su = std::sin(u);
    SurfacePoint p;
    p.d_dv = A[0] * cu * e1 + B[0] * su * e2;
    p.position = position(t) + v * p.d_dv;
    p.d_du = v * (-A[0] * su * e1 + B[0] * cu * e2);
    p.d_dt = length_ * f.tangent + v * (A[1] * cu * e1 + B[1] * su * e2 + A[0] * cu * de1 + B[0] * su * de2);
    return p;
}

CylinderCoordinates GeneralizedCylinder::locate(const glm::dvec3& x) const {
    // Closest point on the node polyline, then Newton on f(t) = (x − T(t))·T̂(t) with
    // f'(t) = −L + (x − T)·dT̂/dt.
    double best = 1e300, t = 0;
    for (int k = 0; k < kFrameTable; ++k) {
        const glm::dvec3 a = node_position_[k], d = node_position_[k + 1] - a;
        const double dd = glm::dot(d, d);
        const double w = dd > 0 ? std::clamp(glm::dot(x - a, d) / dd, 0.0, 1.0) : 0.0;
        const glm::dvec3 q = a + w * d;
        const double dist = glm::dot(x - q, x - q);
        if (dist < best) {
            best = dist;
            t = (k + w) / kFrameTable;
        }
    }
    double f = 0;
    glm::dvec3 p{0}, th{0};
    for (int it = 0; it < 6; ++it) {
        p = position(t);
        th = tangent(t);
        f = glm::dot(x - p, th);
        const double fp = -length_ + glm::dot(x - p, unit_tangent_derivative(t));
        if (std::abs(f) < 1e-12 * length_ || fp >= 0) break;
        const double next = std::clamp(t - f / fp, 0.0, 1.0);
        if (next == t) break;
        t = next;
    }
    p = position(t);
    th = tangent(t);
    f = glm::dot(x - p, th);
    CylinderCoordinates c;
    c.t = t;
    if ((t <= 0.0 && f < 0) || (t >= 1.0 && f > 0)) c.axial = std::abs(f);
    const glm::dvec3 d = x - p - f * th;
    const auto axes = ellipse_axes(t);
    c.in_plane = {glm::dot(d, axes[0]), glm::dot(d, axes[1])};
    const double A = std::max(a_(t), 1e-300), B = std::max(b_(t), 1e-300);
    const double xa = c.in_plane.x / A, xb = c.in_plane.y / B;
    c.v = std::sqrt(xa * xa + xb * xb);
    c.u = std::atan2(xb, xa);
    if (c.u < 0) c.u += kTwoPi;
    return c;
}

double GeneralizedCylinder::distance_outside(const glm::dvec3& x) const {
    const CylinderCoordinates c = locate(x);
    double planar = 0;
    if (c.v > 1.0) planar = point_ellipse_distance(a_(c.t), b_(c.t), c.in_plane.x, c.in_plane.y);
    return std::sqrt(planar * planar + c.axial * c.axial);
}

double point_ellipse_distance(double e0, double e1, double y0, double y1) {
    y0 = std::abs(y0);
    y1 = std::abs(y1);
    e0 = std::abs(e0);
    e1 = std::abs(e1);
    if (e0 < e1) {
        std::swap(e0, e1);
        std::swap(y0, y1);
    }
    if (e1 <= 0) {  // degenerate ellipse: a segment along the e0 axis
        const double dx = std::max(y0 - e0, 0.0);
        return std::sqrt(dx * dx + y1 * y1);
    }
    if (y1 > 0) {
        if (y0 > 0) {
            const double z0 = y0 / e0, z1 = y1 / e1, g = z0 * z0 + z1 * z1 - 1;
            if (g == 0) return 0;
            const double r0 = (e0 / e1) * (e0 / e1), n0 = r0 * z0;
            double s0 = z1 - 1, s1 = g < 0 ? 0 : std::hypot(n0, z1) - 1, s = 0;
            for (int i = 0; i < 200; ++i) {
                s = 0.5 * (s0 + s1);
                if (s == s0 || s == s1) break;
                const double ra = n0 / (s + r0), rb = z1 / (s + 1), gs = ra * ra + rb * rb - 1;
                if (gs > 0) s0 = s;
                else if (gs < 0) s1 = s;
                else break;
            }
            const double x0 = r0 * y0 / (s + r0), x1 = y1 / (s + 1);
            return std::hypot(x0 - y0, x1 - y1);
        }
        return std::abs(y1 - e1);
    }
    const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
    if (numer0 < denom0) {
        const double xde0 = numer0 / denom0;
        const double x0 = e0 * xde0, x1 = e1 * std::sqrt(std::max(0.0, 1 - xde0 * xde0));
        return std::hypot(x0 - y0, x1);
    }
    return std::abs(y0 - e0);
}

}  // namespace coif
