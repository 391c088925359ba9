#pragma once
// Comparing two images in tests.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

#include "models/core/image.h"

namespace coif::test {

// The largest difference of one channel of one pixel between a and b; images of different sizes fail the calling test.
inline double max_difference(const Image& a, const Image& b) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    double worst = 0;
    for (std::size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i)
        worst = std::max(worst, static_cast<double>(std::abs(a.pixels[i] - b.pixels[i])));
    return worst;
}

}  // namespace coif::test
