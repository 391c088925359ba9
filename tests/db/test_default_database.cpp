// The default database policy (db/default_database.h): its cache path, reuse of a cached file, and the log that
// a library user may silence. A tiny database stands in for the default one (the policy, not the records, is
// under test; building the real one takes minutes).
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <sstream>

#include "db/default_database.h"
#include "models/core/progress.h"
#include "tests/common/test_data.h"

namespace {

namespace fs = std::filesystem;

// Sets an environment variable for one scope, restoring it after.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (old_) ::setenv(name_, old_->c_str(), 1);
        else ::unsetenv(name_);
    }

private:
    const char* name_;
    std::optional<std::string> old_;
};

TEST(DefaultDatabase, PathIsInTheXdgCacheAndNamesItsBuild) {
    const fs::path dir = coif::test::scratch_dir("default-db-path");
    const ScopedEnv xdg("XDG_CACHE_HOME", dir.string());
    const fs::path p = coif::default_database_path();
    EXPECT_EQ(p.parent_path(), dir / "coif");
    EXPECT_EQ(p.filename().string().rfind("default-" + std::to_string(coif::kDefaultDatabaseSectors) + "-", 0), 0u) << p;
    EXPECT_EQ(p.extension(), ".db");
    fs::remove_all(dir);
}

TEST(DefaultDatabase, CachedFileIsReusedAndSaidOnTheLogOnly) {
    const fs::path dir = coif::test::scratch_dir("default-db-cached");
    const ScopedEnv xdg("XDG_CACHE_HOME", dir.string());
    coif::Progress::set_quiet(true);
    coif::BuildOptions b;
    b.params.sectors = 3;
    b.params.grids = coif::AngleGrids{8, 8, 2, 8};
    const fs::path cached = coif::default_database_path();
    fs::create_directories(cached.parent_path());
    coif::build_database(b, cached);

    std::ostringstream log;
    const coif::HrirDatabase db = coif::open_database_or_default({}, &log);
    EXPECT_EQ(db.size(), 3u);
    EXPECT_NE(log.str().find("using the cached default database " + cached.string()), std::string::npos) << log.str();
    EXPECT_EQ(coif::open_database_or_default({}, nullptr).size(), 3u);  // silent

    std::ostringstream given_log;  // a given file is opened as it is, and nothing is said
    EXPECT_EQ(coif::open_database_or_default(cached, &given_log).size(), 3u);
    EXPECT_TRUE(given_log.str().empty());
    fs::remove_all(dir);
}

}  // namespace
