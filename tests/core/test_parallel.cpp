// coif::parallel_for (models/core/parallel.h): every index once, errors reach the caller, one thread
// runs inline, and 0 means every hardware thread.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "models/core/error.h"
#include "models/core/parallel.h"

namespace {

TEST(Parallel, EveryIndexRunsExactlyOnce) {
    for (int threads : {0, 1, 2, 3, 8}) {
        for (std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{7}, std::size_t{1000}}) {
            std::vector<std::atomic<int>> runs(count);
            coif::parallel_for(count, threads, [&](std::size_t i) { runs[i].fetch_add(1); });
            for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << "index " << i << " of " << count << ", threads " << threads;
        }
    }
}

TEST(Parallel, UsesSeveralThreadsWhenAsked) {
    // Each index waits until the other one has started: with 2 workers and 2 indices that needs two
    // threads. The wait gives up after 30 s so that an implementation running them one after the other
    // fails here instead of hanging (starting a thread takes microseconds, even on a loaded machine).
    std::mutex m;
    std::vector<std::thread::id> ids;
    std::atomic<int> arrived{0};
    coif::parallel_for(2, 2, [&](std::size_t) {
        {
            const std::lock_guard lock(m);
            ids.push_back(std::this_thread::get_id());
        }
        arrived.fetch_add(1);
        for (int k = 0; k < 30000 && arrived.load() < 2; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    });
    ASSERT_EQ(ids.size(), 2u);
    EXPECT_NE(ids[0], ids[1]);
}

TEST(Parallel, OneThreadRunsInlineInOrder) {
    const auto caller = std::this_thread::get_id();
    std::vector<std::size_t> order;
    bool all_on_caller = true;
    coif::parallel_for(50, 1, [&](std::size_t i) {
        all_on_caller = all_on_caller && std::this_thread::get_id() == caller;
        order.push_back(i);  // unsynchronised on purpose: only safe because it runs inline
    });
    EXPECT_TRUE(all_on_caller);
    ASSERT_EQ(order.size(), 50u);
    for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
    // A single index runs inline whatever the thread count.
    bool inline_one = false;
    coif::parallel_for(1, 0, [&](std::size_t) { inline_one = std::this_thread::get_id() == caller; });
    EXPECT_TRUE(inline_one);
}

TEST(Parallel, FirstExceptionReachesTheCallerAfterAllWorkersStop) {
    for (int threads : {1, 2, 4}) {
        std::atomic<int> running{0}, started{0};
        try {
            coif::parallel_for(10000, threads, [&](std::size_t i) {
                running.fetch_add(1);
                started.fetch_add(1);
                if (i == 3) {
                    running.fetch_sub(1);
                    throw coif::Error("some.file", "index 3", "broken");
                }
                // Every other index takes a while, so the other workers cannot hand out all 10000 (2 s of work
                // per worker) in the moment between index 3's throw and the stop it causes.
                std::this_thread::sleep_for(std::chrono::microseconds(200));
                running.fetch_sub(1);
            });
            ADD_FAILURE() << "no exception, threads " << threads;
        } catch (const coif::Error& e) {
            EXPECT_EQ(e.problem(), "broken");
            EXPECT_EQ(e.place(), "index 3");
        }
        EXPECT_EQ(running.load(), 0) << "a worker was still running when the exception reached the caller";
        // Handing out stops at the error: far fewer than all 10000 indices start.
        EXPECT_LT(started.load(), 10000) << "threads " << threads;
    }
}

TEST(Parallel, OtherExceptionTypesPassThrough) {
    EXPECT_THROW(coif::parallel_for(100, 3, [](std::size_t i) {
        if (i % 7 == 6) throw std::out_of_range("x");
    }), std::out_of_range);
}

TEST(Parallel, ThreadCountZeroMeansEveryHardwareThread) {
    EXPECT_GE(coif::hardware_threads(), 1);
    EXPECT_EQ(coif::thread_count(0), coif::hardware_threads());
    EXPECT_EQ(coif::thread_count(1), 1);
    EXPECT_EQ(coif::thread_count(5), 5);
    EXPECT_THROW((void)coif::thread_count(-1), coif::Error);
    EXPECT_EQ(coif::thread_count(coif::kMaxThreads), coif::kMaxThreads);
    EXPECT_THROW((void)coif::thread_count(coif::kMaxThreads + 1), coif::Error);  // a mistyped count starts no threads
    EXPECT_THROW(coif::parallel_for(3, -2, [](std::size_t) {}), coif::Error);
}

}  // namespace
