// `coif db build` survives SIGKILL: a build killed at seeded random moments, several times over, and then
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

TEST(DbFaults, KilledBuildsResumeToTheSameBytes) {
    const auto dir = coif::test::scratch_dir("dbfaults");
    const fs::path reference = dir / "reference.db", killed_dir = dir / "killed", out = killed_dir / "k.db";
    fs::create_directories(killed_dir);

    const auto t0 = std::chrono::steady_clock::now();
    const auto ref = run_coif(shell_args(reference, false));
    ASSERT_EQ(ref.exit_code, 0) << ref.err;
    // The uninterrupted build's time sets the scale of the kill moments (a choice of moments, not a limit).
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    std::mt19937 rng(2026);
    std::uniform_real_distribution<double> moment(0.05, 0.35);  // of the uninterrupted build's time
    constexpr int kRuns = 8;
    int killed = 0, finished = 0;
    std::string log;
    for (int run = 0; run < kRuns; ++run) {
        const double delay = moment(rng) * seconds;
        log += "run " + std::to_string(run) + ": kill after " + std::to_string(delay) + " s; ";
        const pid_t pid = spawn_build(out);
        ASSERT_GT(pid, 0);
        std::this_thread::sleep_for(std::chrono::duration<double>(delay));
        ::kill(pid, SIGKILL);
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        if (WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) {
            ++killed;
            // Killed: no database (not even a partial one) at the output.
            EXPECT_FALSE(fs::exists(out)) << log;
        } else {
            ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << log;
            ++finished;  // it completed before the kill: start over, so that the next runs are killed mid-build
            fs::remove(out);
        }
    }
    // Most runs must really be killed mid-build, or this test tests nothing.
    EXPECT_GE(killed, kRuns - 2) << log;

    const auto last = run_coif(shell_args(out, true));
    ASSERT_EQ(last.exit_code, 0) << last.err;
    // "wrote …: sectors 0..300 (N reused), …"
    const std::size_t at = last.err.find(" reused)");
    ASSERT_NE(at, std::string::npos) << last.err;
    const std::size_t open = last.err.rfind('(', at);
    ASSERT_NE(open, std::string::npos) << last.err;
    const std::string reused = last.err.substr(open + 1, at - open - 1);
    EXPECT_GT(std::stoi(reused), 0) << "the last run reused nothing: " << log;
    EXPECT_EQ(coif::read_file_bytes(out), coif::read_file_bytes(reference)) << log;
    EXPECT_EQ(names_in(killed_dir), std::vector<std::string>{"k.db"}) << log;  // no temporaries, lock or chunks
    std::printf("%d runs killed, %d finished before their kill; then --resume reused %s sectors and wrote the same bytes\n",
                killed, finished, reused.c_str());
    fs::remove_all(dir);
}

}  // namespace
