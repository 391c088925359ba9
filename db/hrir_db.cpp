#include "db/hrir_db.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <glm/gtc/packing.hpp>
#include <map>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "models/core/atomic_file.h"
#include "models/core/checksum.h"
#include "models/core/bytes.h"
#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "models/sector_features.h"

namespace coif {

namespace fs = std::filesystem;

using bytes::get;
using bytes::put;

namespace {

constexpr char kMagic[8] = {'C', 'O', 'I', 'F', 'H', 'R', 'I', 'R'};
constexpr char kChunkMagic[8] = {'C', 'O', 'I', 'F', 'C', 'H', 'N', 'K'};
constexpr std::uint32_t kChunkVersion = 1;
constexpr std::size_t kFixedHeader = 64;
constexpr std::size_t kAlign = 64;  // block alignment: a cache line, and any GPU upload's alignment
constexpr std::size_t kMaxJson = 16u << 20;
constexpr std::uint32_t kFlagShard = 1;

std::size_t align_up(std::size_t x) { return (x + kAlign - 1) / kAlign * kAlign; }



std::string byte_place(std::size_t offset) { return "byte " + std::to_string(offset); }

void append_checksum(std::vector<std::byte>& b) { put<std::uint64_t>(b, checksum(b)); }

}  // namespace

std::size_t value_size(ValueType t) { return t == ValueType::Half ? 2 : 4; }

std::uint16_t float_to_half(float f) { return glm::packHalf1x16(f); }
float half_to_float(std::uint16_t h) { return glm::unpackHalf1x16(h); }

nlohmann::json params_json(const DbParams& p) {
    return {{"seed", p.seed},
            {"sectors", p.sectors},
            {"generator", to_json(p.generator)},
            {"tracer", to_json(p.tracer)},
            {"grids", to_json(p.grids)},
            {"value_type", p.value_type == ValueType::Half ? "half" : "float"}};
}

DbParams params_from_json(const nlohmann::json& j) {
    DbParams p;
    try {
        p.seed = j.at("seed").get<std::uint64_t>();
        p.sectors = j.at("sectors").get<std::uint64_t>();
        const std::string vt = j.at("value_type").get<std::string>();
        if (vt != "half" && vt != "float") throw Error({}, "JSON /value_type", "must be half or float");
        p.value_type = vt == "half" ? ValueType::Half : ValueType::Float;
        p.generator = sector_ranges_from_json(j.at("generator"));
        p.tracer = tracer_params_from_json(j.at("tracer"));
        p.grids = angle_grids_from_json(j.at("grids"));
    } catch (const nlohmann::json::exception& e) {
        throw Error({}, "JSON header", e.what());
    }
    return p;
}

std::uint64_t params_hash(const DbParams& p) {
    const std::string text = params_json(p).dump();
    return checksum(std::as_bytes(std::span<const char>(text.data(), text.size())));
}

FeatureNormalisation compute_normalisation(std::span<const float> features, std::size_t rows) {
    FeatureNormalisation n;
    const std::size_t F = rows ? features.size() / rows : kRawFeatureCount;
    n.mean.assign(F, 0.0f);
    n.scale.assign(F, 1.0f);
    for (std::size_t c = 0; c < F; ++c) {
        double sum = 0, sum2 = 0;
        for (std::size_t i = 0; i < rows; ++i) sum += features[i * F + c];
        const double mean = rows ? sum / static_cast<double>(rows) : 0.0;
        for (std::size_t i = 0; i < rows; ++i) sum2 += (features[i * F + c] - mean) * (features[i * F + c] - mean);
        const double sd = rows ? std::sqrt(sum2 / static_cast<double>(rows)) : 0.0;
        n.mean[c] = static_cast<float>(mean);
        n.scale[c] = sd > 1e-12 ? static_cast<float>(sd) : 1.0f;
    }
    return n;
}

SectorRecord build_sector(const DbParams& p, std::uint64_t index) {
    const SectorSample sample = generate_sector(p.generator, p.seed, index);
    SectorRecord r;
    r.features = raw_sector_features(sample.feature_grid, sample.params.depth, sample.params.width / sample.params.depth);
    r.values = PlanarTracer(sample.trace_grid, p.tracer).trace_record(p.grids);
    return r;
}

void encode_values(ValueType type, std::span<const float> values, std::vector<std::byte>& out) {
    if (type == ValueType::Float) {
        const auto b = std::as_bytes(values);
        out.insert(out.end(), b.begin(), b.end());
    } else {
        for (float v : values) put<std::uint16_t>(out, float_to_half(v));
    }
}

// ---- writing --------------------------------------------------------------------------------------------

void write_database(const fs::path& out, const DbParams& params, std::uint64_t first, std::uint64_t count, bool shard,
                    std::span<const float> features, std::span<const std::byte> records) {
    const std::size_t F = kRawFeatureCount, V = params.grids.record_values(), vs = value_size(params.value_type);
    if (features.size() != count * F || records.size() != count * V * vs)
        throw Error(out, "", "internal: feature or record block has the wrong size");
    nlohmann::json h = params_json(params);
    h["format"] = "coif HRIR database";
    h["feature_names"] = raw_feature_names();
    h["feature_sets"] = nlohmann::json::object();
    for (FeatureSet s : kAllFeatureSets) h["feature_sets"][feature_set_name(s)] = feature_columns(s);
    h["feature_definition"] =
        "paper: 004 §5.2 (rho_st, rho_s, rho_t) = models/sector_density.h paper_features; rich: rich_features; "
        "shape: ln(H/lambda), ln(W/H); all on the renderer's feature grid";
    if (shard) {
        h["shard"] = {{"first", first}, {"count", count}};
        h["normalisation"] = nullptr;
    } else {
        const FeatureNormalisation n = compute_normalisation(features, count);
        h["normalisation"] = {{"mean", n.mean}, {"scale", n.scale}, {"kind", "z-score over all records, index order"}};
    }
    const std::string json = h.dump();
    const std::size_t features_offset = align_up(kFixedHeader + json.size());
    const std::size_t records_offset = align_up(features_offset + features.size_bytes());

    std::vector<std::byte> b;
    b.reserve(records_offset + records.size() + 8);
    b.insert(b.end(), reinterpret_cast<const std::byte*>(kMagic), reinterpret_cast<const std::byte*>(kMagic) + 8);
    put<std::uint32_t>(b, kHrirFormatVersion);
    put<std::uint32_t>(b, static_cast<std::uint32_t>(json.size()));
    put<std::uint64_t>(b, count);
    put<std::uint32_t>(b, static_cast<std::uint32_t>(F));
    put<std::uint32_t>(b, static_cast<std::uint32_t>(V));
    put<std::uint32_t>(b, static_cast<std::uint32_t>(params.value_type));
    put<std::uint32_t>(b, shard ? kFlagShard : 0u);
    put<std::uint64_t>(b, features_offset);
    put<std::uint64_t>(b, records_offset);
    put<std::uint64_t>(b, first);
    const auto* jp = reinterpret_cast<const std::byte*>(json.data());
    b.insert(b.end(), jp, jp + json.size());
    b.resize(features_offset, std::byte{0});
    const auto fb = std::as_bytes(features);
    b.insert(b.end(), fb.begin(), fb.end());
    b.resize(records_offset, std::byte{0});
    b.insert(b.end(), records.begin(), records.end());
    append_checksum(b);
    write_file_atomic(out, b);
}

// ---- reading ----------------------------------------------------------------------------------------------

HrirDatabase::HrirDatabase(HrirDatabase&& o) noexcept { *this = std::move(o); }

HrirDatabase& HrirDatabase::operator=(HrirDatabase&& o) noexcept {
    if (this != &o) {
        if (data_) ::munmap(const_cast<std::byte*>(data_), size_);
        path_ = std::move(o.path_);
        data_ = std::exchange(o.data_, nullptr);
        size_ = std::exchange(o.size_, 0);
        params_ = o.params_;
        header_ = std::move(o.header_);
        norm_ = std::move(o.norm_);
        checksum_ = o.checksum_;
        first_ = o.first_;
        count_ = o.count_;
        features_offset_ = o.features_offset_;
        records_offset_ = o.records_offset_;
        shard_ = o.shard_;
    }
    return *this;
}

HrirDatabase::~HrirDatabase() {
    if (data_) ::munmap(const_cast<std::byte*>(data_), size_);
}

HrirDatabase HrirDatabase::open(const fs::path& path) {
    HrirDatabase db;
    db.path_ = path;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw Error(path, "", std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        ::close(fd);
        throw Error(path, "", "cannot stat");
    }
    const auto size = static_cast<std::size_t>(st.st_size);
    if (size < kFixedHeader + 8) {
        ::close(fd);
        throw Error(path, byte_place(size), "truncated: " + std::to_string(size) + " bytes is shorter than the 72-byte minimum");
    }
    void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (map == MAP_FAILED) throw Error(path, "", std::string("cannot map: ") + std::strerror(errno));
    db.data_ = static_cast<const std::byte*>(map);
    db.size_ = size;
    const std::byte* d = db.data_;

    if (std::memcmp(d, kMagic, 8) != 0) throw Error(path, "byte 0", "not a coif HRIR database (bad magic)");
    const auto version = get<std::uint32_t>(d + 8);
    if (version != kHrirFormatVersion)
        throw Error(path, "byte 8", "format version " + std::to_string(version) + " (this coif reads version " +
                                        std::to_string(kHrirFormatVersion) + ")");
    const auto J = get<std::uint32_t>(d + 12);
    const auto N = get<std::uint64_t>(d + 16);
    const auto F = get<std::uint32_t>(d + 24);
    const auto V = get<std::uint32_t>(d + 28);
    const auto vt = get<std::uint32_t>(d + 32);
    const auto flags = get<std::uint32_t>(d + 36);
    const auto fo = get<std::uint64_t>(d + 40);
    const auto ro = get<std::uint64_t>(d + 48);
    db.first_ = get<std::uint64_t>(d + 56);
    if (J > kMaxJson || kFixedHeader + J > size - 8) throw Error(path, "byte 12", "JSON header length out of range");
    if (vt != 1 && vt != 2) throw Error(path, "byte 32", "unknown value type " + std::to_string(vt));
    if (F != kRawFeatureCount)
        throw Error(path, "byte 24", std::to_string(F) + " feature columns (this coif uses " + std::to_string(kRawFeatureCount) + ")");
    if (N > (1ull << 32)) throw Error(path, "byte 16", "sector count out of range");
    const std::size_t vs = vt == 1 ? 2 : 4;
    if (fo != align_up(kFixedHeader + J) || ro != align_up(fo + N * F * 4) || ro + N * V * vs + 8 != size)
        throw Error(path, "byte 40", "block offsets do not match the file size " + std::to_string(size) +
                                         " (truncated or corrupt file)");
    // Checksum before trusting anything else.
    const std::uint64_t stored = get<std::uint64_t>(d + size - 8);
    const std::uint64_t actual = coif::checksum(std::span<const std::byte>(d, size - 8));
    if (stored != actual)
        throw Error(path, byte_place(size - 8), "checksum mismatch (stored " + checksum_hex(stored) + ", computed " +
                                                    checksum_hex(actual) + "): the file is corrupt");
    db.checksum_ = actual;
    try {
        db.header_ = nlohmann::json::parse(std::string(reinterpret_cast<const char*>(d + kFixedHeader), J));
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, "byte 64", std::string("JSON header: ") + e.what());
    }
    try {
        db.params_ = params_from_json(db.header_);
    } catch (const Error& e) {
        throw Error(path, e.place(), e.problem());
    }
    if (static_cast<std::uint32_t>(db.params_.value_type) != vt || db.params_.grids.record_values() != V)
        throw Error(path, "JSON header", "value type or record size disagrees with the binary header");
    db.shard_ = (flags & kFlagShard) != 0;
    db.count_ = N;
    db.features_offset_ = fo;
    db.records_offset_ = ro;
    if (!db.shard_) {
        if (db.first_ != 0 || N != db.params_.sectors)
            throw Error(path, "byte 16", "a finished database must hold sectors 0.." + std::to_string(db.params_.sectors));
        try {
            db.norm_.mean = db.header_.at("normalisation").at("mean").get<std::vector<float>>();
            db.norm_.scale = db.header_.at("normalisation").at("scale").get<std::vector<float>>();
        } catch (const nlohmann::json::exception& e) {
            throw Error(path, "JSON /normalisation", e.what());
        }
        if (db.norm_.mean.size() != F || db.norm_.scale.size() != F)
            throw Error(path, "JSON /normalisation", "wrong number of columns");
    } else if (db.first_ + N > db.params_.sectors) {
        throw Error(path, "byte 56", "shard range exceeds the build's sector count");
    }
    return db;
}

std::span<const float> HrirDatabase::all_features() const {
    return {reinterpret_cast<const float*>(data_ + features_offset_), count_ * kRawFeatureCount};
}

std::span<const float> HrirDatabase::features(std::size_t i) const {
    return all_features().subspan(i * kRawFeatureCount, kRawFeatureCount);
}

std::span<const std::byte> HrirDatabase::record_bytes() const {
    return {data_ + records_offset_, count_ * params_.grids.record_values() * value_size(params_.value_type)};
}

float HrirDatabase::value(std::size_t record, std::size_t i) const {
    const std::size_t k = record * params_.grids.record_values() + i;
    if (params_.value_type == ValueType::Half) return half_to_float(get<std::uint16_t>(data_ + records_offset_ + 2 * k));
    return get<float>(data_ + records_offset_ + 4 * k);
}

std::vector<float> HrirDatabase::record(std::size_t i) const {
    std::vector<float> v(params_.grids.record_values());
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = value(i, k);
    return v;
}

// ---- building ---------------------------------------------------------------------------------------------

double BuildReport::records_per_second() const { return seconds > 0 ? static_cast<double>(count - reused) / seconds : 0.0; }

Shard parse_shard(const std::string& text) {
    const auto slash = text.find('/');
    Shard s;
    try {
        if (slash == std::string::npos) throw std::invalid_argument("no slash");
        std::size_t used = 0;
        s.index = std::stoull(text.substr(0, slash), &used);
        if (used != slash) throw std::invalid_argument("k");
        const std::string n = text.substr(slash + 1);
        s.count = std::stoull(n, &used);
        if (used != n.size()) throw std::invalid_argument("n");
    } catch (const std::exception&) {
        throw Error::parameter("--shard " + text, "expected k/n with integers 0 ≤ k < n, e.g. 3/8");
    }
    if (s.count == 0 || s.index >= s.count) throw Error::parameter("--shard " + text, "expected k/n with 0 ≤ k < n, e.g. 3/8");
    return s;
}

namespace {

struct Chunk {
    std::uint64_t first = 0, count = 0;
    std::vector<float> features;
    std::vector<std::byte> records;
};

fs::path chunk_path(const fs::path& parts, std::uint64_t first) { return parts / ("chunk-" + std::to_string(first) + ".bin"); }

void write_chunk(const fs::path& path, std::uint64_t hash, const DbParams& p, const Chunk& c) {
    std::vector<std::byte> b;
    b.insert(b.end(), reinterpret_cast<const std::byte*>(kChunkMagic), reinterpret_cast<const std::byte*>(kChunkMagic) + 8);
    put<std::uint32_t>(b, kChunkVersion);
    put<std::uint32_t>(b, static_cast<std::uint32_t>(p.value_type));
    put<std::uint64_t>(b, hash);
    put<std::uint64_t>(b, c.first);
    put<std::uint64_t>(b, c.count);
    const auto fb = std::as_bytes(std::span<const float>(c.features));
    b.insert(b.end(), fb.begin(), fb.end());
    b.insert(b.end(), c.records.begin(), c.records.end());
    append_checksum(b);
    write_file_atomic(path, b);
}

// A chunk that is present, complete and of this build; nullopt-like false otherwise (it is rebuilt).
bool read_chunk(const fs::path& path, std::uint64_t hash, const DbParams& p, Chunk& c) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    std::vector<std::byte> b;
    try {
        b = read_file_bytes(path);
    } catch (const Error&) {
        return false;
    }
    const std::size_t fbytes = c.count * kRawFeatureCount * 4;
    const std::size_t rbytes = c.count * p.grids.record_values() * value_size(p.value_type);
    if (b.size() != 40 + fbytes + rbytes + 8 || std::memcmp(b.data(), kChunkMagic, 8) != 0) return false;
    if (get<std::uint32_t>(b.data() + 8) != kChunkVersion || get<std::uint32_t>(b.data() + 12) != static_cast<std::uint32_t>(p.value_type) ||
        get<std::uint64_t>(b.data() + 16) != hash || get<std::uint64_t>(b.data() + 24) != c.first ||
        get<std::uint64_t>(b.data() + 32) != c.count)
        return false;
    if (get<std::uint64_t>(b.data() + b.size() - 8) != checksum(std::span<const std::byte>(b.data(), b.size() - 8))) return false;
    c.features.resize(c.count * kRawFeatureCount);
    std::memcpy(c.features.data(), b.data() + 40, fbytes);
    c.records.assign(b.begin() + 40 + static_cast<std::ptrdiff_t>(fbytes), b.end() - 8);
    return true;
}

}  // namespace

BuildReport build_database(const BuildOptions& o, const fs::path& out) {
    const DbParams& p = o.params;
    if (p.sectors == 0) throw Error::parameter("--sectors", "must be at least 1");
    if (p.sectors > (1ull << 32)) throw Error::parameter("--sectors", "at most 2^32");
    if (o.threads < 0) throw Error::parameter("--threads", "must be 0 (every hardware thread) or more");
    (void)thread_count(o.threads);  // above kMaxThreads: refused before anything is written
    if (o.chunk < 1) throw Error::parameter("chunk", "must be at least 1");
    // The reader's checks, before anything is traced or written: a file it would refuse is never built.
    try {
        (void)params_from_json(params_json(p));
    } catch (const Error& e) {
        throw Error::parameter("build parameters (" + e.place() + ")", e.problem());
    }
    const std::uint64_t first = o.shard.first(p.sectors), last = o.shard.last(p.sectors);
    const std::uint64_t hash = params_hash(p);
    // Held for the whole build: a second build of the same file would clear or mix this one's chunks.
    const OutputLock lock(out);
    fs::path parts = out;
    parts += ".parts";
    std::error_code ec;
    if (!o.resume) fs::remove_all(parts, ec);
    fs::create_directories(parts, ec);
    if (ec) throw Error(parts, "", "cannot create the chunk folder: " + ec.message());
    remove_stale_temporaries_in(parts);  // chunks a killed build was writing

    std::vector<Chunk> chunks;
    for (std::uint64_t c = first; c < last; c += o.chunk) chunks.push_back({c, std::min<std::uint64_t>(o.chunk, last - c), {}, {}});
    BuildReport report;
    report.first = first;
    report.count = last - first;
    std::vector<char> done(chunks.size(), 0);
    if (o.resume)
        for (std::size_t i = 0; i < chunks.size(); ++i)
            if (read_chunk(chunk_path(parts, chunks[i].first), hash, p, chunks[i])) {
                done[i] = 1;
                report.reused += chunks[i].count;
            }

    Progress bar("db build", report.count);
    bar.advance(report.reused);
    // Each chunk holds its own sectors' records, joined in index order below: the file does not depend on
    // the thread count. The first error stops the build (finished chunks stay for --resume).
    const auto t0 = std::chrono::steady_clock::now();
    try {
        parallel_for(chunks.size(), o.threads, [&](std::size_t i) {
            if (done[i]) return;
            Chunk& c = chunks[i];
            for (std::uint64_t k = 0; k < c.count; ++k) {
                const SectorRecord r = build_sector(p, c.first + k);
                c.features.insert(c.features.end(), r.features.begin(), r.features.end());
                encode_values(p.value_type, r.values, c.records);
                bar.advance();
            }
            write_chunk(chunk_path(parts, c.first), hash, p, c);
        });
    } catch (...) {
        if (fs::is_empty(parts, ec)) fs::remove(parts, ec);  // no chunk finished: nothing to resume from
        throw;
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    bar.finish();

    std::vector<float> features;
    std::vector<std::byte> records;
    for (const Chunk& c : chunks) {
        features.insert(features.end(), c.features.begin(), c.features.end());
        records.insert(records.end(), c.records.begin(), c.records.end());
    }
    const bool shard = o.shard.count > 1;
    write_database(out, p, first, report.count, shard, features, records);
    if (!o.keep_parts) fs::remove_all(parts, ec);
    return report;
}

void merge_databases(const std::vector<fs::path>& parts, const fs::path& out) {
    if (parts.empty()) throw Error::parameter("PARTS", "no shard files given");
    const OutputLock lock(out);
    std::map<std::uint64_t, HrirDatabase> by_first;
    std::uint64_t hash = 0;
    DbParams params;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        HrirDatabase db = HrirDatabase::open(parts[i]);
        const std::uint64_t h = params_hash(db.params());
        if (i == 0) {
            hash = h;
            params = db.params();
        } else if (h != hash) {
            throw Error(parts[i], "JSON header", "parameters differ from " + parts[0].string() + " (shards of another build)");
        }
        if (db.size() == 0) continue;
        const std::uint64_t f = db.first_index();
        if (by_first.count(f)) throw Error(parts[i], "byte 56", "overlaps another shard starting at sector " + std::to_string(f));
        by_first.emplace(f, std::move(db));
    }
    std::uint64_t expect = 0;
    std::vector<float> features;
    std::vector<std::byte> records;
    for (const auto& [f, db] : by_first) {
        if (f != expect)
            throw Error(db.path(), "byte 56", f > expect ? "sectors " + std::to_string(expect) + ".." + std::to_string(f - 1) + " are missing"
                                                         : "overlaps the previous shard");
        const auto fs_ = db.all_features();
        features.insert(features.end(), fs_.begin(), fs_.end());
        const auto rb = db.record_bytes();
        records.insert(records.end(), rb.begin(), rb.end());
        expect = f + db.size();
    }
    if (expect != params.sectors)
        throw Error(out, "", "the shards cover sectors 0.." + std::to_string(expect) + " of " + std::to_string(params.sectors));
    write_database(out, params, 0, params.sectors, false, features, records);
}

nlohmann::json inspect_json(const HrirDatabase& db) {
    const DbParams& p = db.params();
    nlohmann::json j;
    j["file"] = db.path().string();
    j["format_version"] = kHrirFormatVersion;
    j["checksum"] = checksum_hex(db.checksum());
    j["bytes"] = db.file_size();
    j["kind"] = db.is_shard() ? "shard" : "database";
    j["sectors"] = db.size();
    j["first_sector"] = db.first_index();
    j["sectors_in_build"] = p.sectors;
    j["bytes_per_sector"] = db.size() ? static_cast<double>(db.file_size()) / static_cast<double>(db.size()) : 0.0;
    j["record_values"] = p.grids.record_values();
    j["params"] = params_json(p);
    // Feature ranges over the records.
    const auto names = raw_feature_names();
    nlohmann::json cols = nlohmann::json::array();
    for (std::size_t c = 0; c < names.size(); ++c) {
        float lo = INFINITY, hi = -INFINITY;
        double sum = 0;
        for (std::size_t i = 0; i < db.size(); ++i) {
            const float v = db.features(i)[c];
            lo = std::min(lo, v);
            hi = std::max(hi, v);
            sum += v;
        }
        cols.push_back({{"name", names[c]}, {"min", db.size() ? lo : 0.0f}, {"max", db.size() ? hi : 0.0f},
                        {"mean", db.size() ? sum / static_cast<double>(db.size()) : 0.0}});
    }
    j["features"] = cols;
    // Record value ranges: α and re (a_0).
    double amax = 0, asum = 0, remax = 0;
    std::size_t acount = 0;
    const AngleGrids& g = p.grids;
    for (std::size_t i = 0; i < db.size(); ++i)
        for (int v = 0; v < g.views; ++v)
            for (int x = 0; x < g.hrir_length; ++x) {
                const float a = db.value(i, g.alpha_offset(v) + static_cast<std::size_t>(x));
                amax = std::max<double>(amax, a);
                asum += a;
                ++acount;
                remax = std::max<double>(remax, db.value(i, g.re_offset(v, 0) + static_cast<std::size_t>(x)));
            }
    j["alpha"] = {{"mean", acount ? asum / static_cast<double>(acount) : 0.0}, {"max", amax}};
    j["re_a0_max"] = remax;
    return j;
}

}  // namespace coif
