// models/core/units.h: the constants are exactly the values the code used before they had one home
// (so no image moves), and the conversions invert each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "models/core/units.h"

namespace {

// The literals that were spelled out in the sources before, compared bit for bit.
static_assert(coif::kPi == 3.14159265358979323846);
static_assert(coif::kPiF == 3.14159265358979323846f);
static_assert(coif::kPiF == 3.1415927f);
static_assert(coif::kTwoPiF == 6.2831853f);
static_assert(coif::kRadiansPerDegree == 0.017453292519943295);
static_assert(coif::kDegreesPerRadian == 57.29577951308232);
static_assert(coif::radians(1.0f) == 0.017453292519943295f);
static_assert(coif::kCentimetresPerMetre == 100.0);

TEST(Units, DegreesAndRadiansRoundTrip) {
    for (double d : {-180.0, -7.5, 0.0, 1.0, 45.0, 90.0, 360.0}) EXPECT_NEAR(coif::degrees(coif::radians(d)), d, 1e-12 * std::max(1.0, std::abs(d)));
    EXPECT_DOUBLE_EQ(coif::radians(180.0), coif::kPi);
    EXPECT_FLOAT_EQ(coif::radians(90.0f), 0.5f * coif::kPiF);
}

}  // namespace
