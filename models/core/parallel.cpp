#include "models/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "models/core/error.h"

namespace coif {

int hardware_threads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

int thread_count(int threads) {
    if (threads < 0) throw Error::parameter("threads", "must be 0 (every hardware thread) or more, not " + std::to_string(threads));
    if (threads > kMaxThreads)
        throw Error::parameter("threads", std::to_string(threads) + " is more than coif starts (at most " + std::to_string(kMaxThreads) + ")");
    return threads == 0 ? hardware_threads() : threads;
}

void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& fn) {
    // No more workers than indices: each extra one would start only to find the counter spent.
    const std::size_t workers = std::min(static_cast<std::size_t>(thread_count(threads)), count);
    if (workers <= 1) {
        for (std::size_t i = 0; i < count; ++i) fn(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::mutex error_mutex;
    std::exception_ptr error;
    const auto work = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < count;) {
            try {
                fn(i);
            } catch (...) {
                const std::lock_guard lock(error_mutex);
                if (!error) error = std::current_exception();
                next.store(count);
            }
        }
    };
    {
        std::vector<std::jthread> pool;
        pool.reserve(workers - 1);
        try {
            for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
        } catch (const std::system_error& e) {  // the system refused a thread: stop the started ones, then say so
            next.store(count);
            pool.clear();
            throw Error::parameter("threads", "cannot start " + std::to_string(workers) + " threads: " + e.what());
        }
        work();
    }  // the jthreads join here
    if (error) std::rethrow_exception(error);
}

}  // namespace coif
