#include "models/bspline.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace coif {

namespace {

// Clamped uniform knot vector for n control points of degree p: p+1 zeros, interior knots
// j/(n−p) for j = 1..n−p−1, p+1 ones.
double knot(std::size_t n, int p, int i) {
    const int m = static_cast<int>(n) - p;  // number of spans
    if (i <= p) return 0.0;
    if (i >= static_cast<int>(n)) return 1.0;
    return static_cast<double>(i - p) / m;
}

// Solves the symmetric positive definite system M x = r (dense, small) by Cholesky; M is n×n
// row-major. Columns of r: k right-hand sides.
void solve_spd(std::vector<double>& M, std::vector<double>& r, std::size_t n, std::size_t k) {
    for (std::size_t j = 0; j < n; ++j) {
        double d = M[j * n + j];
        for (std::size_t q = 0; q < j; ++q) d -= M[j * n + q] * M[j * n + q];
        d = std::sqrt(std::max(d, 1e-300));
        M[j * n + j] = d;
        for (std::size_t i = j + 1; i < n; ++i) {
            double s = M[i * n + j];
            for (std::size_t q = 0; q < j; ++q) s -= M[i * n + q] * M[j * n + q];
            M[i * n + j] = s / d;
        }
    }
    for (std::size_t c = 0; c < k; ++c) {
        for (std::size_t i = 0; i < n; ++i) {
            double s = r[i * k + c];
            for (std::size_t q = 0; q < i; ++q) s -= M[i * n + q] * r[q * k + c];
            r[i * k + c] = s / M[i * n + i];
        }
        for (std::size_t i = n; i-- > 0;) {
            double s = r[i * k + c];
            for (std::size_t q = i + 1; q < n; ++q) s -= M[q * n + i] * r[q * k + c];
            r[i * k + c] = s / M[i * n + i];
        }
    }
}

// Normal equations of the smoothed least-squares problem, with k value columns.
std::vector<double> fit_columns(std::span<const double> x, const std::vector<double>& y, std::size_t k,
                                std::size_t n, double smoothing) {
    std::vector<double> M(n * n, 0.0), r(n * k, 0.0);
    for (std::size_t i = 0; i < x.size(); ++i) {
        const BasisAt b = bspline_basis(n, x[i], 0);
        for (int a = 0; a < b.count; ++a) {
            const std::size_t ia = static_cast<std::size_t>(b.first + a);
            for (int c = 0; c < b.count; ++c) M[ia * n + static_cast<std::size_t>(b.first + c)] += b.value[0][a] * b.value[0][c];
            for (std::size_t c = 0; c < k; ++c) r[ia * k + c] += b.value[0][a] * y[i * k + c];
        }
    }
    // Bending regulariser on second differences of the control polygon, plus a tiny ridge so that
    // control points with no samples under their support stay defined.
    double diag = 0;
    for (std::size_t j = 0; j < n; ++j) diag = std::max(diag, M[j * n + j]);
    const double ridge = 1e-12 * std::max(diag, 1.0);
    for (std::size_t j = 0; j < n; ++j) M[j * n + j] += ridge;
    if (n >= 3 && smoothing > 0) {
        for (std::size_t j = 0; j + 2 < n; ++j) {
            const double w[3] = {1.0, -2.0, 1.0};
            for (int a = 0; a < 3; ++a)
                for (int c = 0; c < 3; ++c) M[(j + a) * n + (j + c)] += smoothing * w[a] * w[c];
        }
    }
    solve_spd(M, r, n, k);
    return r;
}

}  // namespace

BasisAt bspline_basis(std::size_t n, double x, int derivatives) {
    BasisAt out;
    if (n == 0) return out;
    const int p = n < 4 ? static_cast<int>(n) - 1 : 3;
    out.count = p + 1;
    if (p == 0) {
        out.value[0][0] = 1.0;
        return out;
    }
    x = std::clamp(x, 0.0, 1.0);
    const int spans = static_cast<int>(n) - p;
    int span = std::min(static_cast<int>(x * spans), spans - 1) + p;  // knot index with knot[span] <= x < knot[span+1]
    out.first = span - p;
    // A2.3 of The NURBS Book: ndu holds basis functions and knot differences.
    double ndu[4][4] = {}, left[4] = {}, right[4] = {};
    ndu[0][0] = 1.0;
    for (int j = 1; j <= p; ++j) {
        left[j] = x - knot(n, p, span + 1 - j);
        right[j] = knot(n, p, span + j) - x;
        double saved = 0.0;
        for (int r = 0; r < j; ++r) {
            ndu[j][r] = right[r + 1] + left[j - r];
            const double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int j = 0; j <= p; ++j) out.value[0][j] = ndu[j][p];
    const int nd = std::min(derivatives, std::min(p, 2));
    double a[2][4] = {};
    for (int r = 0; r <= p; ++r) {
        int s1 = 0, s2 = 1;
        a[0][0] = 1.0;
        for (int k = 1; k <= nd; ++k) {
            double d = 0.0;
            const int rk = r - k, pk = p - k;
            if (r >= k) {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            const int j1 = rk >= -1 ? 1 : -rk;
            const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
            for (int j = j1; j <= j2; ++j) {
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                d += a[s2][j] * ndu[rk + j][pk];
            }
            if (r <= pk) {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            out.value[k][r] = d;
            std::swap(s1, s2);
        }
    }
    double factor = p;
    for (int k = 1; k <= nd; ++k) {
        for (int j = 0; j <= p; ++j) out.value[k][j] *= factor;
        factor *= (p - k);
    }
    return out;
}

template <class T>
std::array<T, 3> BSpline<T>::evaluate(double x, int derivatives) const {
    std::array<T, 3> out{T(0), T(0), T(0)};
    const BasisAt b = bspline_basis(control_.size(), x, derivatives);
    for (int k = 0; k <= std::min(derivatives, 2); ++k)
        for (int j = 0; j < b.count; ++j) out[static_cast<std::size_t>(k)] += b.value[k][j] * control_[static_cast<std::size_t>(b.first + j)];
    return out;
}

template class BSpline<double>;
template class BSpline<glm::dvec3>;

Spline1 fit_bspline(std::span<const double> x, std::span<const double> y, std::size_t n, double smoothing) {
    std::vector<double> cols(y.begin(), y.end());
    return Spline1(fit_columns(x, cols, 1, n, smoothing));
}

Spline3 fit_bspline(std::span<const double> x, std::span<const glm::dvec3> y, std::size_t n, double smoothing) {
    std::vector<double> cols(y.size() * 3);
    for (std::size_t i = 0; i < y.size(); ++i)
        for (int c = 0; c < 3; ++c) cols[i * 3 + static_cast<std::size_t>(c)] = y[i][c];
    const std::vector<double> r = fit_columns(x, cols, 3, n, smoothing);
    std::vector<glm::dvec3> control(n);
    for (std::size_t j = 0; j < n; ++j) control[j] = {r[j * 3], r[j * 3 + 1], r[j * 3 + 2]};
    return Spline3(std::move(control));
}

}  // namespace coif
