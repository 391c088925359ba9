#pragma once
// Paths to the real test data in ../shared/data (outside the repo). A test that needs a file uses
//   COIF_SHARED_DATA(path, "harolongo.data");
// which skips the test with a message naming the missing folder when the data is absent (e.g. on a
// machine that only has the repository), so such a test never passes silently.
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace coif::test {

inline std::filesystem::path shared_data_dir() { return COIF_SHARED_DATA_DIR; }
inline std::filesystem::path source_dir() { return COIF_SOURCE_DIR; }

// The scratch folders this test process made, removed when it ends if every test in it passed (a failed one's are kept,
// for a look at what it wrote). ctest runs each test in a process of its own. Destroyed before gtest's UnitTest, which
// exists before the first scratch_dir call (function-local statics are destroyed in the reverse order of their making).
struct ScratchFolders {
    std::vector<std::filesystem::path> dirs;
    ScratchFolders() = default;
    ScratchFolders(const ScratchFolders&) = delete;
    ScratchFolders& operator=(const ScratchFolders&) = delete;
    ~ScratchFolders() {
        if (!::testing::UnitTest::GetInstance()->Passed()) return;
        std::error_code ec;
        for (const auto& d : dirs) std::filesystem::remove_all(d, ec);
    }
};

// A fresh empty folder for one test's outputs, under the build's temp space.
inline std::filesystem::path scratch_dir(const std::string& name) {
    static ScratchFolders made;
    auto dir = std::filesystem::temp_directory_path() / ("coif-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    made.dirs.push_back(dir);
    return dir;
}

}  // namespace coif::test

#define COIF_SHARED_DATA(var, name)                                                                        \
    const std::filesystem::path var = ::coif::test::shared_data_dir() / (name);                           \
    if (!std::filesystem::exists(var))                                                                    \
    GTEST_SKIP() << "skipped: real test data " << var << " is absent (the tests expect ../shared/data "   \
                    "beside the repository)"
