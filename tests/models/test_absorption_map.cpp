// Painted absorption maps (models/absorption_map.h): file round trip, interpolation along t, and
// every bad file refused with its name and place.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "models/absorption_map.h"
#include "models/core/error.h"
#include "models/core/image.h"

namespace coif {
namespace {

std::filesystem::path temp(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("coif-absorption-" + std::to_string(::getpid()) + "-" + name);
}

TEST(AbsorptionMap, RoundTripsThroughItsFileExactly) {
    AbsorptionMap map(3, 5, glm::vec3(0.4f, 0.6f, 1.0f));
    map.at(1, 4) = glm::vec3(0.05f, 0.1f, 0.3f);
    map.at(2, 0) = glm::vec3(7.0f, 0.0f, 1234.5f);
    const auto path = temp("rt.exr");
    write_absorption_map(path, map);
    const AbsorptionMap back = read_absorption_map(path, 3);
    std::filesystem::remove(path);
    EXPECT_EQ(back.clusters, 3);
    EXPECT_EQ(back.samples, 5);
    EXPECT_EQ(back.sigma_a, map.sigma_a) << "32-bit float EXR keeps every value";
}

TEST(AbsorptionMap, SampleIsLinearAlongTheCluster) {
    AbsorptionMap map(1, 3, glm::vec3(0.0f));
    map.at(0, 0) = glm::vec3(1.0f);
    map.at(0, 1) = glm::vec3(3.0f);
    map.at(0, 2) = glm::vec3(5.0f);
    EXPECT_FLOAT_EQ(map.sample(0, 0.0).x, 1.0f);
    EXPECT_FLOAT_EQ(map.sample(0, 0.25).x, 2.0f);
    EXPECT_FLOAT_EQ(map.sample(0, 1.0).x, 5.0f);
    EXPECT_FLOAT_EQ(map.sample(0, 7.0).x, 5.0f);
    AbsorptionMap one(1, 1, glm::vec3(2.0f));
    EXPECT_FLOAT_EQ(one.sample(0, 0.5).y, 2.0f);
}

TEST(AbsorptionMap, RefusesWrongRowsIntegerImagesAndBadValues) {
    const auto path = temp("bad.exr");
    write_absorption_map(path, AbsorptionMap(4, 2, glm::vec3(0.5f)));
    EXPECT_THROW(read_absorption_map(path, 5), Error) << "4 rows for a 5-cluster style";
    Image nan(2, 4, 3, 0.5f);
    nan.at(1, 2)[1] = std::nanf("");
    WriteOptions f;
    f.full_float = true;
    write_image(path, nan, f);
    try {
        read_absorption_map(path, 4);
        ADD_FAILURE() << "NaN accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("pixel (1, 2)"), std::string::npos) << e.what();
    }
    Image negative(2, 4, 3, -0.1f);
    write_image(path, negative, f);
    EXPECT_THROW(read_absorption_map(path, 4), Error);
    const auto png = temp("bad.png");
    write_image(png, Image(2, 4, 3, 0.5f));
    EXPECT_THROW(read_absorption_map(png, 4), Error) << "an 8-bit image cannot hold σa";
    EXPECT_THROW(read_absorption_map(temp("missing.exr"), 4), Error);
    std::filesystem::remove(path);
    std::filesystem::remove(png);
}

}  // namespace
}  // namespace coif
