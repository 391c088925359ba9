#pragma once
// Clamped uniform B-splines on [0, 1], the curve type of 004 §3.2 (the trajectory T(t) and the 1D
// profiles A(t), B(t), θ(t) of a hair cluster, eqs. 1–2).
//
// With n control points the degree is p = min(3, n − 1): one control point is a constant, two a
// line, three a quadratic, four or more a cubic. The knot vector is clamped (p + 1 repeated end
// knots) and uniform inside, so the curve starts at the first control point and ends at the last,
// which makes hand-written style files predictable. Evaluation is de Boor's basis-function form
// (Piegl & Tiller, The NURBS Book, A2.2/A2.3) in double precision.
#include <array>
#include <cstddef>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace coif {

template <class T>
class BSpline {
public:
    BSpline() = default;
    explicit BSpline(std::vector<T> control) : control_(std::move(control)) {}

    const std::vector<T>& control() const { return control_; }
    std::vector<T>& control() { return control_; }
    std::size_t size() const { return control_.size(); }
    bool empty() const { return control_.empty(); }
    int degree() const { return control_.size() < 4 ? static_cast<int>(control_.size()) - 1 : 3; }

    // Value and the first two derivatives with respect to the parameter; x is clamped to [0, 1].
    T operator()(double x) const { return evaluate(x, 0)[0]; }
    T derivative(double x) const { return evaluate(x, 1)[1]; }
    // out[0] = value, out[1] = first derivative, out[2] = second (zero where the degree is lower).
    std::array<T, 3> evaluate(double x, int derivatives) const;

private:
    std::vector<T> control_;
};

using Spline1 = BSpline<double>;
using Spline3 = BSpline<glm::dvec3>;

// The p+1 non-zero basis functions at x and their derivatives (rows 0..2), and the index of the first
// control point they weigh. Exposed for least-squares fitting.
struct BasisAt {
    int first = 0;
    int count = 0;  // p + 1
    double value[3][4] = {};
};
BasisAt bspline_basis(std::size_t control_count, double x, int derivatives);

// Least-squares fit of a spline with `control_count` control points to samples (x_i, y_i), x in
// [0, 1]. `smoothing` ≥ 0 adds smoothing·Σ|second difference of control points|² (a discrete
// bending energy) so that sparse or noisy samples still give a well-posed, calm curve. The end
// control points are free (least squares), not pinned to the samples.
Spline1 fit_bspline(std::span<const double> x, std::span<const double> y, std::size_t control_count, double smoothing);
Spline3 fit_bspline(std::span<const double> x, std::span<const glm::dvec3> y, std::size_t control_count, double smoothing);

}  // namespace coif
