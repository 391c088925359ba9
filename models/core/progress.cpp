#include "models/core/progress.h"

#include <cstdio>
#include <unistd.h>

namespace coif {
namespace {
std::atomic<bool> g_quiet{false};
}

void Progress::set_quiet(bool quiet) { g_quiet = quiet; }

Progress::Progress(std::string label, std::uint64_t total)
    : label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()),
      last_draw_(start_ - std::chrono::seconds(1)), tty_(::isatty(2) == 1) {}

Progress::~Progress() {
    if (!finished_) finish();
}

double Progress::elapsed_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::advance(std::uint64_t n) {
    const std::uint64_t done = done_ += n;
    if (g_quiet) return;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;  // another thread is drawing; skip this update
    draw(done, false);
}

void Progress::finish() {
    if (finished_) return;
    finished_ = true;
    if (g_quiet) return;
    std::lock_guard lock(mutex_);
    draw(done_.load(), true);
}

void Progress::draw(std::uint64_t done, bool final) {
    const auto now = std::chrono::steady_clock::now();
    const double t = std::chrono::duration<double>(now - start_).count();
    const double frac = total_ ? std::min(1.0, double(done) / double(total_)) : 1.0;
    const double rate = t > 0 ? double(done) / t : 0.0;
    const double eta = rate > 0 && total_ > done ? double(total_ - done) / rate : 0.0;
    if (tty_) {
        if (!final && now - last_draw_ < std::chrono::milliseconds(100)) return;
        last_draw_ = now;
        constexpr int kWidth = 28;
        const int filled = static_cast<int>(frac * kWidth);
        std::string bar(filled, '#');
        bar.append(kWidth - filled, '.');
        std::fprintf(stderr, "\r%s  [%s] %3d%%  %llu/%llu  %.4g/s  %s %.0fs\033[K%s", label_.c_str(), bar.c_str(),
                     static_cast<int>(frac * 100), static_cast<unsigned long long>(done),
                     static_cast<unsigned long long>(total_), rate, final ? "took" : "eta", final ? t : eta,
                     final ? "\n" : "");
    } else {
        const int decile = static_cast<int>(frac * 10);
        if (!final && decile == last_decile_) return;
        if (final && decile == last_decile_ && frac < 1.0) return;
        last_decile_ = decile;
        std::fprintf(stderr, "%s: %3d%% (%llu/%llu, %.4g/s, %.1fs)\n", label_.c_str(), static_cast<int>(frac * 100),
                     static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_), rate, t);
    }
    std::fflush(stderr);
}

}  // namespace coif
