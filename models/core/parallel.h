#pragma once
// The one parallel loop of the project: fn(i) for every i in [0, count) on a number of threads the
// caller chooses. Every --threads option and every library `threads` field means the same thing:
// 0 = every hardware thread (std::thread::hardware_concurrency()), n ≥ 1 = n threads.
//
// Scheduling is dynamic: each worker takes the next index from one atomic counter, so uneven work
// (rows of an image, sectors of a database) spreads itself. The order in which indices run is
// therefore unspecified: for a result independent of the thread count, fn(i) writes only what
// belongs to i (its pixel row, its slot of a vector) and the caller reduces those in index order.
//
// Errors: the first exception any fn(i) throws stops the handing out of further indices; once every
// worker has stopped it is rethrown on the calling thread (later ones are dropped).
// With one thread (or count ≤ 1) the loop runs inline on the caller, in index order, with no thread
// started; otherwise the caller is one of the workers.
#include <cstddef>
#include <functional>

namespace coif {

// The most threads a `threads` setting may ask for: far above any machine coif runs on, below where a
// mistyped count would start thousands of threads. A system that refuses to start a thread gets a
// coif::Error too, never a crash.
inline constexpr int kMaxThreads = 4096;

// std::thread::hardware_concurrency(), or 1 where the platform cannot tell.
int hardware_threads();

// The thread count a `threads` setting stands for: 0 → hardware_threads(), n ≥ 1 → n.
// Throws coif::Error::parameter("threads", …) for a negative value or one above kMaxThreads.
int thread_count(int threads);

void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& fn);

}  // namespace coif
