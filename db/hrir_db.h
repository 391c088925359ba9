#pragma once
// The HRIR database (004 §4–§5): one record of re/α arrays per random generalized sector, indexed by
// the sector's density features. Built from the command line (`coif db build`), shardable.
//
// ---- File format (version 1), little-endian --------------------------------------------------------
//   byte 0    8  magic "COIFHRIR"
//   byte 8    4  uint32 format version (1)
//   byte 12   4  uint32 J, length of the JSON header
//   byte 16   8  uint64 N, sectors (records) in this file
//   byte 24   4  uint32 F, raw feature columns per sector (kRawFeatureCount)
//   byte 28   4  uint32 V, record values per sector (AngleGrids::record_values())
//   byte 32   4  uint32 value type: 1 = IEEE binary16 (half), 2 = float32
//   byte 36   4  uint32 flags: bit 0 = shard (a part of a build, not usable for look-ups until merged)
//   byte 40   8  uint64 features offset (64-aligned)
//   byte 48   8  uint64 records offset (64-aligned)
//   byte 56   8  uint64 first sector index (0 unless a shard)
//   byte 64   J  JSON header (UTF-8): generator ranges, tracer parameters, angle grids, seed, sector
//                total, feature names, feature normalisation (null in a shard), layout notes
//   ...          zero padding to the features offset
//   features     float32 [N][F] (raw, un-normalised; see offline/sector_generator.h)
//   ...          zero padding to the records offset
//   records      [N][V] values of the value type: ONE contiguous array in the AngleGrids layout,
//                uploadable as a GPU buffer or texture (R16F / R32F) without conversion
//   last 8       uint64 XXH3-64 of every byte before it
// Limits: N ≤ 2^32, J ≤ 16 MiB. A reader refuses (coif::Error naming the file and byte) a wrong
// magic, an unknown version, sizes that do not add up to the file's size, a bad JSON header,
// parameters out of range, and any checksum mismatch.
//
// Determinism: sector i depends only on (seed, i); the normalisation statistics are computed when a
// build is finalised (unsharded build or merge) from all features in index order. Hence merging the
// n shards of a build writes the same bytes as the unsharded build with the same seed.
// Resumable builds keep finished chunks in "<out>.parts/chunk-<first>.bin" (format below), each
// written atomically, and reuse the ones that are present and valid.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "models/sector_features.h"
#include "offline/planar_tracer.h"
#include "offline/sector_generator.h"

namespace coif {

inline constexpr std::uint32_t kHrirFormatVersion = 1;
enum class ValueType : std::uint32_t { Half = 1, Float = 2 };
std::size_t value_size(ValueType t);

// Everything that defines a database's content (and nothing else: no thread count, no time).
struct DbParams {
    std::uint64_t seed = 1;
    std::uint64_t sectors = 1000;
    SectorRanges generator;
    TracerParams tracer;
    AngleGrids grids;
    ValueType value_type = ValueType::Half;
};
nlohmann::json params_json(const DbParams& p);
DbParams params_from_json(const nlohmann::json& j);  // throws coif::Error
// XXH3 of the canonical JSON: two builds with the same hash produce the same records.
std::uint64_t params_hash(const DbParams& p);

// z-score statistics of the raw feature columns over all records, in index order.
struct FeatureNormalisation {
    std::vector<float> mean, scale;  // normalised = (raw − mean) / scale; scale = std (1 where std is 0)
};
FeatureNormalisation compute_normalisation(std::span<const float> features, std::size_t rows);

// One sector's content, as built.
struct SectorRecord {
    RawFeatures features{};
    std::vector<float> values;  // AngleGrids::record_values()
};
SectorRecord build_sector(const DbParams& p, std::uint64_t index);

// Half conversions (IEEE binary16, round to nearest even; glm's packHalf).
std::uint16_t float_to_half(float f);
float half_to_float(std::uint16_t h);

// ---- A loaded database: memory-mapped, read-only ----------------------------------------------------
class HrirDatabase {
public:
    // Maps and validates the file (checksum included). Throws coif::Error.
    static HrirDatabase open(const std::filesystem::path& path);
    HrirDatabase(HrirDatabase&&) noexcept;
    HrirDatabase& operator=(HrirDatabase&&) noexcept;
    HrirDatabase(const HrirDatabase&) = delete;
    HrirDatabase& operator=(const HrirDatabase&) = delete;
    ~HrirDatabase();

    const std::filesystem::path& path() const { return path_; }
    const DbParams& params() const { return params_; }
    const nlohmann::json& header() const { return header_; }
    std::uint64_t checksum() const { return checksum_; }
    std::size_t size() const { return count_; }
    std::uint64_t first_index() const { return first_; }
    bool is_shard() const { return shard_; }
    std::size_t file_size() const { return size_; }
    const FeatureNormalisation& normalisation() const { return norm_; }

    std::span<const float> features(std::size_t i) const;
    std::span<const float> all_features() const;
    // The records block: size() × record_values() values of params().value_type, contiguous.
    std::span<const std::byte> record_bytes() const;
    float value(std::size_t record, std::size_t i) const;
    std::vector<float> record(std::size_t i) const;  // decoded to float

private:
    HrirDatabase() = default;
    std::filesystem::path path_;
    const std::byte* data_ = nullptr;
    std::size_t size_ = 0;
    DbParams params_;
    nlohmann::json header_;
    FeatureNormalisation norm_;
    std::uint64_t checksum_ = 0, first_ = 0;
    std::size_t count_ = 0, features_offset_ = 0, records_offset_ = 0;
    bool shard_ = false;
};

// ---- Building -----------------------------------------------------------------------------------------
struct Shard {
    std::uint64_t index = 0, count = 1;  // shard k of n (0-based k)
    // The contiguous range of sector indices this shard owns: [N k / n, N (k+1) / n).
    std::uint64_t first(std::uint64_t total) const { return total * index / count; }
    std::uint64_t last(std::uint64_t total) const { return total * (index + 1) / count; }
};
Shard parse_shard(const std::string& text);  // "k/n" with 0 ≤ k < n; throws coif::Error::parameter

struct BuildOptions {
    DbParams params;
    Shard shard;
    int threads = 0;         // worker threads, 0 = every hardware thread (models/core/parallel.h); was 1 before v0.2
    bool resume = false;
    std::size_t chunk = 64;  // sectors per resumable chunk (progress: coif::Progress, quiet if set so)
    bool keep_parts = false; // keep FILE.parts/ after success (tests of --resume)
};
struct BuildReport {
    std::uint64_t first = 0, count = 0, reused = 0;
    double seconds = 0;  // tracing time (reused chunks excluded)
    double records_per_second() const;
};
// Builds sectors [first, last) of the shard and writes `out` atomically: a finished database if
// the shard is 0/1, else a shard file for `merge_databases`. Throws coif::Error.
BuildReport build_database(const BuildOptions& options, const std::filesystem::path& out);

// Merges shard files covering [0, N) exactly once (any order on the command line) into a finished
// database, byte-identical to the unsharded build. Throws coif::Error on gaps, overlaps, or shards
// of different builds.
void merge_databases(const std::vector<std::filesystem::path>& parts, const std::filesystem::path& out);

// Encodes decoded values [V] into the file's value type, appending to `out`.
void encode_values(ValueType type, std::span<const float> values, std::vector<std::byte>& out);

// Writes a database file from features [count][F] and encoded records [count][V · value_size].
void write_database(const std::filesystem::path& out, const DbParams& params, std::uint64_t first, std::uint64_t count,
                    bool shard, std::span<const float> features, std::span<const std::byte> records);

// A summary for `coif db inspect`.
nlohmann::json inspect_json(const HrirDatabase& db);

}  // namespace coif
