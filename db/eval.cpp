#include "db/eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "models/core/units.h"
#include "models/sector_features.h"

namespace coif {

namespace {

// Pooled relative L2 accumulator.
struct L2 {
    double err2 = 0, ref2 = 0;
    std::size_t n = 0;
    void add(std::span<const float> got, std::span<const float> truth) {
        for (std::size_t i = 0; i < got.size(); ++i) {
            err2 += (got[i] - truth[i]) * static_cast<double>(got[i] - truth[i]);
            ref2 += truth[i] * static_cast<double>(truth[i]);
        }
        n += got.size();
    }
    double relative() const { return std::sqrt(err2) / std::max(std::sqrt(ref2), kErrorFloor * std::sqrt(static_cast<double>(n))); }
};

struct Truth {
    RawFeatures features{};
    std::vector<std::pair<double, double>> angles;
    std::vector<float> re, alpha;  // [pairs][X]
    std::vector<float> own_record;
};

Truth trace_truth(const DbParams& p, std::uint64_t i, int pairs, bool with_record) {
    const SectorSample s = generate_sector(p.generator, held_out_seed(p.seed), i);
    Truth t;
    t.features = raw_sector_features(s.feature_grid, s.params.depth, s.params.width / s.params.depth);
    const PlanarTracer tracer(s.trace_grid, p.tracer);
    const auto X = static_cast<std::size_t>(p.grids.hrir_length);
    Xoshiro256 rng(sector_seed(held_out_seed(p.seed) ^ 0xA9, i));
    t.re.resize(X * pairs);
    t.alpha.resize(X * pairs);
    for (int j = 0; j < pairs; ++j) {
        const double tv = rng.uniform(0, kTwoPi), tl = rng.uniform(0, kTwoPi);
        t.angles.emplace_back(tv, tl);
        const double l[1] = {tl};
        tracer.trace_view(tv, l, p.grids.hrir_length, std::span<float>(t.alpha).subspan(j * X, X), std::span<float>(t.re).subspan(j * X, X));
    }
    if (with_record) {
        t.own_record = tracer.trace_record(p.grids);
        if (p.value_type == ValueType::Half)
            for (float& v : t.own_record) v = half_to_float(float_to_half(v));
    }
    return t;
}

}  // namespace

std::uint64_t held_out_seed(std::uint64_t seed) { return splitmix64(seed ^ kHeldOutSalt); }

ErrorStats error_stats(std::vector<double> e) {
    ErrorStats s;
    if (e.empty()) return s;
    std::sort(e.begin(), e.end());
    const auto at = [&](double q) { return e[std::min(e.size() - 1, static_cast<std::size_t>(q * static_cast<double>(e.size() - 1) + 0.5))]; };
    s.median = at(0.5);
    s.p95 = at(0.95);
    double sum = 0;
    for (double v : e) sum += v;
    s.mean = sum / static_cast<double>(e.size());
    return s;
}

EvalReport evaluate_database(const HrirDatabase& db, const EvalOptions& o) {
    if (o.held_out < 1 || o.angle_pairs < 1) throw Error::parameter("--held-out", "must be at least 1");
    const auto t0 = std::chrono::steady_clock::now();
    const DbParams& p = db.params();
    const auto X = static_cast<std::size_t>(p.grids.hrir_length);
    std::vector<Truth> truth(o.held_out);
    {
        Progress bar("db eval: tracing held-out sectors", o.held_out);
        parallel_for(o.held_out, o.threads, [&](std::size_t i) {
            truth[i] = trace_truth(p, i, o.angle_pairs, true);
            bar.advance();
        });
    }
    EvalReport report;
    report.sectors = db.size();
    report.held_out = o.held_out;
    report.angle_pairs = o.angle_pairs;
    std::vector<float> re(X), alpha(X);
    // Oracle: the sector's own record in storage form.
    {
        std::vector<double> er, ea;
        for (const Truth& t : truth) {
            L2 lr, la;
            for (int j = 0; j < o.angle_pairs; ++j) {
                evaluate_record(p.grids, t.own_record, t.angles[static_cast<std::size_t>(j)].first, t.angles[static_cast<std::size_t>(j)].second, re, alpha);
                lr.add(re, std::span<const float>(t.re).subspan(j * X, X));
                la.add(alpha, std::span<const float>(t.alpha).subspan(j * X, X));
            }
            er.push_back(lr.relative());
            ea.push_back(la.relative());
        }
        report.rows.push_back({"oracle", 0, "-", error_stats(er), error_stats(ea)});
    }
    std::vector<float> queries;
    for (const Truth& t : truth) queries.insert(queries.end(), t.features.begin(), t.features.end());
    for (FeatureSet set : o.sets)
        for (Blend blend : o.blends)
            for (int k : o.ks) {
                if (k == 1 && blend != o.blends.front()) continue;  // k = 1 is the same for every blend
                SatfOptions so;
                so.set = set;
                so.k = k;
                so.blend = blend;
                const SatfIndex index(db, so);
                const auto matches = index.match_all(queries);
                std::vector<double> er(truth.size()), ea(truth.size());
                parallel_for(truth.size(), o.threads, [&](std::size_t i) {
                    std::vector<float> r(X), a(X);
                    L2 lr, la;
                    for (int j = 0; j < o.angle_pairs; ++j) {
                        index.evaluate(matches[i], truth[i].angles[static_cast<std::size_t>(j)].first, truth[i].angles[static_cast<std::size_t>(j)].second, r, a);
                        lr.add(r, std::span<const float>(truth[i].re).subspan(j * X, X));
                        la.add(a, std::span<const float>(truth[i].alpha).subspan(j * X, X));
                    }
                    er[i] = lr.relative();
                    ea[i] = la.relative();
                });
                report.rows.push_back({feature_set_name(set), k, k == 1 ? "-" : blend_name(blend), error_stats(er), error_stats(ea)});
            }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

namespace {
nlohmann::json stats_json(const ErrorStats& s) { return {{"median", s.median}, {"p95", s.p95}, {"mean", s.mean}}; }
}  // namespace

nlohmann::json to_json(const EvalReport& r) {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& row : r.rows)
        rows.push_back({{"features", row.set}, {"k", row.k}, {"blend", row.blend}, {"re", stats_json(row.re)}, {"alpha", stats_json(row.alpha)}});
    return {{"database_sectors", r.sectors}, {"held_out", r.held_out}, {"angle_pairs", r.angle_pairs},
            {"error", "relative L2 per held-out sector, pooled over its angle pairs; median and p95 over sectors"},
            {"rows", rows}, {"seconds", r.seconds}};
}

std::vector<StudyRow> resolution_study(const DbParams& p, std::size_t held_out, int threads) {
    constexpr int kDenseLights = 96;
    constexpr int kFineLength = 256;
    const std::vector<int> orders{1, 2, 3, 4, 6, 8, 12};
    const std::vector<int> views{16, 24, 32, 48, 64};
    const std::vector<int> lengths{8, 16, 24, 32, 48, 64};
    struct PerSector {
        std::vector<double> order_re, view_re, view_a, length_re, length_a, half_re, half_a;
    };
    std::vector<PerSector> per(held_out);
    Progress bar("db eval --study", held_out);
    parallel_for(held_out, threads, [&](std::size_t i) {
        const SectorSample s = generate_sector(p.generator, held_out_seed(p.seed), i);
        const PlanarTracer tracer(s.trace_grid, p.tracer);
        Xoshiro256 rng(sector_seed(held_out_seed(p.seed) ^ 0x57, i));
        const int X = p.grids.hrir_length;
        const auto Xs = static_cast<std::size_t>(X);
        PerSector& out = per[i];
        // Fourier order: dense θl at one random θv.
        {
            const double tv = rng.uniform(0, kTwoPi);
            std::vector<double> tl(kDenseLights);
            for (int j = 0; j < kDenseLights; ++j) tl[static_cast<std::size_t>(j)] = kTwoPi * (j + 0.5 * rng.uniform()) / kDenseLights;
            std::vector<float> a(Xs), re(kDenseLights * Xs);
            tracer.trace_view(tv, tl, X, a, re);
            for (int K : orders) {
                // Projection by the (nearly uniform) samples' quadrature, then reconstruction.
                std::vector<float> rec(re.size());
                for (std::size_t x = 0; x < Xs; ++x) {
                    std::vector<double> coef(static_cast<std::size_t>(2 * K + 1), 0.0);
                    for (int j = 0; j < kDenseLights; ++j) {
                        const double v = re[static_cast<std::size_t>(j) * Xs + x], t = tl[static_cast<std::size_t>(j)];
                        coef[0] += v / kDenseLights;
                        for (int k = 1; k <= K; ++k) {
                            coef[static_cast<std::size_t>(2 * k - 1)] += 2.0 * v * std::cos(k * t) / kDenseLights;
                            coef[static_cast<std::size_t>(2 * k)] += 2.0 * v * std::sin(k * t) / kDenseLights;
                        }
                    }
                    for (int j = 0; j < kDenseLights; ++j) {
                        const double t = tl[static_cast<std::size_t>(j)];
                        double v = coef[0];
                        for (int k = 1; k <= K; ++k) v += coef[static_cast<std::size_t>(2 * k - 1)] * std::cos(k * t) + coef[static_cast<std::size_t>(2 * k)] * std::sin(k * t);
                        rec[static_cast<std::size_t>(j) * Xs + x] = static_cast<float>(std::max(0.0, v));
                    }
                }
                L2 l;
                l.add(rec, re);
                out.order_re.push_back(l.relative());
            }
        }
        // Views: linear interpolation at the mid-point between grid views, at one random θl.
        {
            const double tl[1] = {rng.uniform(0, kTwoPi)};
            for (int Nv : views) {
                const double i0 = std::floor(rng.uniform(0, Nv));
                std::vector<float> a0(Xs), r0(Xs), a1(Xs), r1(Xs), am(Xs), rm(Xs);
                tracer.trace_view(kTwoPi * i0 / Nv, tl, X, a0, r0);
                tracer.trace_view(kTwoPi * (i0 + 1) / Nv, tl, X, a1, r1);
                tracer.trace_view(kTwoPi * (i0 + 0.5) / Nv, tl, X, am, rm);
                for (std::size_t x = 0; x < Xs; ++x) {
                    a0[x] = 0.5f * (a0[x] + a1[x]);
                    r0[x] = 0.5f * (r0[x] + r1[x]);
                }
                L2 lr, la;
                lr.add(r0, rm);
                la.add(a0, am);
                out.view_re.push_back(lr.relative());
                out.view_a.push_back(la.relative());
            }
        }
        // HRIR length: X samples linearly interpolated (periodic, sample j at (j + ½)/X) vs 256 samples.
        {
            const double tv = rng.uniform(0, kTwoPi), tl[1] = {rng.uniform(0, kTwoPi)};
            std::vector<float> af(kFineLength), rf(kFineLength);
            tracer.trace_view(tv, tl, kFineLength, af, rf);
            for (int L : lengths) {
                const auto Ls = static_cast<std::size_t>(L);
                std::vector<float> a(Ls), r(Ls), au(kFineLength), ru(kFineLength);
                tracer.trace_view(tv, tl, L, a, r);
                for (int q = 0; q < kFineLength; ++q) {
                    const double f = (q + 0.5) / kFineLength * L - 0.5;
                    const double f0 = std::floor(f);
                    const double t = f - f0;
                    const auto j0 = static_cast<std::size_t>((static_cast<int>(f0) % L + L) % L), j1 = (j0 + 1) % Ls;
                    au[static_cast<std::size_t>(q)] = static_cast<float>((1 - t) * a[j0] + t * a[j1]);
                    ru[static_cast<std::size_t>(q)] = static_cast<float>((1 - t) * r[j0] + t * r[j1]);
                }
                L2 lr, la;
                lr.add(ru, rf);
                la.add(au, af);
                out.length_re.push_back(lr.relative());
                out.length_a.push_back(la.relative());
            }
        }
        // Half floats: the stored record's values rounded.
        {
            const std::vector<float> rec = tracer.trace_record(p.grids);
            std::vector<float> h(rec.size());
            for (std::size_t k = 0; k < rec.size(); ++k) h[k] = half_to_float(float_to_half(rec[k]));
            const std::size_t A = p.grids.alpha_values();
            L2 lr, la;
            la.add(std::span<const float>(h).first(A), std::span<const float>(rec).first(A));
            lr.add(std::span<const float>(h).subspan(A), std::span<const float>(rec).subspan(A));
            out.half_re.push_back(lr.relative());
            out.half_a.push_back(la.relative());
        }
        bar.advance();
    });
    std::vector<StudyRow> rows;
    const auto column = [&](auto member, std::size_t j) {
        std::vector<double> v;
        for (const auto& s : per) v.push_back((s.*member)[j]);
        return error_stats(v);
    };
    for (std::size_t j = 0; j < orders.size(); ++j) rows.push_back({"fourier_order", orders[j], column(&PerSector::order_re, j), {}});
    for (std::size_t j = 0; j < views.size(); ++j) rows.push_back({"views", views[j], column(&PerSector::view_re, j), column(&PerSector::view_a, j)});
    for (std::size_t j = 0; j < lengths.size(); ++j)
        rows.push_back({"hrir_length", lengths[j], column(&PerSector::length_re, j), column(&PerSector::length_a, j)});
    rows.push_back({"half", 16, column(&PerSector::half_re, 0), column(&PerSector::half_a, 0)});
    return rows;
}

nlohmann::json to_json(const std::vector<StudyRow>& rows) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& r : rows) a.push_back({{"quantity", r.quantity}, {"value", r.value}, {"re", stats_json(r.re)}, {"alpha", stats_json(r.alpha)}});
    return a;
}

}  // namespace coif
