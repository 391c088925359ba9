// models/core/atomic_file.h: the output lock stops a second process at once and is shared within one
// process; it leaves no lock file behind; taking it removes the temporaries of killed writers and keeps
// those of running ones. The waiting lock makes a second process wait instead.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "models/core/atomic_file.h"
#include "models/core/error.h"
#include "tests/common/test_data.h"

namespace {

namespace fs = std::filesystem;

// Exit code of a child process that tries to lock `path`: 0 locked, 1 refused with a coif::Error that names
// the file and the holder's pid, 2 refused otherwise.
int lock_in_child(const fs::path& path) {
    const pid_t parent = ::getpid();
    const pid_t child = ::fork();
    if (child == 0) {
        int code = 0;
        try {
            coif::OutputLock lock(path);
        } catch (const coif::Error& e) {
            const std::string what = e.what();
            code = what.find(path.string()) != std::string::npos &&
                           what.find("pid " + std::to_string(parent)) != std::string::npos
                       ? 1
                       : 2;
        } catch (...) {
            code = 2;
        }
        ::_exit(code);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A pid that ran and is gone (reaped).
pid_t finished_pid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return child;
}

void touch(const fs::path& p) { std::ofstream(p) << "x"; }

TEST(OutputLock, ASecondProcessIsRefusedAndTheLockFileGoesAway) {
    const auto dir = coif::test::scratch_dir("outputlock");
    const fs::path out = dir / "a.db";
    EXPECT_EQ(lock_in_child(out), 0);  // free: the child takes it and lets go
    EXPECT_FALSE(fs::exists(coif::OutputLock::lock_file(out)));
    {
        const coif::OutputLock held(out);
        EXPECT_TRUE(fs::exists(coif::OutputLock::lock_file(out)));
        EXPECT_EQ(lock_in_child(out), 1);
        const coif::OutputLock again(out);  // the same process: shared, not refused
        EXPECT_EQ(lock_in_child(dir / "b.db"), 0);  // another output is free
    }
    EXPECT_FALSE(fs::exists(coif::OutputLock::lock_file(out)));
    EXPECT_EQ(lock_in_child(out), 0);
    // A lock file left by a killed process (no flock on it) is taken over.
    std::ofstream(coif::OutputLock::lock_file(out)) << "999999\n";
    EXPECT_EQ(lock_in_child(out), 0);
    EXPECT_THROW(coif::OutputLock(dir / "missing" / "a.db"), coif::Error);
    fs::remove_all(dir);
}

// The waiting lock (the default database's builder holds one while the others wait): a second process asking for it
// is told that it waits and gets it once the first lets go, after the first's work is done.
TEST(WaitingLock, ASecondProcessWaitsForTheFirstAndThenGetsIt) {
    const auto dir = coif::test::scratch_dir("waitinglock");
    const fs::path lock = dir / "cache.db.building", done = dir / "cache.db";
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t child = ::fork();
    if (child == 0) {
        ::close(ready[0]);
        const coif::WaitingLock held(lock);
        char c = 'x';
        if (::write(ready[1], &c, 1) != 1) ::_exit(2);
        ::usleep(300 * 1000);  // the work the others wait for
        std::ofstream(done) << "built";
        ::_exit(0);
    }
    ::close(ready[1]);
    char c = 0;
    ASSERT_EQ(::read(ready[0], &c, 1), 1);  // the child holds the lock
    ::close(ready[0]);
    bool told = false;
    {
        const coif::WaitingLock turn(lock, [&] { told = true; });
        EXPECT_TRUE(told);
        EXPECT_TRUE(fs::exists(done)) << "the lock was granted before its holder finished";
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    told = false;
    const coif::WaitingLock free_now(lock, [&] { told = true; });  // nobody holds it: no wait
    EXPECT_FALSE(told);
    EXPECT_THROW(coif::WaitingLock(dir / "missing" / "x.building"), coif::Error);
    fs::remove_all(dir);
}

TEST(OutputLock, TakingItRemovesOnlyTheTemporariesOfFinishedWriters) {
    const auto dir = coif::test::scratch_dir("stale");
    const std::string dead = std::to_string(finished_pid()), live = std::to_string(::getppid());
    const std::vector<std::string> removed = {"a.tmp-" + dead + "-0.exr", "a.tmp-" + dead + "-17.exr"};
    const std::vector<std::string> kept = {
        "a.tmp-" + live + "-0.exr",  // its writer runs
        "b.tmp-" + dead + "-0.exr",  // another output's
        "a.tmp-" + dead + "-0.png",  // another extension: another output
        "a.tmp-" + dead + ".exr",    // not coif's pattern
        "a.tmp-x-0.exr",
    };
    for (const auto& n : removed) touch(dir / n);
    for (const auto& n : kept) touch(dir / n);
    { const coif::OutputLock lock(dir / "a.exr"); }
    for (const auto& n : removed) EXPECT_FALSE(fs::exists(dir / n)) << n;
    for (const auto& n : kept) EXPECT_TRUE(fs::exists(dir / n)) << n;

    // The folder-wide sweep (a build's chunk folder) removes every finished writer's temporary.
    const auto parts = dir / "a.db.parts";
    fs::create_directories(parts);
    touch(parts / ("chunk-0.tmp-" + dead + "-3.bin"));
    touch(parts / ("chunk-64.tmp-" + live + "-4.bin"));
    touch(parts / "chunk-128.bin");
    EXPECT_EQ(coif::remove_stale_temporaries_in(parts), 1u);
    EXPECT_TRUE(fs::exists(parts / ("chunk-64.tmp-" + live + "-4.bin")));
    EXPECT_TRUE(fs::exists(parts / "chunk-128.bin"));
    fs::remove_all(dir);
}

TEST(AtomicWrite, ReplacesTheFileWhole) {
    const auto dir = coif::test::scratch_dir("atomicwrite");
    coif::write_file_atomic(dir / "t.txt", std::string_view("first"));
    coif::write_file_atomic(dir / "t.txt", std::string_view("second, longer"));
    const auto bytes = coif::read_file_bytes(dir / "t.txt");
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()), "second, longer");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    fs::remove_all(dir);
}

}  // namespace
