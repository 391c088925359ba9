// `coif db build` survives SIGKILL: a build killed at seeded moments of its progress, several times over, and then
// finished with --resume writes a database byte-identical to an uninterrupted build, and leaves nothing
// else behind (the killed runs' temporaries and lock file are cleaned up by the run that finishes).
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <random>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "models/core/atomic_file.h"
#include "tests/common/run.h"
#include "tests/common/test_data.h"

namespace {

namespace fs = std::filesystem;
using coif::test::run_coif;

// A small build with many chunks (150 chunk writes), so that kills land while tracing, while a chunk is
// written and flushed, and while the database itself is written.
const std::vector<std::string> kBuild = {"db",  "build", "--sectors", "300", "--seed", "5", "--views", "8", "--hrir-length", "8",
                                          "--fourier-order", "2", "--light-samples", "8", "--chunk", "2", "--threads", "1"};

std::string shell_args(const fs::path& out, bool resume) {
    std::string s;
    for (const auto& a : kBuild) s += a + " ";
    if (resume) s += "--resume ";
    return s + "-o '" + out.string() + "'";
}

// Starts `coif db build … --resume -o out` with its output thrown away; returns its pid.
pid_t spawn_build(const fs::path& out) {
    std::vector<std::string> args = {COIF_EXE};
    args.insert(args.end(), kBuild.begin(), kBuild.end());
    args.insert(args.end(), {"--resume", "-o", out.string()});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 1);
        ::dup2(null, 2);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    return pid;
}

std::vector<std::string> names_in(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Finished chunks in the build's chunk folder (their temporaries not counted).
std::size_t finished_chunks(const fs::path& parts) {
    std::size_t n = 0;
    std::error_code ec;
    for (fs::directory_iterator it(parts, ec), e; !ec && it != e; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        n += name.rfind("chunk-", 0) == 0 && name.find(".tmp-") == std::string::npos;
    }
    return n;
}

TEST(DbFaults, KilledBuildsResumeToTheSameBytes) {
    const auto dir = coif::test::scratch_dir("dbfaults");
    const fs::path reference = dir / "reference.db", killed_dir = dir / "killed", out = killed_dir / "k.db";
    fs::path parts = out;
    parts += ".parts";
    fs::create_directories(killed_dir);
    const auto ref = run_coif(shell_args(reference, false));
    ASSERT_EQ(ref.exit_code, 0) << ref.err;

    // The kill moments are seeded and tied to the build's progress, not to the clock (a sanitizer build or a
    // loaded machine starts and traces at another pace): run i is killed once the folder holds a seeded
    // number of finished chunks more than the last run left (1..15 of the 150), plus a seeded 0..20 ms, so
    // that kills land while sectors are traced, while a chunk is written and flushed, or between the two.
    std::mt19937 rng(2026);
    std::uniform_int_distribution<std::size_t> more(1, 15);
    std::uniform_int_distribution<int> extra_us(0, 20000);
    constexpr int kRuns = 8;
    int killed = 0;
    std::string log;
    for (int run = 0; run < kRuns; ++run) {
        const std::size_t target = finished_chunks(parts) + more(rng);
        const int extra = extra_us(rng);
        log += "run " + std::to_string(run) + ": kill at " + std::to_string(target) + " chunks + " + std::to_string(extra) + " us; ";
        const pid_t pid = spawn_build(out);
        ASSERT_GT(pid, 0);
        int status = 0;
        bool exited = false;
        while (finished_chunks(parts) < target) {
            if (::waitpid(pid, &status, WNOHANG) == pid) {
                exited = true;
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        ASSERT_FALSE(exited) << "the build ended before its kill (status " << status << "): " << log;
        std::this_thread::sleep_for(std::chrono::microseconds(extra));
        ::kill(pid, SIGKILL);
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << log;
        ++killed;
        EXPECT_FALSE(fs::exists(out)) << log;  // killed: no database, not even a partial one
    }
    const std::size_t left = finished_chunks(parts);
    const auto last = run_coif(shell_args(out, true));
    ASSERT_EQ(last.exit_code, 0) << last.err;
    // "wrote …: sectors 0..300 (N reused), …"
    const std::size_t at = last.err.find(" reused)");
    ASSERT_NE(at, std::string::npos) << last.err;
    const std::size_t open = last.err.rfind('(', at);
    ASSERT_NE(open, std::string::npos) << last.err;
    const std::string reused = last.err.substr(open + 1, at - open - 1);
    EXPECT_EQ(std::stoul(reused), 2 * left) << "the last run must reuse every chunk the killed runs finished: " << log;
    EXPECT_EQ(coif::read_file_bytes(out), coif::read_file_bytes(reference)) << log;
    EXPECT_EQ(names_in(killed_dir), std::vector<std::string>{"k.db"}) << log;  // no temporaries, lock or chunks
    std::printf("%d runs killed mid-build (%s); then --resume reused %s sectors and wrote the same bytes\n", killed,
                log.c_str(), reused.c_str());
    fs::remove_all(dir);
}

}  // namespace
