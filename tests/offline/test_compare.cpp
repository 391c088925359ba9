// Image-quality metrics (models/core/image_metrics.h) and `coif compare`.
#include <array>
#include <cmath>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <limits>
#include <random>

#include "models/core/error.h"
#include "models/core/image.h"
#include "models/core/image_metrics.h"
#include "tests/common/run.h"
#include "tests/common/test_data.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A small "hair-like" test picture: thin bright diagonal strokes over a uniform background, with alpha.
Image strokes(int w, int h, unsigned seed, float noise) {
    Image img(w, h, 4);
    std::mt19937 rng(seed);
    std::normal_distribution<float> n(0.0f, noise);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = img.at(x, y);
            const bool hair = ((x + 2 * y) % 9) < 2 && x > 4 && x < w - 4 && y > 4 && y < h - 4;
            const float v = hair ? 0.4f + 0.3f * std::sin(0.2f * x) : 0.05f;
            p[0] = std::max(0.0f, v + (hair ? n(rng) : 0.0f));
            p[1] = std::max(0.0f, 0.6f * v + (hair ? n(rng) : 0.0f));
            p[2] = std::max(0.0f, 0.3f * v + (hair ? n(rng) : 0.0f));
            p[3] = hair ? 1.0f : 0.0f;
        }
    return img;
}

Image uniform(int w, int h, float r, float g, float b) {
    Image img(w, h, 3);
    for (int i = 0; i < w * h; ++i) img.pixels[3 * i] = r, img.pixels[3 * i + 1] = g, img.pixels[3 * i + 2] = b;
    return img;
}

TEST(Compare, LitWeightedRatioWeighsEachCellByTheShareOfTheLightThatReachesIt) {
    // Three 2 × 2 cells side by side (cell 2): the light reaches the first fully (V = 1), the second half (V = 0.5, a
    // reddish shadow: V is of the channels' sum), the third not at all. The test image is 2×, 4× and 100× the
    // unshadowed one there, so the ratio is (1 · 2 + 0.5 · 4) / (1 + 0.5) = 8/3 in every channel, whatever the third.
    Image unshadowed(6, 2, 3, 1.0f), shadowed(6, 2, 3, 0.0f), test(6, 2, 3, 0.0f);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 6; ++x) {
            const int cell = x / 2;
            for (int c = 0; c < 3; ++c) {
                shadowed.at(x, y)[c] = cell == 0 ? 1.0f : cell == 1 ? (c == 0 ? 1.5f : 0.0f) : 0.0f;
                test.at(x, y)[c] = cell == 0 ? 2.0f : cell == 1 ? 4.0f : 100.0f;
            }
        }
    const std::array<double, 3> r = lit_weighted_ratio(unshadowed, shadowed, test, 2, "cells");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r[c], 8.0 / 3.0, 1e-12) << c;
    // One cell of the whole image: V = Σ shadowed / Σ unshadowed = (4 · 3 + 4 · 1.5) / 36 = 0.5, and the ratio is the
    // test's mean over the unshadowed's, (8 + 16 + 400) / 12 per channel.
    const std::array<double, 3> whole = lit_weighted_ratio(unshadowed, shadowed, test, 8, "cells");
    EXPECT_NEAR(whole[1], 424.0 / 12.0, 1e-9);
    // Bad input: a clear error naming the images.
    EXPECT_THROW(lit_weighted_ratio(unshadowed, shadowed, test, 0, "cells"), Error);
    EXPECT_THROW(lit_weighted_ratio(unshadowed, shadowed, Image(4, 2, 3, 1.0f), 2, "cells"), Error);
    Image nan = test;
    nan.at(0, 0)[0] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(lit_weighted_ratio(unshadowed, shadowed, nan, 2, "cells"), Error);
    try {
        lit_weighted_ratio(unshadowed, Image(6, 2, 3, 0.0f), test, 2, "the kept images");
        ADD_FAILURE() << "no cell reached";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("the kept images"));
    }
}

TEST(Compare, IdenticalImagesGiveInfinitePsnrAndZeroFlip) {
    const Image a = strokes(64, 48, 1, 0.05f);
    const CompareResult r = compare_images(a, a, {});
    // Exact: every difference is 0, so MSE = 0, SSIM = 1 up to float rounding of the window sums, and
    // FLIP = ΔE_c^(1-ΔE_f) = 0^1 = 0.
    EXPECT_TRUE(std::isinf(r.linear.psnr_db) && r.linear.psnr_db > 0);
    EXPECT_TRUE(std::isinf(r.tone_mapped.psnr_db));
    EXPECT_EQ(r.linear.flip, 0.0);
    EXPECT_EQ(r.tone_mapped.flip, 0.0);
    EXPECT_NEAR(r.linear.ssim, 1.0, 1e-5);
    EXPECT_NEAR(r.tone_mapped.ssim, 1.0, 1e-5);
    EXPECT_EQ(format_metric(r.linear.psnr_db, 2), "inf");
    EXPECT_THAT(r.mask.rule, HasSubstr("alpha"));
}

TEST(Compare, PsnrMatchesItsDefinition) {
    // A uniform offset d on every masked channel: tone-mapped-free linear PSNR = 10 log10(peak²/d²), exact
    // up to float rounding (1e-4 dB).
    Image a = strokes(32, 32, 2, 0.0f), b = a;
    for (int i = 0; i < 32 * 32; ++i)
        if (a.pixels[4 * i + 3] > 0)
            for (int c = 0; c < 3; ++c) b.pixels[4 * i + c] += 0.01f;
    const CompareResult r = compare_images(a, b, {});
    EXPECT_NEAR(r.linear.psnr_db, 10.0 * std::log10(r.linear_peak * r.linear_peak / 1e-4), 1e-3);
}

TEST(Compare, FlipOfUniformBlackAgainstWhiteMatchesTheHandComputation) {
    // No features in uniform images, so FLIP = ΔE_c: HyAB(black, white) in Hunt-adjusted L*a*b* is
    // |ΔL*| = 100; cmax = HyAB(hunt(green), hunt(blue))^0.7 with CIELAB green (87.736, -86.179, 83.183) and blue
    // (32.298, 79.194, -107.859) (D65, sRGB primaries). ΔE_c = 0.95 + 0.05 (100^0.7 - 0.4 cmax)/(0.6 cmax).
    // The CIELAB values are given to 3 decimals, hence the 1e-4 tolerance.
    const double gl = 87.736, ga = -86.179 * 0.87736, gb = 83.183 * 0.87736;
    const double bl = 32.298, ba = 79.194 * 0.32298, bb = -107.859 * 0.32298;
    const double cmax = std::pow(std::abs(gl - bl) + std::hypot(ga - ba, gb - bb), 0.7);
    const double e = std::pow(100.0, 0.7);
    const double expected = 0.95 + 0.05 * (e - 0.4 * cmax) / (0.6 * cmax);
    const Planes black = tone_mapped_planes(uniform(40, 30, 0, 0, 0), 0), white = tone_mapped_planes(uniform(40, 30, 1, 1, 1), 0);
    const std::vector<float> m = flip_ldr_map(black, white);
    EXPECT_NEAR(m[0], expected, 1e-4);
    EXPECT_NEAR(m[40 * 15 + 20], expected, 1e-4);
    // Pure green against pure blue is FLIP's largest colour difference: exactly 1.
    const auto g = tone_mapped_planes(uniform(40, 30, 0, 1, 0), 0), b = tone_mapped_planes(uniform(40, 30, 0, 0, 1), 0);
    EXPECT_NEAR(flip_ldr_map(g, b)[600], 1.0, 1e-5);
}

TEST(Compare, LdrFlipIsSymmetricAndLocal) {
    // LDR-FLIP has no preferred image: HyAB and the feature difference |‖f_A‖ − ‖f_B‖| are symmetric, so
    // swapping A and B gives the same map (to float rounding, 1e-6). A change confined to one corner leaves
    // pixels beyond the filters' reach (CSF radius 10 px, feature radius 9 px at 67 px/°) exactly at 0.
    Image a = uniform(64, 32, 0.2f, 0.2f, 0.2f), b = a;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) b.at(x, y)[0] = 0.6f;
    const auto ab = flip_ldr_map(tone_mapped_planes(a, 0), tone_mapped_planes(b, 0));
    const auto ba = flip_ldr_map(tone_mapped_planes(b, 0), tone_mapped_planes(a, 0));
    for (size_t i = 0; i < ab.size(); ++i) ASSERT_NEAR(ab[i], ba[i], 1e-6);
    EXPECT_GT(ab[3 * 64 + 3], 0.1f);
    EXPECT_EQ(ab[20 * 64 + 40], 0.0f);
}

TEST(Compare, MoreNoiseScoresWorse) {
    const Image a = strokes(64, 48, 3, 0.0f);
    const CompareResult small = compare_images(a, strokes(64, 48, 4, 0.02f), {});
    const CompareResult large = compare_images(a, strokes(64, 48, 4, 0.1f), {});
    EXPECT_GT(small.linear.psnr_db, large.linear.psnr_db);
    EXPECT_GT(small.tone_mapped.ssim, large.tone_mapped.ssim);
    EXPECT_LT(small.tone_mapped.flip, large.tone_mapped.flip);
    EXPECT_LT(small.linear.flip, large.linear.flip);
}

TEST(Compare, BackgroundMaskFindsTheStrokes) {
    Image a = strokes(48, 48, 5, 0.0f);
    Image rgb(48, 48, 3);
    for (int i = 0; i < 48 * 48; ++i)
        for (int c = 0; c < 3; ++c) rgb.pixels[3 * i + c] = a.pixels[4 * i + c];
    const HairMask by_alpha = image_hair_mask(a, MaskMode::alpha, 0, "a");
    const HairMask by_background = image_hair_mask(rgb, MaskMode::background, 0, "a");
    EXPECT_EQ(by_alpha.inside, by_background.inside);
    EXPECT_GT(by_alpha.count, 100u);
}

TEST(Compare, BadInputIsAClearError) {
    const Image a = strokes(32, 32, 1, 0.0f), b = strokes(32, 16, 1, 0.0f);
    EXPECT_THROW(compare_images(a, b, {}), Error);
    Image nan = a;
    nan.pixels[5] = std::nanf("");
    try {
        compare_images(a, nan, {}, "a.exr", "b.exr");
        FAIL() << "expected coif::Error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("b.exr"));
        EXPECT_THAT(e.what(), HasSubstr("NaN"));
    }
    // Neither image has alpha or a uniform background.
    Image ramp(16, 16, 3);
    for (size_t i = 0; i < ramp.pixels.size(); ++i) ramp.pixels[i] = float(i % 97) / 97.0f;
    EXPECT_THROW(compare_images(ramp, ramp, {}), Error);
    CompareOptions none;
    none.mask = MaskMode::none;
    EXPECT_NO_THROW(compare_images(ramp, ramp, none));
}

// ───────────────────────── appearance metrics ─────────────────────────

Image scaled_hair(const Image& a, float k) {
    Image b = a;
    for (size_t i = 0; i < b.pixels.size(); ++i)
        if (i % 4 != 3) b.pixels[i] *= k;
    return b;
}

TEST(CompareAppearance, RadianceRatioIsTheScaleOfTheHair) {
    // Straight alpha: scaling RGB by k scales the coverage-weighted mean radiance by k exactly (float
    // rounding of the sums: 1e-5); halving every alpha leaves it unchanged (weights cancel) and the masks equal.
    const Image a = strokes(64, 48, 11, 0.05f);
    const CompareResult r = compare_images(a, scaled_hair(a, 1.7f), {});
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.appearance.radiance_ratio[c], 1.7, 1e-5);
    EXPECT_DOUBLE_EQ(r.appearance.mask_iou, 1.0);
    Image thin = a;
    for (size_t i = 3; i < thin.pixels.size(); i += 4) thin.pixels[i] *= 0.5f;
    const CompareResult t = compare_images(a, thin, {});
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t.appearance.radiance_ratio[c], 1.0, 1e-6);
    // Over a uniform background (no alpha): the radiance is the pixel minus the corners' colour, so
    // bg + k (A − bg) has ratio k.
    const float bg[3] = {0.05f, 0.05f, 0.06f};
    Image ra(64, 48, 3), rb(64, 48, 3);
    for (int i = 0; i < 64 * 48; ++i)
        for (int c = 0; c < 3; ++c) {
            const float al = a.pixels[4 * i + 3];
            ra.pixels[3 * i + c] = al * a.pixels[4 * i + c] + (1 - al) * bg[c];
            rb.pixels[3 * i + c] = bg[c] + 0.6f * (ra.pixels[3 * i + c] - bg[c]);
        }
    const CompareResult o = compare_images(ra, rb, {});
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(o.appearance.radiance_ratio[c], 0.6, 1e-4);
    EXPECT_EQ(o.appearance.radiance_warning, "") << "the hair stands well above the background";
    EXPECT_EQ(r.appearance.radiance_warning, "") << "read with alpha";
}

// Dark hair over the default blue-grey background: darker than it in some pixels and brighter in others, so that its
// mean minus the background cancels, and the ratio of two such means says little (0.15 and 1.46 in R and G for two
// renders 8 % apart, measured over the default background). The ratio is still given, with a warning naming the image
// and the channel; hair that stands apart from the background (the test above) gets none.
TEST(CompareAppearance, RadianceOfHairAboutTheBackgroundIsFlagged) {
    const float bg[3] = {0.05f, 0.05f, 0.06f};
    const Image a = strokes(64, 48, 11, 0.0f);
    Image ra(64, 48, 3);
    for (int i = 0; i < 64 * 48; ++i)
        for (int c = 0; c < 3; ++c) {
            const float al = a.pixels[4 * i + 3];
            // In R, hair pixels alternately 0.02 below and 0.021 above the background: their mean is 2 % of their
            // mean distance from it. G and B stand well above it.
            const float hair = c == 0 ? (i % 2 ? 0.03f : 0.071f) : 0.5f;
            ra.pixels[3 * i + c] = al * hair + (1 - al) * bg[c];
        }
    const CompareResult o = compare_images(ra, ra, {});
    EXPECT_THAT(o.appearance.radiance_warning, HasSubstr("A's hair is darker than its background in some pixels"));
    EXPECT_THAT(o.appearance.radiance_warning, HasSubstr("in R its mean"));
    EXPECT_THAT(o.appearance.radiance_warning, HasSubstr("--background 0 0 0"));
    EXPECT_NEAR(o.appearance.radiance_ratio[1], 1.0, 1e-6);
}

TEST(CompareAppearance, MaskIouCountsOverlapOverUnion) {
    // Two 20×10 boxes, B shifted right by 5 px: overlap 15×10, union 25×10, IoU 0.6 exactly.
    Image a(48, 32, 4), b(48, 32, 4);
    for (int y = 10; y < 20; ++y)
        for (int x = 0; x < 20; ++x) {
            float* pa = a.at(5 + x, y);
            float* pb = b.at(10 + x, y);
            for (int c = 0; c < 3; ++c) pa[c] = pb[c] = 0.5f;
            pa[3] = pb[3] = 1.0f;
        }
    const CompareResult r = compare_images(a, b, {});
    EXPECT_EQ(r.appearance.pixels_both, 150u);
    EXPECT_EQ(r.appearance.pixels_either, 250u);
    EXPECT_DOUBLE_EQ(r.appearance.mask_iou, 0.6);
}

TEST(CompareAppearance, DetailRatioPrefersMisalignedFibresToBlurWherePsnrPrefersBlur) {
    // The property the metric exists for. B1 = A's fibres moved by 1 px (the same look, fibres not lined
    // up); B2 = A blurred (a smear). Per-pixel PSNR rates the smear higher; the detail ratio keeps the
    // moved fibres at ~1 (measured 1.00 ± 0.05) and puts the smear far below (< 0.6); the blurred PSNR
    // rates the moved fibres as close as the smear (both > per-pixel PSNR + 3 dB).
    const int w = 96, h = 64;
    const auto fibres = [&](int shift) {
        Image im(w, h, 3);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const bool inside = x >= 8 && x < w - 8 && y >= 8 && y < h - 8;
                const bool fibre = ((x + shift) % 3) == 0;
                for (int c = 0; c < 3; ++c) im.at(x, y)[c] = inside ? (fibre ? 0.6f : 0.15f) * (1.0f - 0.2f * c) : 0.0f;
            }
        return im;
    };
    const Image a = fibres(0), moved = fibres(1);
    Planes blurred = gaussian_blur(linear_planes(a), 1.5);
    Image smear = a;
    for (int i = 0; i < w * h; ++i)
        for (int c = 0; c < 3; ++c) smear.pixels[3 * i + c] = a.pixels[3 * i] > 0 ? blurred.c[c][i] : 0.0f;  // the same silhouette
    CompareOptions o;
    o.mask = MaskMode::background;
    const CompareResult rm = compare_images(a, moved, o), rs = compare_images(a, smear, o);
    EXPECT_GT(rs.tone_mapped.psnr_db, rm.tone_mapped.psnr_db);
    EXPECT_NEAR(rm.appearance.detail_ratio, 1.0, 0.05);
    EXPECT_LT(rs.appearance.detail_ratio, 0.6);
    EXPECT_GT(rm.appearance.blurred_psnr_db, rm.tone_mapped.psnr_db + 3.0);
    // A noisier image has more detail than its reference.
    const Image a2 = strokes(64, 48, 12, 0.0f);
    EXPECT_GT(compare_images(a2, strokes(64, 48, 13, 0.15f), {}).appearance.detail_ratio, 1.1);
}

TEST(CompareAppearance, BadBlurOrNoOverlapIsAClearError) {
    const Image a = strokes(32, 32, 1, 0.0f);
    for (double sigma : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        CompareOptions o;
        o.blur_sigma = sigma;
        try {
            compare_images(a, a, o);
            FAIL() << "expected coif::Error for sigma " << sigma;
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("--blur"));
        }
    }
    Image left(32, 32, 4), right(32, 32, 4);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 8; ++x) left.at(x, y)[3] = right.at(31 - x, y)[3] = 1.0f, left.at(x, y)[0] = right.at(31 - x, y)[0] = 0.5f;
    try {
        compare_images(left, right, {}, "l.exr", "r.exr");
        FAIL() << "expected coif::Error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("no pixel is hair in both"));
        EXPECT_THAT(e.what(), HasSubstr("l.exr"));
    }
}

// The radiance ratio by region: B is twice A's radiance over the left half of the hair's box and half of it over the
// right half, so the one mean is (2 + 0.5) / 2 = 1.25 where no pixel is off by that, and 2 × 2 regions give 2 and 0.5
// (float rounding of the sums: 1e-5). The box is the hair's, and a region with no hair in both images has no ratio.
TEST(CompareAppearance, RadianceRatioByRegionShowsWhatTheOneMeanHides) {
    Image a(48, 32, 4), b(48, 32, 4);
    for (int y = 8; y < 24; ++y)
        for (int x = 8; x < 40; ++x) {
            float* pa = a.at(x, y);
            float* pb = b.at(x, y);
            for (int c = 0; c < 3; ++c) {
                pa[c] = 0.2f + 0.1f * c;
                pb[c] = pa[c] * (x < 24 ? 2.0f : 0.5f);
            }
            pa[3] = pb[3] = 1.0f;
        }
    CompareOptions o;
    o.regions = 2;
    const AppearanceMetrics m = compare_images(a, b, o).appearance;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.radiance_ratio[c], 1.25, 1e-5);
    const RegionRatios& g = m.regions;
    ASSERT_EQ(g.n, 2);
    ASSERT_EQ(g.cells.size(), 4u);
    EXPECT_EQ(g.x0, 8);
    EXPECT_EQ(g.y0, 8);
    EXPECT_EQ(g.x1, 40);
    EXPECT_EQ(g.y1, 24);
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 2; ++col) {
            const RegionRatio& r = g.cells[static_cast<std::size_t>(row * 2 + col)];
            EXPECT_EQ(r.pixels, 128u);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.radiance_ratio[c], col == 0 ? 2.0 : 0.5, 1e-5);
        }
    EXPECT_EQ(compare_images(a, b, {}).appearance.regions.n, 0) << "not asked for";
    // Hair in the top-left corner of the box only: the other regions hold none, and say so.
    Image c = a;
    for (int y = 16; y < 24; ++y)
        for (int x = 8; x < 40; ++x) c.at(x, y)[3] = 0.0f;
    for (int y = 8; y < 16; ++y)
        for (int x = 24; x < 40; ++x) c.at(x, y)[3] = 0.0f;
    o.mask = MaskMode::alpha;
    const RegionRatios corner = compare_images(c, c, o).appearance.regions;
    EXPECT_EQ(corner.x1, 24);
    EXPECT_EQ(corner.y1, 16);
    EXPECT_EQ(corner.cells[0].pixels, 32u);  // the box is 16 × 8: each region is 8 × 4
    EXPECT_NEAR(corner.cells[0].radiance_ratio[0], 1.0, 1e-6);
    for (int r = 0; r < 4; ++r) EXPECT_GT(corner.cells[static_cast<std::size_t>(r)].pixels, 0u) << "the box is the hair's own";
    for (int bad : {-1, kMaxRegions + 1}) {
        CompareOptions w;
        w.regions = bad;
        try {
            compare_images(a, b, w);
            FAIL() << "expected coif::Error for regions " << bad;
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("--regions"));
        }
    }
}

TEST(CompareCli, ThresholdsSetTheExitStatus) {
    const fs::path dir = test::scratch_dir("compare-gates");
    const Image a = strokes(64, 48, 7, 0.05f);
    write_image(dir / "a.exr", a);
    write_image(dir / "dark.exr", scaled_hair(a, 0.5f));
    const std::string ab = "compare '" + (dir / "a.exr").string() + "' '" + (dir / "dark.exr").string() + "' ";
    const test::RunResult pass = test::run_coif(ab + "--min-iou 0.99 --detail-range 0.3 1.2 --radiance-range 0.45 0.55");
    EXPECT_EQ(pass.exit_code, 0) << pass.err;
    EXPECT_THAT(pass.out, HasSubstr("radiance ratio"));
    EXPECT_THAT(pass.out, HasSubstr("pass"));
    const test::RunResult fail = test::run_coif(ab + "--radiance-range 0.8 1.25 --json");
    EXPECT_EQ(fail.exit_code, 1);
    EXPECT_THAT(fail.err, HasSubstr("radiance ratio R"));
    const auto doc = nlohmann::json::parse(fail.out);  // the report is still printed whole
    EXPECT_NEAR(doc["appearance"]["radiance_ratio"][1].get<double>(), 0.5, 1e-5);
    EXPECT_EQ(doc["appearance"]["mask_iou"].get<double>(), 1.0);
    EXPECT_FALSE(doc["gates"][0]["pass"].get<bool>());
    for (const char* key : {"blurred_psnr_db", "blurred_ssim", "detail_ratio", "blur_sigma_px"}) EXPECT_TRUE(doc["appearance"].contains(key)) << key;
    EXPECT_TRUE(doc["appearance"]["regions"].is_null()) << "not asked for";
    const test::RunResult by_region = test::run_coif(ab + "--regions 3 --json");
    ASSERT_EQ(by_region.exit_code, 0) << by_region.err;
    const auto regions = nlohmann::json::parse(by_region.out)["appearance"]["regions"];
    EXPECT_EQ(regions["n"].get<int>(), 3);
    ASSERT_EQ(regions["rows"].size(), 3u);
    ASSERT_EQ(regions["rows"][0].size(), 3u);
    EXPECT_NEAR(regions["rows"][1][1]["radiance_ratio"][0].get<double>(), 0.5, 1e-5);
    EXPECT_THAT(test::run_coif(ab + "--regions 2").out, HasSubstr("radiance ratio by region"));
    // Bad options: exit 1 or 2, a message naming the option, and no heatmap.
    for (const std::string bad :
         {"--blur 0", "--blur -2", "--blur nan", "--detail-range 2 1", "--radiance-range nan 1", "--min-iou nan", "--regions 17"}) {
        const test::RunResult r = test::run_coif(ab + bad + " --heatmap '" + (dir / "h.png").string() + "'");
        EXPECT_TRUE(r.exit_code == 1 || r.exit_code == 2) << bad << ": " << r.exit_code;
        EXPECT_THAT(r.err, HasSubstr(bad.substr(0, bad.find(' ')))) << bad;
        EXPECT_FALSE(fs::exists(dir / "h.png")) << bad;
    }
    fs::remove_all(dir);
}

TEST(CompareCli, SelfComparePrintsInfAndZeroFlip) {
    const fs::path dir = test::scratch_dir("compare-cli");
    write_image(dir / "a.exr", strokes(48, 32, 7, 0.05f));
    const test::RunResult r = test::run_coif("compare '" + (dir / "a.exr").string() + "' '" + (dir / "a.exr").string() +
                                             "' --heatmap '" + (dir / "h.png").string() + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("inf"));
    EXPECT_THAT(r.out, HasSubstr("0.0000"));
    EXPECT_TRUE(fs::exists(dir / "h.png"));
    const test::RunResult j = test::run_coif("compare --json '" + (dir / "a.exr").string() + "' '" + (dir / "a.exr").string() + "'");
    EXPECT_EQ(j.exit_code, 0) << j.err;
    const auto doc = nlohmann::json::parse(j.out);
    EXPECT_EQ(doc["linear"]["psnr_db"], "inf");
    EXPECT_EQ(doc["tone_mapped"]["flip_mean"].get<double>(), 0.0);
    fs::remove_all(dir);
}

TEST(CompareCli, MissingFileOrSizeMismatchExitsOneWithoutOutput) {
    const fs::path dir = test::scratch_dir("compare-bad");
    write_image(dir / "a.exr", strokes(48, 32, 7, 0.0f));
    write_image(dir / "b.exr", strokes(32, 32, 7, 0.0f));
    const test::RunResult missing = test::run_coif("compare '" + (dir / "a.exr").string() + "' '" + (dir / "nope.exr").string() +
                                                   "' --heatmap '" + (dir / "h.png").string() + "'");
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_THAT(missing.err, HasSubstr("nope.exr"));
    const test::RunResult size = test::run_coif("compare '" + (dir / "a.exr").string() + "' '" + (dir / "b.exr").string() +
                                                "' --heatmap '" + (dir / "h.png").string() + "'");
    EXPECT_EQ(size.exit_code, 1);
    EXPECT_THAT(size.err, HasSubstr("sizes differ"));
    EXPECT_FALSE(fs::exists(dir / "h.png"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace coif
