// Image I/O through OpenImageIO and atomic writes.
#include <cmath>
#include <fstream>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/atomic_file.h"
#include "models/core/error.h"
#include "models/core/image.h"
#include "tests/common/test_data.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

Image gradient(int channels) {
    Image img(16, 8, channels);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            float* p = img.at(x, y);
            p[0] = 0.1f * float(x);       // up to 1.5: above 1 on purpose
            p[1] = 0.05f * float(y);
            p[2] = 1e-3f * float(x * y);
            if (channels == 4) p[3] = float(x) / 15.0f;
        }
    return img;
}

size_t files_in(const fs::path& dir) {
    return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(Image, ExrRoundTripIsLinearWithinHalfPrecision) {
    const auto dir = test::scratch_dir("exr");
    const Image img = gradient(4);
    write_image(dir / "a.exr", img);
    ImageInfo info;
    const Image back = read_image(dir / "a.exr", &info);
    EXPECT_TRUE(info.floating_point);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.channels, 4);
    // Half floats keep 11 significant bits: relative error ≤ 2^-11 ≈ 4.9e-4.
    for (size_t i = 0; i < img.pixels.size(); ++i)
        EXPECT_NEAR(back.pixels[i], img.pixels[i], 4.9e-4f * std::abs(img.pixels[i]) + 1e-7f) << i;
    EXPECT_EQ(files_in(dir), 1u);  // no temporary left behind
    fs::remove_all(dir);
}

TEST(Image, PngIsToneMappedSrgbAndDecodesBackToLinear) {
    const auto dir = test::scratch_dir("png");
    const Image img = gradient(3);
    write_image(dir / "a.png", img);
    ImageInfo info;
    const Image back = read_image(dir / "a.png", &info);
    EXPECT_FALSE(info.floating_point);
    EXPECT_EQ(info.bits_per_channel, 8);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float expected = std::min(img.at(x, y)[c], 1.0f);  // the tone map clips at 1
                // 8-bit sRGB: one code step is at most 1/255 in encoded units; in linear that is below 0.013.
                EXPECT_NEAR(back.at(x, y)[c], expected, 0.013f) << x << "," << y << "," << c;
            }
    fs::remove_all(dir);
}

TEST(Image, ToneMapIsExposureClipSrgb) {
    EXPECT_FLOAT_EQ(tone_map_srgb(0.0f, 1.0f), 0.0f);
    EXPECT_FLOAT_EQ(tone_map_srgb(1.0f, 1.0f), 1.0f);
    EXPECT_FLOAT_EQ(tone_map_srgb(5.0f, 1.0f), 1.0f);
    EXPECT_NEAR(tone_map_srgb(0.5f, 1.0f), 0.7353569f, 1e-6f);  // IEC 61966-2-1 at 0.5
    EXPECT_NEAR(tone_map_srgb(0.25f, 2.0f), tone_map_srgb(0.5f, 1.0f), 1e-7f);
    EXPECT_FLOAT_EQ(tone_map_srgb(NAN, 1.0f), 0.0f);
    EXPECT_NEAR(srgb_to_linear(tone_map_srgb(0.2f, 1.0f)), 0.2f, 1e-6f);
}

TEST(Image, FailedWritesLeaveNoFile) {
    const auto dir = test::scratch_dir("failwrite");
    const Image img = gradient(3);
    EXPECT_THROW(write_image(dir / "missing-folder" / "a.png", img), Error);
    EXPECT_THROW(write_image(dir / "a.bmpx", img), Error);
    Image bad = img;
    bad.pixels.resize(3);
    EXPECT_THROW(write_image(dir / "bad.exr", bad), Error);
    EXPECT_EQ(files_in(dir), 0u);
    // A write that throws midway removes its temporary and keeps the old file intact.
    write_file_atomic(dir / "keep.txt", std::string_view("old"));
    EXPECT_THROW(write_atomically(dir / "keep.txt",
                                  [](const fs::path& temp) {
                                      std::ofstream(temp) << "partial";
                                      throw Error(temp, "", "simulated failure");
                                  }),
                 Error);
    EXPECT_EQ(files_in(dir), 1u);
    std::ifstream in(dir / "keep.txt");
    std::string text;
    in >> text;
    EXPECT_EQ(text, "old");
    fs::remove_all(dir);
}

TEST(Image, BadFilesGiveErrorsNamingTheFile) {
    const auto dir = test::scratch_dir("badimage");
    const auto expect = [&](const fs::path& p, const std::string& what) {
        try {
            read_image(p);
            ADD_FAILURE() << "no error for " << p;
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), p);
            EXPECT_THAT(e.what(), HasSubstr(what));
        }
    };
    expect(dir / "missing.exr", "no such file");
    std::ofstream(dir / "empty.png").close();
    expect(dir / "empty.png", "empty file");
    write_image(dir / "ok.png", gradient(3));
    auto bytes = read_file_bytes(dir / "ok.png");
    bytes.resize(bytes.size() / 2);
    write_file_atomic(dir / "truncated.png", bytes);
    EXPECT_THROW(read_image(dir / "truncated.png"), Error);
    std::ofstream(dir / "text.exr") << "this is not an image";
    EXPECT_THROW(read_image(dir / "text.exr"), Error);
    fs::remove_all(dir);
}

TEST(Image, ReadsTheSharedHdrAndExrMaps) {
    COIF_SHARED_DATA(exr, "blender_studiolight_courtyard.exr");
    COIF_SHARED_DATA(hdr, "blender_studiolight_courtyard.hdr");
    ImageInfo info;
    const Image a = read_image(exr, &info);
    EXPECT_TRUE(info.floating_point);
    const Image b = read_image(hdr);
    ASSERT_EQ(a.width, 1024);
    ASSERT_EQ(a.height, 512);
    ASSERT_EQ(b.width, 1024);
    // PROVENANCE.md: EXR mean R = 0.637; the .hdr copy is clamped and RGBE-rounded (means ~0.3 % lower).
    double mean_a = 0, mean_b = 0;
    for (int i = 0; i < a.width * a.height; ++i) {
        mean_a += a.pixels[size_t(i) * a.channels];
        mean_b += b.pixels[size_t(i) * b.channels];
    }
    mean_a /= a.width * a.height;
    mean_b /= b.width * b.height;
    EXPECT_NEAR(mean_a, 0.637, 0.0005);
    EXPECT_NEAR(mean_b / mean_a, 1.0, 0.01);
}

}  // namespace
}  // namespace coif
