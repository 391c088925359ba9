// Writes under faults, for every kind of file coif writes (database, style, lights, images in each format,
// absorption map, strands): a full disk and a read-only folder give exit code 1, an error naming the file,
// and leave no output, temporary or lock file. The disk is a 64 KiB tmpfs filled to its last page, mounted
// in a private mount namespace (`unshare --mount`, as root; a user namespace otherwise), so nothing outside
// the test sees it. Where neither is allowed the test is skipped with a message.
// Also: a second coif writing a file that another process is writing is stopped at once.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "models/core/atomic_file.h"
#include "tests/common/run.h"
#include "tests/common/test_data.h"

namespace {

namespace fs = std::filesystem;
using coif::test::read_text;
using coif::test::run_coif;

std::string q(const fs::path& p) {
    std::string s(1, '\'');
    s += p.string();
    s += '\'';
    return s;
}

// "unshare …" that gives a shell its own mounts, or "" where this machine allows none.
std::string private_mounts(const fs::path& probe_dir) {
    for (const std::string prefix : {"unshare --mount --propagation private", "unshare --user --map-root-user --mount"}) {
        const std::string cmd = prefix + " sh -c 'mount -t tmpfs -o size=64k tmpfs " + q(probe_dir) + "' >/dev/null 2>&1";
        if (std::system(cmd.c_str()) == 0) return prefix;
    }
    return "";
}

struct Case {
    std::string name, output, args;  // output: the file name in the faulty folder; args: after `coif`, with @D for it
};

// Each command's output, written into the folder D.
std::vector<Case> cases(const fs::path& in_hair) {
    const std::string tiny = "--views 8 --hrir-length 8 --fourier-order 2 --light-samples 8";
    const std::string map = (coif::test::source_dir() / "tools/assets/default_env.hdr").string();
    return {
        {"database", "t.db", "db build --sectors 6 " + tiny + " -o @D/t.db"},
        {"style", "s.json", "style import " + q(in_hair) + " --clusters 4 -o @D/s.json"},
        {"lights", "l.json", "env fit " + q(map) + " --lights 2 --fit-width 32 -o @D/l.json"},
        {"image.exr", "r.exr", "reference --width 8 --height 8 --spp 1 -o @D/r.exr"},
        {"image.png", "r.png", "reference --width 8 --height 8 --spp 1 -o @D/r.png"},
        {"image.hdr", "r.hdr", "reference --width 8 --height 8 --spp 1 -o @D/r.hdr"},
        {"absorption", "a.exr", "style paint-absorption @default --tip 0.05 0.12 0.3 -o @D/a.exr"},
        {"strands", "c.hair", "hair convert " + q(in_hair) + " @D/c.hair"},
    };
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
    return s;
}

// Runs every case with D on a tmpfs that is full (`full`) or read-only; returns, per case, "rc", "err", "ls"
// (everything left in D afterwards, recursively).
std::map<std::string, std::map<std::string, std::string>> run_faulty(const std::string& unshare, const fs::path& dir, bool full,
                                                                     const fs::path& in_hair) {
    const fs::path D = dir / "D", script = dir / "faults.sh";
    fs::create_directories(D);
    std::ofstream sh(script);
    sh << "mount -t tmpfs -o size=64k tmpfs " << q(D) << " || exit 9\n";
    if (full)  // 15 of the 16 pages: the last one goes to the lock file, so the output itself meets the full disk
        sh << "dd if=/dev/zero of=" << q(D / "filler") << " bs=4096 count=15 2>/dev/null\n";
    else
        sh << "mount -o remount,ro " << q(D) << " || exit 9\n";
    for (const Case& c : cases(in_hair)) {
        const fs::path base = dir / c.name;
        sh << "'" << COIF_EXE << "' " << replace_all(c.args, "@D", q(D)) << " >/dev/null 2>" << q(base.string() + ".err") << "\n";
        sh << "echo $? >" << q(base.string() + ".rc") << "\n";
        sh << "(cd " << q(D) << " && find . -mindepth 1 ! -name filler) >" << q(base.string() + ".ls") << "\n";
    }
    sh.close();
    EXPECT_EQ(std::system((unshare + " sh " + q(script)).c_str()), 0);
    std::map<std::string, std::map<std::string, std::string>> results;
    for (const Case& c : cases(in_hair))
        for (const char* what : {"rc", "err", "ls"}) results[c.name][what] = read_text(dir / (c.name + "." + what));
    return results;
}

void expect_refused_cleanly(const std::map<std::string, std::map<std::string, std::string>>& results, const fs::path& D,
                            const std::vector<Case>& all, const std::string& because) {
    for (const Case& c : all) {
        const auto& r = results.at(c.name);
        SCOPED_TRACE(c.name + ": " + c.args);
        EXPECT_EQ(r.at("rc"), "1\n");
        EXPECT_NE(r.at("err").find("coif: error: " + D.string() + "/"), std::string::npos) << r.at("err");  // names the file
        EXPECT_NE(r.at("err").find(because), std::string::npos) << r.at("err");
        // Nothing left: no output, temporary, lock, or (a build that finished no chunk) chunk folder.
        EXPECT_EQ(r.at("ls"), "") << "left behind in the faulty folder";
    }
}

class Faults : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = coif::test::scratch_dir("faults");
        fs::create_directories(dir_ / "probe");
        unshare_ = private_mounts(dir_ / "probe");
        if (unshare_.empty())
            GTEST_SKIP() << "skipped: this machine lets the test mount no private tmpfs (needs root, or unprivileged user "
                            "namespaces for `unshare --user --map-root-user --mount`)";
        in_hair_ = dir_ / "in.hair";
        const auto r = run_coif("style export-strands @default -o " + q(in_hair_));
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_, in_hair_;
    std::string unshare_;
};

TEST_F(Faults, AFullDiskLeavesNoPartialFile) {
    const auto results = run_faulty(unshare_, dir_, true, in_hair_);
    expect_refused_cleanly(results, dir_ / "D", cases(in_hair_), "No space left on device (the disk is full)");
}

TEST_F(Faults, AReadOnlyFolderIsRefusedBeforeTheWork) {
    const auto results = run_faulty(unshare_, dir_, false, in_hair_);
    expect_refused_cleanly(results, dir_ / "D", cases(in_hair_), "Read-only file system");
}

TEST(OutputLockCli, ASecondWriterOfTheSameFileIsStopped) {
    const auto dir = coif::test::scratch_dir("lockcli");
    const fs::path out = dir / "e.hair";
    {
        const coif::OutputLock held(out);  // this process is "the other job" writing e.hair
        const auto r = run_coif("style export-strands @default -o " + q(out));
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_NE(r.err.find("another process (pid " + std::to_string(::getpid()) + ") is writing this file"), std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    const auto r = run_coif("style export-strands @default -o " + q(out));  // free again
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out));
    EXPECT_FALSE(fs::exists(coif::OutputLock::lock_file(out)));
    fs::remove_all(dir);
}

}  // namespace
