// The HRIR database (db/hrir_db.h, db/satf.h): deterministic and shardable builds, every corrupt-file
// case refused, and the look-up returning a record for its own features. Tiny databases: fast.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <numbers>

#include "db/coverage.h"
#include "db/hrir_db.h"
#include "db/satf.h"
#include "models/core/atomic_file.h"
#include "models/core/checksum.h"
#include "models/core/error.h"
#include "models/core/progress.h"
#include "tests/common/test_data.h"

namespace {

namespace fs = std::filesystem;

coif::BuildOptions tiny(std::uint64_t sectors = 7) {
    coif::Progress::set_quiet(true);
    coif::BuildOptions o;
    o.params.sectors = sectors;
    o.params.seed = 9;
    o.params.grids = coif::AngleGrids{8, 8, 2, 8};
    o.chunk = 2;
    return o;
}

std::vector<std::byte> bytes(const fs::path& p) { return coif::read_file_bytes(p); }

void write_bytes(const fs::path& p, const std::vector<std::byte>& b) {
    std::ofstream f(p, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// Expects open() to throw a coif::Error whose message contains `what`.
void expect_refused(const fs::path& p, const std::string& what) {
    try {
        (void)coif::HrirDatabase::open(p);
        ADD_FAILURE() << "accepted " << p;
    } catch (const coif::Error& e) {
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
}

TEST(HrirDb, BuildsAreDeterministicAcrossThreadCounts) {
    const auto dir = coif::test::scratch_dir("db-determinism");
    auto o = tiny();
    o.threads = 1;
    coif::build_database(o, dir / "a.db");
    o.threads = 2;
    coif::build_database(o, dir / "b.db");
    EXPECT_EQ(bytes(dir / "a.db"), bytes(dir / "b.db"));
    o.threads = 0;  // the default: every hardware thread
    EXPECT_EQ(coif::BuildOptions{}.threads, 0);
    coif::build_database(o, dir / "c.db");
    EXPECT_EQ(bytes(dir / "a.db"), bytes(dir / "c.db"));
    EXPECT_FALSE(fs::exists(dir / "a.db.parts"));
    const auto db = coif::HrirDatabase::open(dir / "a.db");
    EXPECT_EQ(db.size(), 7u);
    EXPECT_FALSE(db.is_shard());
    EXPECT_EQ(db.record_bytes().size(), 7u * o.params.grids.record_values() * 2);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(db.record_bytes().data()) % 64, 0u);  // GPU-uploadable, aligned
}

TEST(HrirDb, ShardMergeIsByteIdenticalToTheUnshardedBuild) {
    const auto dir = coif::test::scratch_dir("db-shards");
    auto o = tiny();
    coif::build_database(o, dir / "whole.db");
    std::vector<fs::path> parts;
    for (std::uint64_t k = 0; k < 3; ++k) {
        o.shard = {k, 3};
        parts.push_back(dir / ("part" + std::to_string(k) + ".db"));
        coif::build_database(o, parts.back());
        EXPECT_TRUE(coif::HrirDatabase::open(parts.back()).is_shard());
    }
    std::reverse(parts.begin(), parts.end());  // any order on the command line
    coif::merge_databases(parts, dir / "merged.db");
    EXPECT_EQ(bytes(dir / "whole.db"), bytes(dir / "merged.db"));

    // A missing shard, a duplicated one, or a shard of another build is refused.
    EXPECT_THROW(coif::merge_databases({parts[0], parts[1]}, dir / "gap.db"), coif::Error);
    EXPECT_THROW(coif::merge_databases({parts[0], parts[1], parts[2], parts[2]}, dir / "dup.db"), coif::Error);
    auto other = tiny();
    other.params.seed = 10;
    other.shard = {0, 3};
    coif::build_database(other, dir / "other0.db");
    EXPECT_THROW(coif::merge_databases({dir / "other0.db", parts[0], parts[1]}, dir / "mixed.db"), coif::Error);
    EXPECT_FALSE(fs::exists(dir / "gap.db"));
    EXPECT_FALSE(fs::exists(dir / "mixed.db"));
}

TEST(HrirDb, ResumeReusesValidChunksAndRebuildsBadOnes) {
    const auto dir = coif::test::scratch_dir("db-resume");
    auto o = tiny();
    o.keep_parts = true;  // what a killed build leaves behind
    coif::build_database(o, dir / "a.db");
    const auto reference = bytes(dir / "a.db");
    ASSERT_TRUE(fs::exists(dir / "a.db.parts/chunk-2.bin"));
    // Corrupt one chunk, truncate another: both are rebuilt, the rest reused.
    auto c = bytes(dir / "a.db.parts/chunk-2.bin");
    c[50] ^= std::byte{0xFF};
    write_bytes(dir / "a.db.parts/chunk-2.bin", c);
    fs::resize_file(dir / "a.db.parts/chunk-4.bin", 20);
    fs::remove(dir / "a.db");
    o.resume = true;
    o.keep_parts = false;
    const auto report = coif::build_database(o, dir / "a.db");
    EXPECT_EQ(report.reused, 3u);  // chunks 0 and 6 (2 + 1 sectors); 2 and 4 rebuilt
    EXPECT_EQ(bytes(dir / "a.db"), reference);
    EXPECT_FALSE(fs::exists(dir / "a.db.parts"));
}

TEST(HrirDb, EveryCorruptFileIsRefused) {
    const auto dir = coif::test::scratch_dir("db-corrupt");
    const auto o = tiny(3);
    coif::build_database(o, dir / "good.db");
    const auto good = bytes(dir / "good.db");
    const auto variant = [&](const std::string& name, auto&& edit) {
        auto b = good;
        edit(b);
        write_bytes(dir / name, b);
        return dir / name;
    };
    write_bytes(dir / "empty.db", {});
    expect_refused(dir / "empty.db", "truncated");
    expect_refused(variant("magic.db", [](auto& b) { b[0] = std::byte{'X'}; }), "bad magic");
    expect_refused(variant("version.db", [](auto& b) { b[8] = std::byte{9}; }), "format version 9");
    expect_refused(variant("truncated.db", [](auto& b) { b.erase(b.end() - 100, b.end()); }), "truncated or corrupt");
    expect_refused(variant("extended.db", [](auto& b) { b.push_back(std::byte{0}); }), "truncated or corrupt");
    expect_refused(variant("record.db", [](auto& b) { b[b.size() - 20] ^= std::byte{1}; }), "checksum mismatch");
    expect_refused(variant("json.db", [](auto& b) { b[70] ^= std::byte{0x20}; }), "checksum mismatch");
    expect_refused(variant("valuetype.db", [](auto& b) { b[32] = std::byte{7}; }), "unknown value type");
    expect_refused(dir / "missing.db", "cannot open");
    // A header that is valid JSON but disagrees with the binary layout (checksum recomputed).
    {
        auto b = good;
        std::uint32_t J;
        std::memcpy(&J, b.data() + 12, 4);
        std::string json(reinterpret_cast<const char*>(b.data() + 64), J);
        const auto at = json.find("\"views\":8");
        ASSERT_NE(at, std::string::npos);
        json.replace(at, 9, "\"views\":9");
        std::memcpy(b.data() + 64, json.data(), J);
        const std::uint64_t h = coif::checksum(std::span<const std::byte>(b.data(), b.size() - 8));
        std::memcpy(b.data() + b.size() - 8, &h, 8);
        write_bytes(dir / "mismatch.db", b);
        expect_refused(dir / "mismatch.db", "disagrees with the binary header");
    }
}

TEST(HrirDb, LookUpOfARecordsOwnFeaturesReturnsThatRecord) {
    const auto dir = coif::test::scratch_dir("db-lookup");
    auto o = tiny(12);
    coif::build_database(o, dir / "a.db");
    const auto db = coif::HrirDatabase::open(dir / "a.db");
    const auto& g = db.params().grids;
    coif::SatfOptions so;
    so.k = 1;
    const coif::SatfIndex index(db, so);
    std::vector<float> re(static_cast<std::size_t>(g.hrir_length)), alpha(re.size()), re_rec(re.size()), a_rec(re.size());
    for (std::size_t i = 0; i < db.size(); ++i) {
        const auto f = db.features(i);
        const auto m = index.match(f);
        // Several sectors can share identical features (e.g. empty ones); then any of them is exact.
        const auto fm = db.features(m.id[0]);
        EXPECT_TRUE(std::equal(f.begin(), f.end(), fm.begin())) << "sector " << i;
        // At a grid view the look-up is the stored record, exactly (same arithmetic).
        index.evaluate(m, 2 * std::numbers::pi * 3 / g.views, 1.1, re, alpha);
        coif::evaluate_record(g, db.record(m.id[0]), 2 * std::numbers::pi * 3 / g.views, 1.1, re_rec, a_rec);
        for (std::size_t x = 0; x < re.size(); ++x) {
            EXPECT_NEAR(re[x], re_rec[x], 1e-6);
            EXPECT_NEAR(alpha[x], a_rec[x], 1e-6);
        }
    }
    // The batched form agrees with single queries.
    const auto all = index.match_all(db.all_features());
    for (std::size_t i = 0; i < db.size(); ++i) EXPECT_EQ(all[i].id[0], index.match(db.features(i)).id[0]);
}

// `coif db coverage`'s density match: a database's own sectors, looked up, find records of their own density (ratio 1
// exactly: the nearest record of a sector's features is itself or one with identical features), and a style whose
// sectors are all empty has no ratio at all.
TEST(HrirDb, CoverageOfADatabasesOwnSectorsMatchesTheirDensity) {
    const auto dir = coif::test::scratch_dir("db-coverage-density");
    auto o = tiny(12);
    coif::build_database(o, dir / "a.db");
    const auto db = coif::HrirDatabase::open(dir / "a.db");
    const std::vector<float> held = coif::held_out_sector_features(db.params(), 4);
    const std::span<const float> own = db.all_features();
    const coif::CoverageOptions options;
    const coif::CoverageReport r = coif::database_coverage(db, own, held, options);
    std::size_t nonempty = 0;
    for (std::size_t i = 0; i < db.size(); ++i) nonempty += db.features(i)[coif::kMeanDensityColumn] >= options.empty_density ? 1 : 0;
    ASSERT_GT(nonempty, 0u);
    EXPECT_EQ(r.density_ratio.sectors, nonempty);
    EXPECT_DOUBLE_EQ(r.density_ratio.p10, 1.0);
    EXPECT_DOUBLE_EQ(r.density_ratio.median, 1.0);
    EXPECT_DOUBLE_EQ(r.density_ratio.p90, 1.0);
    EXPECT_DOUBLE_EQ(r.density_ratio.outside_half_to_double, 0.0);

    std::vector<float> empty(own.begin(), own.end());
    for (std::size_t i = 0; i < db.size(); ++i) empty[i * coif::kRawFeatureCount + coif::kMeanDensityColumn] = 0.0f;
    const coif::CoverageReport e = coif::database_coverage(db, empty, held, options);
    EXPECT_EQ(e.density_ratio.sectors, 0u);
    EXPECT_EQ(e.density_ratio.median, 0.0);
}

TEST(HrirDb, SavedFlannIndexIsBoundToItsDatabase) {
    const auto dir = coif::test::scratch_dir("db-flann");
    auto o = tiny(10);
    coif::build_database(o, dir / "a.db");
    o.params.seed = 77;
    coif::build_database(o, dir / "b.db");
    const auto a = coif::HrirDatabase::open(dir / "a.db");
    const auto b = coif::HrirDatabase::open(dir / "b.db");
    coif::SatfOptions so;
    so.k = 3;
    coif::SatfIndex ia(a, so);
    const fs::path saved = coif::SatfIndex::saved_path(a, so.set);
    ia.save(saved);
    const auto before = ia.match_all(a.all_features());
    ia.load(saved);
    const auto after = ia.match_all(a.all_features());
    for (std::size_t i = 0; i < before.size(); ++i)
        for (int j = 0; j < so.k; ++j) EXPECT_EQ(before[i].id[static_cast<std::size_t>(j)], after[i].id[static_cast<std::size_t>(j)]);
    coif::SatfIndex ib(b, so);
    EXPECT_THROW(ib.load(saved), coif::Error);  // another database's checksum
    auto bad = bytes(saved);
    bad[bad.size() / 2] ^= std::byte{0x10};
    write_bytes(dir / "bad.flann", bad);
    EXPECT_THROW(ia.load(dir / "bad.flann"), coif::Error);
    // open() falls back to building when the saved index is stale.
    const auto ob = coif::SatfIndex::open(b, so);
    EXPECT_EQ(ob.match(b.features(0)).id[0], ib.match(b.features(0)).id[0]);
}

TEST(HrirDb, ShardParsing) {
    EXPECT_EQ(coif::parse_shard("3/8").index, 3u);
    EXPECT_EQ(coif::parse_shard("3/8").count, 8u);
    EXPECT_THROW(coif::parse_shard("8/8"), coif::Error);
    EXPECT_THROW(coif::parse_shard("x/8"), coif::Error);
    EXPECT_THROW(coif::parse_shard("3"), coif::Error);
    const coif::Shard s{2, 3};
    EXPECT_EQ(s.first(10), 6u);
    EXPECT_EQ(s.last(10), 10u);
}

}  // namespace
