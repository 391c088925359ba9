#pragma once
// Progress of long work, on stderr. On a terminal: one line redrawn in place
//   "label  [#########.........]  45%  4500/10000  1234/s  eta 4s"
// Otherwise (a log file, CI): a plain line at every 10 % and at the end, so logs stay readable.
// Thread-safe: advance() may be called from worker threads. Quiet mode (set_quiet) prints nothing,
// for --json output and tests.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace coif {

class Progress {
public:
    Progress(std::string label, std::uint64_t total);
    ~Progress();  // finishes the line if finish() was not called
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void advance(std::uint64_t n = 1);
    void finish();
    double elapsed_seconds() const;

    static void set_quiet(bool quiet);

private:
    void draw(std::uint64_t done, bool final);
    std::string label_;
    std::uint64_t total_;
    std::atomic<std::uint64_t> done_{0};
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
    int last_decile_ = -1;
    bool tty_;
    bool finished_ = false;
    std::mutex mutex_;
};

}  // namespace coif
