#include "db/satf.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#include <flann/flann.hpp>
#pragma GCC diagnostic pop

#include "models/core/atomic_file.h"
#include "models/core/checksum.h"
#include "models/core/bytes.h"
#include "models/core/error.h"
#include "models/core/units.h"
#include "models/sector_features.h"

namespace coif {

namespace fs = std::filesystem;

using bytes::get;
using bytes::put;

namespace {

constexpr char kIndexMagic[8] = {'C', 'O', 'I', 'F', 'F', 'L', 'N', 'N'};
constexpr std::uint32_t kIndexVersion = 1;
constexpr std::size_t kIndexHeader = 48;
constexpr int kLeafMaxSize = 10;  // FLANN's default leaf size for the single k-d tree


std::uint32_t set_id(FeatureSet s) { return static_cast<std::uint32_t>(s); }

// View interpolation: the two grid views around θv and the weight of the second.
struct ViewPair {
    int i0 = 0, i1 = 0;
    double t = 0;
};
ViewPair view_pair(int views, double theta_v) {
    double f = theta_v / kTwoPi * views;
    f -= std::floor(f / views) * views;  // [0, views)
    ViewPair p;
    p.i0 = std::min(static_cast<int>(f), views - 1);
    p.t = f - p.i0;
    p.i1 = (p.i0 + 1) % views;
    return p;
}

// Fourier basis at θl in the coefficient order of AngleGrids.
std::vector<double> fourier_basis(int order, double theta_l) {
    std::vector<double> b(static_cast<std::size_t>(2 * order + 1));
    b[0] = 1.0;
    for (int k = 1; k <= order; ++k) {
        b[static_cast<std::size_t>(2 * k - 1)] = std::cos(k * theta_l);
        b[static_cast<std::size_t>(2 * k)] = std::sin(k * theta_l);
    }
    return b;
}

// Adds weight × (record at θv, θl) into re/α; `value(i)` reads the record's value i.
template <class Value>
void accumulate(const AngleGrids& g, const Value& value, double weight, const ViewPair& vp, const std::vector<double>& basis,
                std::span<double> re, std::span<double> alpha) {
    const int X = g.hrir_length, C = g.coefficients();
    const double w0 = weight * (1 - vp.t), w1 = weight * vp.t;
    for (int x = 0; x < X; ++x) {
        alpha[static_cast<std::size_t>(x)] += w0 * value(g.alpha_offset(vp.i0) + static_cast<std::size_t>(x)) +
                                              w1 * value(g.alpha_offset(vp.i1) + static_cast<std::size_t>(x));
    }
    for (int c = 0; c < C; ++c) {
        const double b0 = w0 * basis[static_cast<std::size_t>(c)], b1 = w1 * basis[static_cast<std::size_t>(c)];
        const std::size_t o0 = g.re_offset(vp.i0, c), o1 = g.re_offset(vp.i1, c);
        for (int x = 0; x < X; ++x)
            re[static_cast<std::size_t>(x)] += b0 * value(o0 + static_cast<std::size_t>(x)) + b1 * value(o1 + static_cast<std::size_t>(x));
    }
}

void finish(std::span<const double> re_acc, std::span<const double> alpha_acc, std::span<float> re, std::span<float> alpha) {
    for (std::size_t x = 0; x < re.size(); ++x) {
        re[x] = static_cast<float>(std::max(0.0, re_acc[x]));
        alpha[x] = static_cast<float>(std::clamp(alpha_acc[x], 0.0, 1.0));
    }
}

}  // namespace

std::string blend_name(Blend b) { return b == Blend::InverseDistance ? "idw" : "gauss"; }

Blend blend_from_name(const std::string& name) {
    if (name == "idw") return Blend::InverseDistance;
    if (name == "gauss") return Blend::Gaussian;
    throw Error::parameter("blend '" + name + "'", "unknown; use idw or gauss");
}

struct SatfIndex::Impl {
    std::vector<int> columns;
    std::vector<float> points;  // normalised, rows × columns
    std::size_t rows = 0;
    std::unique_ptr<flann::KDTreeSingleIndex<flann::L2<float>>> tree;

    flann::Matrix<float> matrix() { return {points.data(), rows, columns.size()}; }
    void build() {
        tree = std::make_unique<flann::KDTreeSingleIndex<flann::L2<float>>>(matrix(), flann::KDTreeSingleIndexParams(kLeafMaxSize));
        tree->buildIndex();
    }
};

SatfIndex::SatfIndex(const HrirDatabase& db, const SatfOptions& options) : db_(&db), opt_(options), impl_(std::make_unique<Impl>()) {
    if (db.is_shard()) throw Error(db.path(), "", "a shard cannot be searched: merge the shards first (coif db merge)");
    if (db.size() == 0) throw Error(db.path(), "", "the database is empty");
    if (opt_.k < 1 || opt_.k > kMaxNeighbours) throw Error::parameter("k", "must be within 1.." + std::to_string(kMaxNeighbours));
    opt_.k = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(opt_.k), db.size()));
    impl_->columns = feature_columns(opt_.set);
    impl_->rows = db.size();
    const std::size_t D = impl_->columns.size();
    impl_->points.resize(impl_->rows * D);
    const auto& n = db.normalisation();
    for (std::size_t i = 0; i < impl_->rows; ++i) {
        const auto f = db.features(i);
        for (std::size_t c = 0; c < D; ++c) {
            const auto col = static_cast<std::size_t>(impl_->columns[c]);
            impl_->points[i * D + c] = (f[col] - n.mean[col]) / n.scale[col];
        }
    }
    impl_->build();
}

SatfIndex::SatfIndex(SatfIndex&&) noexcept = default;
SatfIndex::~SatfIndex() = default;

fs::path SatfIndex::saved_path(const HrirDatabase& db, FeatureSet set) {
    std::string name = feature_set_name(set);
    std::replace(name.begin(), name.end(), '+', '_');
    fs::path p = db.path();
    p += "." + name + ".flann";
    return p;
}

SatfIndex SatfIndex::open(const HrirDatabase& db, const SatfOptions& options) {
    SatfIndex index(db, options);  // cheap for our sizes; the saved tree replaces it when valid
    const fs::path p = saved_path(db, options.set);
    std::error_code ec;
    if (fs::exists(p, ec)) {
        try {
            index.load(p);
        } catch (const Error&) {
            index.impl_->build();  // stale or corrupt: keep the freshly built tree
        }
    }
    return index;
}

void SatfIndex::save(const fs::path& path) const {
    write_atomically(path, [&](const fs::path& tmp) {
        FILE* f = std::fopen(tmp.c_str(), "wb");
        if (!f) throw Error(tmp, "", "cannot create");
        std::vector<std::byte> head;
        head.insert(head.end(), reinterpret_cast<const std::byte*>(kIndexMagic), reinterpret_cast<const std::byte*>(kIndexMagic) + 8);
        put<std::uint32_t>(head, kIndexVersion);
        put<std::uint32_t>(head, set_id(opt_.set));
        put<std::uint64_t>(head, db_->checksum());
        put<std::uint64_t>(head, impl_->rows);
        put<std::uint32_t>(head, static_cast<std::uint32_t>(impl_->columns.size()));
        put<std::uint32_t>(head, 0);
        put<std::uint64_t>(head, 0);  // FLANN bytes checksum, patched below
        std::fwrite(head.data(), 1, head.size(), f);
        try {
            impl_->tree->saveIndex(f);
        } catch (const std::exception& e) {
            std::fclose(f);
            throw Error(tmp, "", std::string("FLANN: ") + e.what());
        }
        if (std::fclose(f) != 0) throw Error(tmp, "", "write failed");
        // Patch in the checksum of the FLANN bytes.
        std::vector<std::byte> all = read_file_bytes(tmp);
        const std::uint64_t h = checksum(std::span<const std::byte>(all).subspan(kIndexHeader));
        std::memcpy(all.data() + 40, &h, 8);
        FILE* g = std::fopen(tmp.c_str(), "wb");
        if (!g || std::fwrite(all.data(), 1, all.size(), g) != all.size()) {
            if (g) std::fclose(g);
            throw Error(tmp, "", "write failed");
        }
        if (std::fclose(g) != 0) throw Error(tmp, "", "write failed");
    });
}

void SatfIndex::load(const fs::path& path) {
    const std::vector<std::byte> all = read_file_bytes(path);
    if (all.size() < kIndexHeader || std::memcmp(all.data(), kIndexMagic, 8) != 0)
        throw Error(path, "byte 0", "not a coif FLANN index");
    if (get<std::uint32_t>(all.data() + 8) != kIndexVersion) throw Error(path, "byte 8", "unknown index version");
    if (get<std::uint32_t>(all.data() + 12) != set_id(opt_.set)) throw Error(path, "byte 12", "index of another feature set");
    if (get<std::uint64_t>(all.data() + 16) != db_->checksum())
        throw Error(path, "byte 16", "index of another database (checksum " + checksum_hex(get<std::uint64_t>(all.data() + 16)) +
                                         ", database " + checksum_hex(db_->checksum()) + ")");
    if (get<std::uint64_t>(all.data() + 24) != impl_->rows || get<std::uint32_t>(all.data() + 32) != impl_->columns.size())
        throw Error(path, "byte 24", "index size does not match the database");
    if (get<std::uint64_t>(all.data() + 40) != checksum(std::span<const std::byte>(all).subspan(kIndexHeader)))
        throw Error(path, "byte 40", "checksum mismatch: the index file is corrupt");
    std::vector<std::byte> flann_bytes(all.begin() + kIndexHeader, all.end());
    FILE* f = ::fmemopen(flann_bytes.data(), flann_bytes.size(), "rb");
    if (!f) throw Error(path, "", "cannot read");
    auto tree = std::make_unique<flann::KDTreeSingleIndex<flann::L2<float>>>(impl_->matrix(), flann::KDTreeSingleIndexParams(kLeafMaxSize));
    try {
        tree->loadIndex(f);
    } catch (const std::exception& e) {
        std::fclose(f);
        throw Error(path, "", std::string("FLANN: ") + e.what());
    }
    std::fclose(f);
    impl_->tree = std::move(tree);
}

SectorMatch SatfIndex::match(std::span<const float> raw) const { return match_all(raw).front(); }

std::vector<SectorMatch> SatfIndex::match_all(std::span<const float> raw) const {
    if (raw.size() % kRawFeatureCount != 0 || raw.empty())
        throw Error::parameter("features", "expected rows of " + std::to_string(kRawFeatureCount) + " raw features");
    const std::size_t n = raw.size() / kRawFeatureCount, D = impl_->columns.size();
    const auto& norm = db_->normalisation();
    std::vector<float> q(n * D);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < D; ++c) {
            const auto col = static_cast<std::size_t>(impl_->columns[c]);
            q[i * D + c] = (raw[i * kRawFeatureCount + col] - norm.mean[col]) / norm.scale[col];
        }
    const auto k = static_cast<std::size_t>(opt_.k);
    std::vector<std::size_t> ids(n * k);
    std::vector<float> d2(n * k);
    flann::Matrix<float> qm(q.data(), n, D);
    flann::Matrix<std::size_t> im(ids.data(), n, k);
    flann::Matrix<float> dm(d2.data(), n, k);
    flann::SearchParams sp;
    sp.sorted = true;
    impl_->tree->knnSearch(qm, im, dm, k, sp);
    std::vector<SectorMatch> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        SectorMatch& m = out[i];
        m.k = opt_.k;
        double sum = 0;
        const double dk = std::sqrt(std::max(0.0f, d2[i * k + k - 1]));
        for (std::size_t j = 0; j < k; ++j) {
            const double d = std::sqrt(std::max(0.0f, d2[i * k + j]));
            double w;
            if (opt_.blend == Blend::InverseDistance) w = 1.0 / std::pow(d + opt_.idw_epsilon, opt_.idw_power);
            else w = dk > 0 ? std::exp(-(d / dk) * (d / dk)) : 1.0;
            m.id[j] = static_cast<std::uint32_t>(ids[i * k + j]);
            m.distance[j] = static_cast<float>(d);
            m.weight[j] = static_cast<float>(w);
            sum += w;
        }
        for (std::size_t j = 0; j < k; ++j) m.weight[j] = static_cast<float>(m.weight[j] / sum);
    }
    return out;
}

void SatfIndex::evaluate(const SectorMatch& m, double theta_v, double theta_l, std::span<float> re, std::span<float> alpha) const {
    const AngleGrids& g = db_->params().grids;
    const auto X = static_cast<std::size_t>(g.hrir_length);
    if (re.size() != X || alpha.size() != X) throw Error::parameter("evaluate", "spans must hold hrir_length values");
    std::vector<double> re_acc(X, 0.0), a_acc(X, 0.0);
    const ViewPair vp = view_pair(g.views, theta_v);
    const auto basis = fourier_basis(g.fourier_order, theta_l);
    for (int j = 0; j < m.k; ++j) {
        const std::uint32_t id = m.id[static_cast<std::size_t>(j)];
        accumulate(g, [&](std::size_t i) { return db_->value(id, i); }, m.weight[static_cast<std::size_t>(j)], vp, basis, re_acc, a_acc);
    }
    finish(re_acc, a_acc, re, alpha);
}

void SatfIndex::coefficients(const SectorMatch& m, double theta_v, std::span<float> out) const {
    const AngleGrids& g = db_->params().grids;
    const auto X = static_cast<std::size_t>(g.hrir_length), C = static_cast<std::size_t>(g.coefficients());
    if (out.size() != X * C) throw Error::parameter("coefficients", "span must hold (2K+1) × hrir_length values");
    std::fill(out.begin(), out.end(), 0.0f);
    const ViewPair vp = view_pair(g.views, theta_v);
    for (int j = 0; j < m.k; ++j) {
        const std::uint32_t id = m.id[static_cast<std::size_t>(j)];
        const double w = m.weight[static_cast<std::size_t>(j)];
        for (std::size_t c = 0; c < C; ++c)
            for (std::size_t x = 0; x < X; ++x)
                out[c * X + x] += static_cast<float>(w * ((1 - vp.t) * db_->value(id, g.re_offset(vp.i0, static_cast<int>(c)) + x) +
                                                          vp.t * db_->value(id, g.re_offset(vp.i1, static_cast<int>(c)) + x)));
    }
}

void evaluate_record(const AngleGrids& g, std::span<const float> record, double theta_v, double theta_l, std::span<float> re,
                     std::span<float> alpha) {
    const auto X = static_cast<std::size_t>(g.hrir_length);
    std::vector<double> re_acc(X, 0.0), a_acc(X, 0.0);
    accumulate(g, [&](std::size_t i) { return record[i]; }, 1.0, view_pair(g.views, theta_v), fourier_basis(g.fourier_order, theta_l),
               re_acc, a_acc);
    finish(re_acc, a_acc, re, alpha);
}

}  // namespace coif
