#include "models/style_fit.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <random>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "models/core/random.h"
#include "models/core/units.h"

namespace coif {

namespace {

constexpr int kRepresentativeSamples = 48;  // points of a cluster's mean curve
constexpr double kMaxCrossingV = 4.0;       // crossings farther out than this (relative) are not the cluster's
// A member's crossing of the plane at t is searched within ±kArcWindow·(longest member) of arc length
// t·(longest member) from its root: the mean curve is at most ~25 % shorter than wavy members.
constexpr double kArcWindow = 0.25;
// A plane's principal axes are estimated only from at least this share of the cluster's members (and 3);
// skipped planes take A, B, θ from the spline through the others. A guard against planes crossed by a few
// strands only: on harolongo at 64 clusters it changes nothing (the tip planes that made the stray
// cluster had 26–36 crossings of 73; kRepresentativeLengthQuantile below is what removed it).
constexpr double kMinProfileCrossingShare = 0.1;
// measured on harolongo at 64 clusters (style import --check): 1.0 (the longest member) strays 9.1 cluster
// radii, IoU 0.934, blurred PSNR 27.0 dB; 0.9: 4.1, 0.942, 27.8 dB; 0.75: 4.1, 0.940, 26.7 dB. Points inside
// their envelope fall from 91.9 to 89.9 % (the longest members' last tenth is outside).
constexpr double kRepresentativeLengthQuantile = 0.9;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Polyline {
    std::vector<glm::dvec3> p;
    std::vector<double> s;  // cumulative arc length
    double length() const { return s.back(); }
    glm::dvec3 at(double arc) const {
        if (arc <= 0) return p.front();
        if (arc >= s.back()) return p.back();
        const std::size_t k = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), arc) - s.begin()) - 1;
        const double w = (arc - s[k]) / std::max(s[k + 1] - s[k], 1e-300);
        return p[k] + w * (p[k + 1] - p[k]);
    }
};

Polyline make_polyline(const Strands& st, std::size_t i, const glm::dmat3& R) {
    Polyline l;
    for (std::uint32_t k = st.offsets[i]; k < st.offsets[i + 1]; ++k) l.p.push_back(R * glm::dvec3(st.points[k]));
    l.s.resize(l.p.size(), 0.0);
    for (std::size_t k = 1; k < l.p.size(); ++k) l.s[k] = l.s[k - 1] + glm::length(l.p[k] - l.p[k - 1]);
    return l;
}

// ── k-means on shape features ──
std::vector<int> kmeans(const std::vector<std::vector<double>>& f, int k, int iterations, std::uint32_t seed, Progress* bar) {
    const std::size_t n = f.size(), d = f[0].size();
    Rng rng = seeded_rng(seed);
    const auto dist2 = [&](const std::vector<double>& a, const std::vector<double>& b) {
        double acc = 0;
        for (std::size_t q = 0; q < d; ++q) acc += (a[q] - b[q]) * (a[q] - b[q]);
        return acc;
    };
    // k-means++ seeding.
    std::vector<std::vector<double>> centres;
    centres.push_back(f[std::uniform_int_distribution<std::size_t>(0, n - 1)(rng)]);
    std::vector<double> nearest(n, std::numeric_limits<double>::max());
    while (static_cast<int>(centres.size()) < k) {
        double total = 0;
        for (std::size_t i = 0; i < n; ++i) {
            nearest[i] = std::min(nearest[i], dist2(f[i], centres.back()));
            total += nearest[i];
        }
        double pick = std::uniform_real_distribution<double>(0, total)(rng);
        std::size_t chosen = n - 1;
        for (std::size_t i = 0; i < n; ++i) {
            pick -= nearest[i];
            if (pick <= 0) {
                chosen = i;
                break;
            }
        }
        centres.push_back(f[chosen]);
    }
    std::vector<int> label(n, -1);
    for (int it = 0; it < iterations; ++it) {
        // Assignment: each point's nearest centre, independent of the others (and of the thread count).
        std::atomic<bool> changed{false};
        parallel_for(n, 0, [&](std::size_t i) {
            int best = 0;
            double bd = std::numeric_limits<double>::max();
            for (int c = 0; c < k; ++c) {
                const double dd = dist2(f[i], centres[static_cast<std::size_t>(c)]);
                if (dd < bd) {
                    bd = dd;
                    best = c;
                }
            }
            if (label[i] != best) {
                label[i] = best;
                changed.store(true, std::memory_order_relaxed);
            }
        });
        if (bar) bar->advance();
        bool any = changed.load();
        // Update, re-seeding empty clusters at the point farthest from its centre.
        std::vector<std::vector<double>> sum(static_cast<std::size_t>(k), std::vector<double>(d, 0.0));
        std::vector<std::size_t> count(static_cast<std::size_t>(k), 0);
        for (std::size_t i = 0; i < n; ++i) {
            const auto c = static_cast<std::size_t>(label[i]);
            ++count[c];
            for (std::size_t q = 0; q < d; ++q) sum[c][q] += f[i][q];
        }
        for (std::size_t c = 0; c < static_cast<std::size_t>(k); ++c) {
            if (count[c] == 0) {
                std::size_t far = 0;
                double fd = -1;
                for (std::size_t i = 0; i < n; ++i) {
                    const double dd = dist2(f[i], centres[static_cast<std::size_t>(label[i])]);
                    if (dd > fd) {
                        fd = dd;
                        far = i;
                    }
                }
                centres[c] = f[far];
                label[far] = static_cast<int>(c);
                any = true;
                continue;
            }
            for (std::size_t q = 0; q < d; ++q) centres[c][q] = sum[c][q] / static_cast<double>(count[c]);
        }
        if (!any) break;
    }
    return label;
}

// The crossing of a polyline with the plane through `o` with normal `t`, nearest to `o`, among the
// segments within `window` of arc length `arc` from the root (a wavy strand crosses the infinite plane
// far from the cluster too); near the ends, an end point within `end_slack` of the plane counts
// (roots sit on the root plane).
std::optional<glm::dvec3> plane_crossing(const Polyline& l, const glm::dvec3& o, const glm::dvec3& t, double end_slack,
                                         double arc, double window) {
    std::optional<glm::dvec3> best;
    double bd = std::numeric_limits<double>::max();
    double prev = glm::dot(l.p[0] - o, t);
    for (std::size_t k = 1; k < l.p.size(); ++k) {
        const double cur = glm::dot(l.p[k] - o, t);
        const bool near = l.s[k] >= arc - window && l.s[k - 1] <= arc + window;
        if (near && ((prev <= 0 && cur > 0) || (prev >= 0 && cur < 0) || cur == 0)) {
            const double w = prev == cur ? 0.0 : prev / (prev - cur);
            const glm::dvec3 x = l.p[k - 1] + w * (l.p[k] - l.p[k - 1]);
            const double d = glm::dot(x - o, x - o);
            if (d < bd) {
                bd = d;
                best = x;
            }
        }
        prev = cur;
    }
    if (!best) {
        for (int end = 0; end < 2; ++end) {
            const glm::dvec3& e = end == 0 ? l.p.front() : l.p.back();
            const bool in_window = end == 0 ? arc - window <= 0 : arc + window >= l.length();
            if (in_window && std::abs(glm::dot(e - o, t)) <= end_slack) {
                const glm::dvec3 x = e - glm::dot(e - o, t) * t;
                const double d = glm::dot(x - o, x - o);
                if (d < bd) {
                    bd = d;
                    best = x;
                }
            }
        }
    }
    return best;
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const double x = q * static_cast<double>(v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(x);
    if (i + 1 >= v.size()) return v.back();
    return v[i] + (x - i) * (v[i + 1] - v[i]);
}

struct FittedCluster {
    std::vector<std::size_t> members;
    std::shared_ptr<GeneralizedCylinder> shape;
    std::shared_ptr<DensitySource> density;
    std::vector<bool> member_crosses;  // per member: crosses ≥ 1 sector plane
};

FittedCluster fit_cluster(const std::vector<Polyline>& lines, std::vector<std::size_t> members, const FitOptions& o,
                          double r_min) {
    FittedCluster fc;
    fc.members = std::move(members);
    const DiskLayout& layout = o.layout;
    // Representative curve: mean at equal absolute arc length, up to the length that a share
    // kRepresentativeLengthQuantile of the members reach (beyond it the mean is of a few members and jumps
    // as each drops out, swinging the curve's end).
    double lmax = 0;
    std::vector<double> lengths;
    for (std::size_t m : fc.members) {
        lmax = std::max(lmax, lines[m].length());
        lengths.push_back(lines[m].length());
    }
    const double lrep = quantile(lengths, kRepresentativeLengthQuantile);
    std::vector<glm::dvec3> rep(kRepresentativeSamples);
    for (int k = 0; k < kRepresentativeSamples; ++k) {
        const double arc = lrep * k / (kRepresentativeSamples - 1);
        glm::dvec3 acc(0);
        int n = 0;
        for (std::size_t m : fc.members)
            if (lines[m].length() >= arc - 1e-12 * lmax) {
                acc += lines[m].at(arc);
                ++n;
            }
        rep[static_cast<std::size_t>(k)] = n ? acc / static_cast<double>(n) : rep[static_cast<std::size_t>(k - 1)];
    }
    std::vector<double> x(rep.size(), 0.0);
    for (std::size_t k = 1; k < rep.size(); ++k) x[k] = x[k - 1] + glm::length(rep[k] - rep[k - 1]);
    const double total = x.back();
    for (double& v : x) v = total > 0 ? v / total : 0.0;
    const Spline3 traj = fit_bspline(x, rep, static_cast<std::size_t>(o.trajectory_control_points), 1e-3);
    const GeneralizedCylinder axis(traj, Spline1({1.0}), Spline1({1.0}), Spline1({0.0}));

    // A, B, θ from principal axes of crossings on 2·s_t + 1 planes.
    const int planes = 2 * layout.s_t + 1;
    std::vector<double> tq, Aq, Bq, Thq;
    double prev_theta = 0;
    bool have_prev = false;
    const double slack = 0.05 * lmax;
    for (int q = 0; q < planes; ++q) {
        const double t = static_cast<double>(q) / (planes - 1);
        const glm::dvec3 o3 = axis.position(t);
        const Frame f = axis.frame(t);
        std::vector<glm::dvec2> pts;
        for (std::size_t m : fc.members)
            if (auto c = plane_crossing(lines[m], o3, f.tangent, slack, t * lmax, kArcWindow * lmax)) pts.emplace_back(glm::dot(*c - o3, f.normal), glm::dot(*c - o3, f.binormal));
        // Crossings far out are not the cluster's own (a wavy strand crosses the infinite plane elsewhere too):
        // keep those within kMaxCrossingV times the median distance from the axis, as the density does.
        // Measured on harolongo at 64 clusters: median cluster stray 2.25 → 1.97 radii, the worst unchanged.
        if (!pts.empty()) {
            std::vector<double> r(pts.size());
            for (std::size_t i = 0; i < pts.size(); ++i) r[i] = glm::length(pts[i]);
            std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
            const double keep = kMaxCrossingV * std::max(r[r.size() / 2], r_min);
            std::erase_if(pts, [keep](const glm::dvec2& p) { return glm::length(p) > keep; });
        }
        if (pts.size() < std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(kMinProfileCrossingShare * double(fc.members.size())))))
            continue;
        double mxx = 0, myy = 0, mxy = 0;
        for (const auto& p : pts) {
            mxx += p.x * p.x;
            myy += p.y * p.y;
            mxy += p.x * p.y;
        }
        const double n = static_cast<double>(pts.size());
        mxx /= n;
        myy /= n;
        mxy /= n;
        double theta = 0.5 * std::atan2(2 * mxy, mxx - myy);
        const double c = std::cos(theta), s = std::sin(theta);
        double s1 = std::sqrt(std::max(c * c * mxx + 2 * c * s * mxy + s * s * myy, 0.0));
        double s2 = std::sqrt(std::max(s * s * mxx - 2 * c * s * mxy + c * c * myy, 0.0));
        s1 = std::max(s1, r_min);
        s2 = std::max(s2, r_min);
        std::vector<double> radius;
        radius.reserve(pts.size());
        for (const auto& p : pts) {
            const double a = (c * p.x + s * p.y) / s1, b = (-s * p.x + c * p.y) / s2;
            radius.push_back(std::sqrt(a * a + b * b));
        }
        const double k = std::max(quantile(radius, o.coverage), 1e-6);
        double A = std::max(k * s1, r_min), B = std::max(k * s2, r_min);
        // Unwrap: θ and θ + π/2 (A, B swapped) describe the same ellipse; pick the nearest turn.
        if (have_prev) {
            double best = theta, bestA = A, bestB = B, bd = std::numeric_limits<double>::max();
            for (int m = -8; m <= 8; ++m) {
                const double cand = theta + m * kPi / 2;
                if (std::abs(cand - prev_theta) < bd) {
                    bd = std::abs(cand - prev_theta);
                    best = cand;
                    bestA = (m % 2 == 0) ? A : B;
                    bestB = (m % 2 == 0) ? B : A;
                }
            }
            theta = best;
            A = bestA;
            B = bestB;
        }
        prev_theta = theta;
        have_prev = true;
        tq.push_back(t);
        Aq.push_back(A);
        Bq.push_back(B);
        Thq.push_back(theta);
    }
    if (tq.empty()) {  // no crossings at all (cannot happen for a member with ≥ 2 points): a thin tube
        tq = {0.0, 1.0};
        Aq = Bq = {r_min, r_min};
        Thq = {0.0, 0.0};
    }
    const auto n_prof = static_cast<std::size_t>(std::min<int>(o.profile_control_points, static_cast<int>(tq.size())));
    Spline1 As = fit_bspline(tq, Aq, n_prof, 1e-3), Bs = fit_bspline(tq, Bq, n_prof, 1e-3), Ts = fit_bspline(tq, Thq, n_prof, 1e-3);
    for (double& a : As.control()) a = std::max(a, r_min);
    for (double& b : Bs.control()) b = std::max(b, r_min);
    fc.shape = std::make_shared<GeneralizedCylinder>(traj, std::move(As), std::move(Bs), std::move(Ts));

    // Density: member crossings of the s_t + 1 sector planes.
    fc.density = std::make_shared<DensitySource>();
    fc.density->kind = DensitySource::Kind::Strands;
    fc.density->strand_weight = o.store_every;
    fc.member_crosses.assign(fc.members.size(), false);
    std::vector<std::vector<std::optional<glm::dvec2>>> vu(fc.members.size(),
                                                           std::vector<std::optional<glm::dvec2>>(static_cast<std::size_t>(layout.s_t) + 1));
    for (int i = 0; i <= layout.s_t; ++i) {
        const double t = layout.plane_t(i);
        const glm::dvec3 o3 = fc.shape->position(t);
        const glm::dvec3 T = fc.shape->tangent(t);
        const auto e = fc.shape->ellipse_axes(t);
        const double A = fc.shape->a(t), B = fc.shape->b(t);
        for (std::size_t m = 0; m < fc.members.size(); ++m) {
            const auto c = plane_crossing(lines[fc.members[m]], o3, T, slack, t * lmax, kArcWindow * lmax);
            if (!c) continue;
            const double a = glm::dot(*c - o3, e[0]) / A, b = glm::dot(*c - o3, e[1]) / B;
            const double v = std::sqrt(a * a + b * b);
            if (v > kMaxCrossingV) continue;
            double u = std::atan2(b, a);
            if (u < 0) u += kTwoPi;
            vu[m][static_cast<std::size_t>(i)] = glm::dvec2(v, u);
            fc.member_crosses[m] = true;
        }
    }
    for (std::size_t m = 0; m < fc.members.size(); ++m) {
        if (o.store_every > 1 && fc.members[m] % static_cast<std::size_t>(o.store_every) != 0) continue;
        StrandRun run;
        for (int i = 0; i <= layout.s_t + 1; ++i) {
            const bool have = i <= layout.s_t && vu[m][static_cast<std::size_t>(i)].has_value();
            if (have) {
                if (run.vu.empty()) run.first_plane = i;
                run.vu.push_back(*vu[m][static_cast<std::size_t>(i)]);
            } else if (!run.vu.empty()) {
                fc.density->strands.push_back(std::move(run));
                run = StrandRun{};
            }
        }
    }
    return fc;
}

// Envelope descriptor for macro-cluster matching: axis points and ellipse axis ends at 9 values of t.
struct Descriptor {
    std::vector<glm::dvec3> axis, end_a, end_b;  // end_a = p + A e1 (sign ambiguity handled when comparing)
    std::vector<glm::dvec3> dir_a, dir_b;        // A e1, B e2
    double mean_radius = 0;
};

Descriptor describe(const GeneralizedCylinder& c) {
    Descriptor d;
    for (int k = 0; k <= 8; ++k) {
        const double t = k / 8.0;
        const glm::dvec3 p = c.position(t);
        const auto e = c.ellipse_axes(t);
        d.axis.push_back(p);
        d.dir_a.push_back(c.a(t) * e[0]);
        d.dir_b.push_back(c.b(t) * e[1]);
        d.mean_radius += 0.5 * (c.a(t) + c.b(t)) / 9.0;
    }
    return d;
}

// Least-squares similarity taking points `from` onto `to` (Umeyama 1991), via the 3×3 SVD-free
// polar decomposition of the covariance by Horn's quaternion method.
Similarity align(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to) {
    const double n = static_cast<double>(from.size());
    glm::dvec3 cf(0), ct(0);
    for (std::size_t i = 0; i < from.size(); ++i) {
        cf += from[i] / n;
        ct += to[i] / n;
    }
    double S[3][3] = {};
    double var_f = 0, var_t = 0;
    for (std::size_t i = 0; i < from.size(); ++i) {
        const glm::dvec3 a = from[i] - cf, b = to[i] - ct;
        var_f += glm::dot(a, a);
        var_t += glm::dot(b, b);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) S[r][c] += a[r] * b[c];
    }
    // Horn's 4×4 symmetric matrix; its dominant eigenvector is the rotation quaternion (w, x, y, z).
    const double N[4][4] = {{S[0][0] + S[1][1] + S[2][2], S[1][2] - S[2][1], S[2][0] - S[0][2], S[0][1] - S[1][0]},
                            {S[1][2] - S[2][1], S[0][0] - S[1][1] - S[2][2], S[0][1] + S[1][0], S[2][0] + S[0][2]},
                            {S[2][0] - S[0][2], S[0][1] + S[1][0], -S[0][0] + S[1][1] - S[2][2], S[1][2] + S[2][1]},
                            {S[0][1] - S[1][0], S[2][0] + S[0][2], S[1][2] + S[2][1], -S[0][0] - S[1][1] + S[2][2]}};
    // Power iteration on N + σI (shifted to be positive definite).
    double shift = 0;
    for (const auto& row : N)
        for (double v : row) shift += std::abs(v);
    double q[4] = {1, 0.1, 0.05, 0.02};
    for (int it = 0; it < 300; ++it) {
        double r[4] = {};
        for (int a = 0; a < 4; ++a) {
            r[a] = shift * q[a];
            for (int b = 0; b < 4; ++b) r[a] += N[a][b] * q[b];
        }
        const double len = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
        if (!(len > 0)) break;
        for (int a = 0; a < 4; ++a) q[a] = r[a] / len;
    }
    Similarity s;
    s.rotation = glm::normalize(glm::dquat(q[0], q[1], q[2], q[3]));
    s.scale = var_f > 0 ? std::sqrt(var_t / var_f) : 1.0;
    s.translation = ct - s.scale * (s.rotation * cf);
    return s;
}

double descriptor_distance(const Descriptor& proto, const Descriptor& cand, const Similarity& s) {
    double acc = 0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < proto.axis.size(); ++k) {
        const glm::dvec3 p = s.apply(proto.axis[k]);
        const glm::dvec3 a = s.scale * (s.rotation * proto.dir_a[k]), b = s.scale * (s.rotation * proto.dir_b[k]);
        acc += glm::dot(p - cand.axis[k], p - cand.axis[k]);
        // An ellipse is the same under e1 → −e1 and under swapping its axes with a quarter turn.
        const double same = std::min(glm::dot(a - cand.dir_a[k], a - cand.dir_a[k]), glm::dot(a + cand.dir_a[k], a + cand.dir_a[k])) +
                            std::min(glm::dot(b - cand.dir_b[k], b - cand.dir_b[k]), glm::dot(b + cand.dir_b[k], b + cand.dir_b[k]));
        const double swapped = std::min(glm::dot(a - cand.dir_b[k], a - cand.dir_b[k]), glm::dot(a + cand.dir_b[k], a + cand.dir_b[k])) +
                               std::min(glm::dot(b - cand.dir_a[k], b - cand.dir_a[k]), glm::dot(b + cand.dir_a[k], b + cand.dir_a[k]));
        acc += std::min(same, swapped);
        n += 3;
    }
    return std::sqrt(acc / static_cast<double>(n));
}

}  // namespace

// Median nearest-neighbour distance between roots (a grid hash would be faster; n ≤ 1e5 here).
double median_root_spacing(const std::vector<glm::dvec3>& roots) {
    if (roots.size() < 2) return 1.0;
    std::vector<std::size_t> order(roots.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return roots[a].x < roots[b].x; });
    std::vector<double> nn(roots.size(), std::numeric_limits<double>::max());
    for (std::size_t a = 0; a < order.size(); ++a) {
        const glm::dvec3& p = roots[order[a]];
        double& best = nn[order[a]];
        for (std::size_t b = a + 1; b < order.size() && roots[order[b]].x - p.x < std::sqrt(best); ++b)
            best = std::min(best, glm::dot(roots[order[b]] - p, roots[order[b]] - p));
        for (std::size_t b = a; b-- > 0 && p.x - roots[order[b]].x < std::sqrt(best);)
            best = std::min(best, glm::dot(roots[order[b]] - p, roots[order[b]] - p));
    }
    for (double& d : nn) d = std::sqrt(d);
    const double m = quantile(nn, 0.5);
    return m > 0 ? m : 1e-3;
}

void check_gaussian_width(double width, const Strands& strands, const std::string& place) {
    char value[64];
    std::snprintf(value, sizeof value, "%g", width);
    if (!std::isfinite(width) || !(width > 0))
        throw Error::parameter(place, std::string("the Gaussian width must be a finite number > 0 (the model file's units), got ") + value);
    const StrandStats stats = strand_stats(strands);
    const double extent = glm::length(stats.bbox_max - stats.bbox_min);
    if (!(extent > 0)) return;  // a single point: nothing to compare with
    char range[160];
    std::snprintf(range, sizeof range, "[%g, %g] (%g to 1 × the diagonal %g of the strands' bounding box, file units)",
                  kMinGaussianWidthOverExtent * extent, extent, kMinGaussianWidthOverExtent, extent);
    if (width < kMinGaussianWidthOverExtent * extent || width > extent)
        throw Error::parameter(place, std::string("the Gaussian width ") + value + " is outside " + range + ": wrong units?");
}

HairStyle fit_style(const Strands& strands, const FitOptions& options, FitReport* report) {
    FitOptions o = options;
    const std::size_t n = strands.strand_count();
    const auto t0 = Clock::now();
    FitReport local;
    FitReport& rep = report ? *report : local;
    rep = FitReport{};
    rep.requested_clusters = static_cast<std::size_t>(o.clusters);
    if (n == 0) throw std::invalid_argument("fit_style: no strands");
    if (o.layout.gaussian_width != 0) check_gaussian_width(o.layout.gaussian_width, strands, "FitOptions layout.gaussian_width");
    const StrandStats stats = strand_stats(strands);
    rep.rotation = o.orient_y_up ? glm::dmat3(hang_axis_rotation(stats)) : glm::dmat3(1.0);

    std::vector<Polyline> lines;
    lines.reserve(n);
    std::vector<glm::dvec3> roots;
    for (std::size_t i = 0; i < n; ++i) {
        lines.push_back(make_polyline(strands, i, rep.rotation));
        roots.push_back(lines.back().p.front());
    }
    if (o.layout.gaussian_width == 0) o.layout.gaussian_width = median_root_spacing(roots);
    const double r_min = o.layout.gaussian_width;
    const int k = std::max(1, std::min<int>(o.clusters, static_cast<int>(n)));

    // Features: K points at relative arc length, the root weighted.
    std::vector<std::vector<double>> feat(n, std::vector<double>(3 * kShapeSamples));
    for (std::size_t i = 0; i < n; ++i)
        for (int q = 0; q < kShapeSamples; ++q) {
            const glm::dvec3 p = lines[i].at(lines[i].length() * q / (kShapeSamples - 1)) * (q == 0 ? kRootWeight : 1.0);
            for (int c = 0; c < 3; ++c) feat[i][static_cast<std::size_t>(3 * q + c)] = p[c];
        }
    std::vector<int> label;
    {
        std::optional<Progress> bar;
        if (o.progress) bar.emplace("clustering (k-means iterations)", static_cast<std::uint64_t>(o.kmeans_iterations));
        label = kmeans(feat, k, o.kmeans_iterations, o.seed, bar ? &*bar : nullptr);
        if (bar) bar->finish();
    }
    rep.seconds_clustering = seconds_since(t0);

    const auto t1 = Clock::now();
    std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(k));
    for (std::size_t i = 0; i < n; ++i) members[static_cast<std::size_t>(label[i])].push_back(i);
    std::vector<FittedCluster> fitted;
    {
        std::optional<Progress> bar;
        if (o.progress) bar.emplace("fitting clusters", static_cast<std::uint64_t>(k));
        std::vector<std::optional<FittedCluster>> slots(members.size());
        parallel_for(members.size(), 0, [&](std::size_t c) {
            if (!members[c].empty()) slots[c] = fit_cluster(lines, members[c], o, r_min);
            if (bar) bar->advance();
        });
        if (bar) bar->finish();
        for (auto& s : slots)
            if (s) fitted.push_back(std::move(*s));
    }

    HairStyle style;
    style.layout = o.layout;
    rep.strand_cluster.assign(n, -1);
    rep.strand_crosses.assign(n, 0);
    std::vector<std::size_t> order(fitted.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return fitted[a].members.size() > fitted[b].members.size(); });
    std::vector<Descriptor> desc;
    std::vector<std::size_t> prototypes;  // cluster indices in the style
    for (std::size_t idx : order) {
        FittedCluster& fc = fitted[idx];
        Cluster cl;
        const std::size_t id = style.clusters.size();
        cl.name = "c" + std::to_string(id);
        Descriptor d = describe(*fc.shape);
        std::optional<std::size_t> match;
        Similarity transform;
        if (o.macro_tolerance > 0) {
            double best = std::numeric_limits<double>::max();
            for (std::size_t p = 0; p < prototypes.size(); ++p) {
                const Similarity s = align(desc[p].axis, d.axis);
                if (s.scale < 0.5 || s.scale > 2.0) continue;
                const double dist = descriptor_distance(desc[p], d, s);
                if (dist < best && dist <= o.macro_tolerance * d.mean_radius) {
                    best = dist;
                    match = prototypes[p];
                    transform = s;
                }
            }
        }
        if (match) {
            cl.instance_of = *match;
            cl.transform = transform;
        } else {
            cl.shape = fc.shape;
            cl.density = fc.density;
            prototypes.push_back(id);
            desc.push_back(std::move(d));
        }
        for (std::size_t m = 0; m < fc.members.size(); ++m) {
            rep.strand_cluster[fc.members[m]] = static_cast<int>(id);
            rep.strand_crosses[fc.members[m]] = fc.member_crosses[m] ? 1 : 0;
        }
        style.clusters.push_back(std::move(cl));
    }
    style.resolve();
    rep.seconds_fitting = seconds_since(t1);

    const auto t2 = Clock::now();
    Strands rotated = strands;
    for (auto& p : rotated.points) p = glm::vec3(rep.rotation * glm::dvec3(p));
    rep.error = fitting_error(style, rotated, rep.strand_cluster, rep.strand_crosses, o.progress);
    rep.stray = stray_distances(style, rotated, rep.strand_cluster);
    rep.seconds_error = seconds_since(t2);
    return style;
}

StrayReport stray_distances(const HairStyle& style, const Strands& strands, const std::vector<int>& strand_cluster) {
    const std::size_t n = style.clusters.size();
    std::vector<std::vector<glm::dvec3>> members(n);
    for (std::size_t i = 0; i < strands.strand_count() && i < strand_cluster.size(); ++i) {
        const int c = strand_cluster[i];
        if (c < 0 || static_cast<std::size_t>(c) >= n) continue;
        for (std::uint32_t k = strands.offsets[i]; k < strands.offsets[i + 1]; ++k) members[c].emplace_back(strands.points[k]);
    }
    struct Worst {
        double d = -1, t = 0;
    };
    std::vector<Worst> worst(n);
    const int rings = 2 * style.layout.s_t + 1;
    parallel_for(n, 0, [&](std::size_t c) {
        const Cluster& cl = style.clusters[c];
        if (members[c].empty() || !cl.shape) return;
        double radius = 0;
        for (int r = 0; r < rings; ++r) {
            const double t = double(r) / (rings - 1);
            radius += std::sqrt(cl.shape->a(t) * cl.shape->b(t));
        }
        radius *= cl.placement.scale / rings;
        if (!(radius > 0)) return;
        for (int r = 0; r < rings; ++r) {
            const double t = double(r) / (rings - 1);
            for (int k = 0; k < kStraySamplesU; ++k) {
                const glm::dvec3 x = cl.placement.apply(cl.shape->point(t, 1.0, 2.0 * kPi * k / kStraySamplesU));
                double best = std::numeric_limits<double>::infinity();
                for (const glm::dvec3& p : members[c]) best = std::min(best, glm::dot(p - x, p - x));
                const double d = std::sqrt(best) / radius;
                if (d > worst[c].d) worst[c] = {d, t};
            }
        }
    });
    StrayReport s;
    std::vector<double> per_cluster;
    for (std::size_t c = 0; c < n; ++c) {
        if (worst[c].d < 0) continue;
        per_cluster.push_back(worst[c].d);
        if (worst[c].d > s.worst) s = {worst[c].d, c, worst[c].t, 0, 0};
    }
    s.clusters = per_cluster.size();
    if (!per_cluster.empty()) {
        std::nth_element(per_cluster.begin(), per_cluster.begin() + per_cluster.size() / 2, per_cluster.end());
        s.median_cluster = per_cluster[per_cluster.size() / 2];
    }
    return s;
}

FitError fitting_error(const HairStyle& style, const Strands& strands, const std::vector<int>& strand_cluster,
                       const std::vector<char>& strand_crosses, bool progress) {
    FitError e;
    const std::size_t n = strands.strand_count();
    e.strands = n;
    std::optional<Progress> bar;
    if (progress) bar.emplace("measuring fitting error (strands)", n);
    // One partial per strand, summed in strand order: the figure does not depend on the thread count.
    struct Partial {
        std::size_t points = 0, inside = 0, outside = 0, assigned = 0;
        double sum2 = 0, max = 0;
    };
    std::vector<Partial> part(n);
    parallel_for(n, 0, [&](std::size_t i) {
        Partial& p = part[i];
        const int c = i < strand_cluster.size() ? strand_cluster[i] : -1;
        const bool crosses = i < strand_crosses.size() && strand_crosses[i];
        p.points = strands.point_count(i);
        if (c < 0 || static_cast<std::size_t>(c) >= style.clusters.size()) {
            // Unassigned: every point counts as outside at an unknown distance; not in the RMS.
            return;
        }
        p.assigned = crosses ? 1 : 0;
        const Cluster& cl = style.clusters[static_cast<std::size_t>(c)];
        const Similarity& s = cl.placement;
        const glm::dquat inv = glm::conjugate(s.rotation);
        for (std::uint32_t k = strands.offsets[i]; k < strands.offsets[i + 1]; ++k) {
            const glm::dvec3 x = inv * ((glm::dvec3(strands.points[k]) - s.translation) / s.scale);
            const double d = cl.shape->distance_outside(x) * s.scale;
            if (d == 0) ++p.inside;
            else {
                ++p.outside;
                p.sum2 += d * d;
                p.max = std::max(p.max, d);
            }
        }
        if (bar) bar->advance();
    });
    if (bar) bar->finish();
    double sum2 = 0;
    std::size_t outside = 0;
    for (const Partial& p : part) {
        outside += p.outside;
        e.points += p.points;
        e.inside += p.inside;
        e.assigned += p.assigned;
        sum2 += p.sum2;
        e.max_outside = std::max(e.max_outside, p.max);
    }
    e.rms_outside = outside ? std::sqrt(sum2 / static_cast<double>(outside)) : 0.0;
    return e;
}

}  // namespace coif
