#pragma once
// Small statistics of measured values (timings of frames and passes).
#include <algorithm>
#include <cstddef>
#include <vector>

namespace coif {

// The median of `v` (not empty; of an even count, the upper of the two middle values).
inline double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace coif
