// `coif db …` at the command line: exit codes, messages that name the file, nothing written on
// failure, --json output, and the help of every subcommand. Tiny databases (6 sectors, 8×8 grids):
// fast.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "models/core/atomic_file.h"
#include "tests/common/run.h"
#include "tests/common/test_data.h"

namespace {

namespace fs = std::filesystem;
using coif::test::run_coif;

const char* const kTinyGrids = "--views 8 --hrir-length 8 --fourier-order 2 --light-samples 8";

// Shell-quoted path (appended piecewise: GCC 12's -Wrestrict misfires on "'" + string).
std::string q(const fs::path& p) {
    std::string s(1, '\'');
    s += p.string();
    s += '\'';
    return s;
}

// Builds a 6-sector database at dir/name through the command line.
fs::path tiny_db(const fs::path& dir, const std::string& name = "t.db", const std::string& extra = "") {
    const fs::path out = dir / name;
    const auto r = run_coif("db build --sectors 6 --seed 3 " + std::string(kTinyGrids) + " " + extra + " -o " + q(out));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
}

void write_bytes(const fs::path& p, const std::vector<std::byte>& b) {
    std::ofstream f(p, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// Only these names in the folder: nothing half-written (temporaries, FILE.parts/) is left behind.
void expect_only(const fs::path& dir, std::vector<std::string> names) {
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir)) found.push_back(e.path().filename().string());
    std::sort(found.begin(), found.end());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(found, names);
}

TEST(DbCli, BuildThenInspectJson) {
    const auto dir = coif::test::scratch_dir("dbcli-build");
    const fs::path db = tiny_db(dir);
    expect_only(dir, {"t.db"});  // the chunk folder is removed after success
    const auto r = run_coif("db inspect " + q(db) + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);  // stdout is JSON only
    EXPECT_EQ(j["kind"], "database");
    EXPECT_EQ(j["sectors"], 6);
    EXPECT_EQ(j["sectors_in_build"], 6);
    EXPECT_EQ(j["bytes"], fs::file_size(db));
    EXPECT_EQ(j["features"].size(), 18u);
    const auto t = run_coif("db inspect " + q(db));
    EXPECT_EQ(t.exit_code, 0) << t.err;
    EXPECT_NE(t.out.find("sectors          6"), std::string::npos) << t.out;
}

TEST(DbCli, CorruptAndTruncatedFilesExitOneNamingTheFile) {
    const auto dir = coif::test::scratch_dir("dbcli-corrupt");
    const fs::path good = tiny_db(dir);
    const std::vector<std::byte> bytes = coif::read_file_bytes(good);
    std::vector<std::byte> flipped = bytes;
    flipped[bytes.size() / 2] ^= std::byte{0x40};  // inside the records: only the checksum can tell
    write_bytes(dir / "flipped.db", flipped);
    write_bytes(dir / "truncated.db", std::vector<std::byte>(bytes.begin(), bytes.end() - 100));
    write_bytes(dir / "empty.db", {});
    for (const char* name : {"flipped.db", "truncated.db", "empty.db"}) {
        const fs::path p = dir / name;
        const std::vector<std::string> commands = {"db inspect " + q(p), "db eval " + q(p) + " --held-out 1 --k 1",
                                                   "db coverage " + q(p) + " @default --held-out 2",
                                                   "db plot " + q(p) + " -o " + q(dir / "plot.png"), "db index " + q(p)};
        for (const std::string& cmd : commands) {
            const auto r = run_coif(cmd);
            EXPECT_EQ(r.exit_code, 1) << cmd << "\n" << r.err;
            EXPECT_NE(r.err.find("coif: error: " + p.string()), std::string::npos) << cmd << "\n" << r.err;
        }
    }
    // A corrupt part refuses the merge, and no output appears.
    const auto m = run_coif("db merge " + q(dir / "flipped.db") + " -o " + q(dir / "merged.db"));
    EXPECT_EQ(m.exit_code, 1) << m.err;
    EXPECT_NE(m.err.find("flipped.db"), std::string::npos) << m.err;
    expect_only(dir, {"t.db", "flipped.db", "truncated.db", "empty.db"});
}

TEST(DbCli, BadShardSyntaxIsRefusedAndWritesNothing) {
    const auto dir = coif::test::scratch_dir("dbcli-shard");
    for (const std::string shard : {"3", "3/2", "2/2", "1/0", "a/b", "1/2x", "-1/2", "/"}) {
        const auto r = run_coif("db build --sectors 4 " + std::string(kTinyGrids) + " --shard '" + shard + "' -o " + q(dir / "s.db"));
        EXPECT_EQ(r.exit_code, 1) << shard << "\n" << r.err;  // a bad parameter value: exit 1 (conventions)
        EXPECT_NE(r.err.find("--shard " + shard), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("k/n"), std::string::npos) << r.err;
    }
    const auto missing = run_coif("db build --sectors 4 --shard -o " + q(dir / "s.db"));  // no value: a parse error
    EXPECT_EQ(missing.exit_code, 2) << missing.err;
    expect_only(dir, {});
}

TEST(DbCli, FailuresLeaveNoOutputBehind) {
    const auto dir = coif::test::scratch_dir("dbcli-nothing");
    // Shards of one build do not make a finished database when one is missing.
    const fs::path p0 = tiny_db(dir, "p0.db", "--shard 0/3");
    const fs::path p2 = tiny_db(dir, "p2.db", "--shard 2/3");
    const auto gap = run_coif("db merge " + q(p0) + " " + q(p2) + " -o " + q(dir / "m.db"));
    EXPECT_EQ(gap.exit_code, 1) << gap.err;
    // A shard cannot be looked up, evaluated or measured for coverage.
    for (const std::string verb : {"eval", "coverage", "index"}) {
        const auto r = run_coif("db " + verb + " " + q(p0) + (verb == "coverage" ? " @default" : ""));
        EXPECT_EQ(r.exit_code, 1) << verb << "\n" << r.err;
        EXPECT_NE(r.err.find("shard"), std::string::npos) << r.err;
    }
    // Bad parameter values.
    EXPECT_EQ(run_coif("db build --sectors 4 --views 0 -o " + q(dir / "v.db")).exit_code, 1);
    EXPECT_EQ(run_coif("db eval " + q(p0) + " --features nonsense").exit_code, 1);
    const fs::path db = tiny_db(dir);
    const auto missing_style = run_coif("db coverage " + q(db) + " " + q(dir / "absent.json"));
    EXPECT_EQ(missing_style.exit_code, 1) << missing_style.err;
    EXPECT_NE(missing_style.err.find("absent.json"), std::string::npos) << missing_style.err;
    const auto plot = run_coif("db plot " + q(db) + " --record 99 -o " + q(dir / "plot.png"));
    EXPECT_EQ(plot.exit_code, 1) << plot.err;
    expect_only(dir, {"p0.db", "p2.db", "t.db"});
}

TEST(DbCli, CoverageOfTheDefaultStyleAsJson) {
    const auto dir = coif::test::scratch_dir("dbcli-coverage");
    const fs::path db = tiny_db(dir);
    const auto r = run_coif("db coverage " + q(db) + " @default --held-out 5 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j.size(), 1u);
    const auto& c = j[0];
    EXPECT_EQ(c["style"], "@default");
    EXPECT_EQ(c["database_sectors"], 6);
    EXPECT_EQ(c["held_out_sectors"], 5);
    EXPECT_EQ(c["style_sectors"], 64 * 9 * 4 * 8);  // the embedded style: 64 clusters × (s_t + 1)·L·s_u sectors
    EXPECT_EQ(c["columns"].size(), 18u);
    // Shares are fractions; distances non-negative and the p95 at least the median.
    for (const auto& col : c["columns"]) {
        EXPECT_GE(col["share_below_db_p01"].get<double>(), 0.0);
        EXPECT_LE(col["share_below_db_p01"].get<double>() + col["share_above_db_p99"].get<double>(), 1.0);
    }
    for (const char* who : {"style", "held_out"}) {
        const auto& d = c["nearest_record_distance"][who];
        EXPECT_GE(d["median"].get<double>(), 0.0);
        EXPECT_GE(d["p95"].get<double>(), d["median"].get<double>());
    }
    // The density match: the tiny database's 6 records cannot match the style's densities, but the figures are ordered
    // quantiles of positive ratios over the non-empty sectors, and a share.
    const auto& dm = c["density_ratio"];
    ASSERT_TRUE(dm.is_object()) << c.dump();
    EXPECT_GT(dm["sectors"].get<int>(), 0);
    EXPECT_LE(dm["sectors"].get<int>(), c["style_sectors"].get<int>());
    ASSERT_TRUE(dm["p10"].is_number() && dm["median"].is_number()) << dm.dump();
    EXPECT_GT(dm["p10"].get<double>(), 0.0);
    EXPECT_LE(dm["p10"].get<double>(), dm["median"].get<double>());
    if (dm["p90"].is_number()) {
        EXPECT_LE(dm["median"].get<double>(), dm["p90"].get<double>());
    }
    EXPECT_GE(dm["share_outside_half_to_double"].get<double>(), 0.0);
    EXPECT_LE(dm["share_outside_half_to_double"].get<double>(), 1.0);
    const auto text = run_coif("db coverage " + q(db) + " @default --held-out 5");
    EXPECT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("mean density, style sector over its nearest record"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("ln_depth_over_lambda"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("nearest-record distance"), std::string::npos) << text.out;
}

TEST(DbCli, EverySubcommandHelpHasExamples) {
    for (const char* verb : {"build", "merge", "inspect", "plot", "eval", "index", "coverage"}) {
        const auto r = run_coif(std::string("db ") + verb + " --help");
        EXPECT_EQ(r.exit_code, 0) << verb;
        EXPECT_NE(r.out.find("Examples:"), std::string::npos) << verb << "\n" << r.out;
        EXPECT_NE(r.out.find("coif db " + std::string(verb)), std::string::npos) << verb << "\n" << r.out;
    }
}

}  // namespace
