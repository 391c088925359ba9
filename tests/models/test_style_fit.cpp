// Fitting cluster hairstyles to strands (models/style_fit.h): a synthetic cluster with a known
// envelope, the real Bangs model (fast), and harolongo at N = 128 (label slow).
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>

#include "models/core/error.h"
#include "models/style_fit.h"
#include "models/style_strands.h"
#include "tests/common/run.h"

namespace coif {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(StyleFit, RecoversAKnownEllipticCluster) {
    // 3000 straight strands hanging along −y, filling an ellipse of half-axes 2 and 1 turned by 30°.
    Strands s;
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> U(0, 1);
    const double A = 2.0, B = 1.0, th = kPi / 6;
    for (int i = 0; i < 3000; ++i) {
        const double v = std::sqrt(U(rng)), u = 2 * kPi * U(rng);
        const double x = A * v * std::cos(u), z = B * v * std::sin(u);
        const glm::dvec3 off(std::cos(th) * x - std::sin(th) * z, 0, std::sin(th) * x + std::cos(th) * z);
        std::vector<glm::vec3> pts;
        for (int k = 0; k <= 10; ++k) pts.emplace_back(off + glm::dvec3(0, -k, 0));
        s.add_strand(pts);
    }
    FitOptions o;
    o.clusters = 1;
    o.coverage = 1.0;
    o.progress = false;
    o.layout.gaussian_width = 0.05;
    FitReport rep;
    const HairStyle style = fit_style(s, o, &rep);
    ASSERT_EQ(style.clusters.size(), 1u);
    const GeneralizedCylinder& c = *style.clusters[0].shape;
    // 3000 samples of the disc: second moments known to ~2 % (1/√(2n) per axis), the enclosing
    // scale from the extreme sample; 5 % on the axes, 3° on the orientation.
    EXPECT_NEAR(std::max(c.a(0.5), c.b(0.5)), A, 0.05 * A);
    EXPECT_NEAR(std::min(c.a(0.5), c.b(0.5)), B, 0.05 * B);
    EXPECT_NEAR(c.length(), 10.0, 1e-3);
    const auto axes = c.ellipse_axes(0.5);
    const glm::dvec3 major = c.a(0.5) > c.b(0.5) ? axes[0] : axes[1];
    EXPECT_GT(std::abs(glm::dot(major, glm::dvec3(std::cos(th), 0, std::sin(th)))), std::cos(3 * kPi / 180));
    std::printf("synthetic: inside %.4f, RMS outside %.3g\n", rep.error.inside_fraction(), rep.error.rms_outside);
    EXPECT_GT(rep.error.inside_fraction(), 0.97);
    EXPECT_LT(rep.error.rms_outside, 0.05);  // what lies outside, lies just outside
    EXPECT_EQ(rep.error.assigned_share(), 1.0);
}

TEST(StyleFit, BangsHangsDownAndFits) {
    COIF_SHARED_DATA(path, "Bangs_100.hair");
    const Strands s = read_strands(path);
    FitOptions o;
    o.clusters = 32;
    o.progress = false;
    o.layout.gaussian_width = 0;
    FitReport rep;
    const HairStyle style = fit_style(s, o, &rep);
    EXPECT_EQ(style.clusters.size(), 32u);
    // The file hangs along −x; the style hangs along −y (PROVENANCE.md).
    EXPECT_LT(glm::length(rep.rotation * glm::dvec3(-1, 0, 0) - glm::dvec3(0, -1, 0)), 1e-6);
    double down = 0;
    for (const Cluster& c : style.clusters) down += glm::dot(c.placement.apply(c.shape->position(1)) - c.placement.apply(c.shape->position(0)), glm::dvec3(0, -1, 0)) > 0;
    EXPECT_GE(down, 31);
    std::printf("Bangs N=32: inside %.4f, RMS outside %.3g, assigned %.3f\n", rep.error.inside_fraction(), rep.error.rms_outside,
                rep.error.assigned_share());
    // Measured 0.84 for N = 32 (see the issue report); 0.8 leaves room for seed changes. A member
    // whose strand crosses none of its cluster's planes near the axis is not assigned (≤ 2 %).
    EXPECT_GT(rep.error.inside_fraction(), 0.8);
    EXPECT_GE(rep.error.assigned_share(), 0.98);
    // The style survives a JSON round trip, and most members come back (measured 89 of 100: a strand
    // shorter than one HSV crosses a single sector plane, which makes no strand; 80 is the bound).
    const HairStyle again = parse_style(style_text(style), "bangs.json");
    StrandSampling so;
    so.from = StrandSampling::From::Members;
    EXPECT_GE(sample_strands(again, so).strand_count(), 80u);
}

TEST(StyleFit, HarolongoFitKeepsItsSilhouetteWithoutStrays) {
    // Issue 16's fit figures, through `style import --check --json` (harolongo, 64 clusters):
    //  - strays: no envelope sample farther than 5 cluster radii from its own strands (measured 4.1; 9.1 before
    //    the representative curve stopped at the members' 90th-percentile length), median cluster ≤ 1.5 (1.09);
    //  - the fitted strands path-traced against the file's: blurred PSNR ≥ 26 dB (the goal; measured
    //    27.8) and mask IoU ≥ 0.93 (measured 0.942; the goal 0.95 is not reached yet).
    COIF_SHARED_DATA(path, "harolongo.data");
    const auto dir = test::scratch_dir("style-stray");
    const test::RunResult r =
        test::run_coif("style import '" + path.string() + "' --clusters 64 --check --json -o '" + (dir / "h.json").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_LE(doc["stray"]["worst_cluster_radii"].get<double>(), 5.0) << doc["stray"].dump();
    EXPECT_LE(doc["stray"]["median_cluster_radii"].get<double>(), 1.5) << doc["stray"].dump();
    EXPECT_GE(doc["check"]["blurred_psnr_db"].get<double>(), 26.0) << doc["check"].dump();
    EXPECT_GE(doc["check"]["mask_iou"].get<double>(), 0.93) << doc["check"].dump();
    std::filesystem::remove_all(dir);
}

TEST(StyleFit, ImportCommandPrintsTheFittingError) {
    COIF_SHARED_DATA(path, "Bangs_100.data");
    const auto dir = test::scratch_dir("style-import");
    const test::RunResult r = test::run_coif("style import '" + path.string() + "' --clusters 8 -o '" + (dir / "b.json").string() + "' --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["counts"]["clusters"], 8);
    EXPECT_GT(doc["fitting_error"]["inside_fraction"].get<double>(), 0.5);
    const test::RunResult i = test::run_coif("style inspect '" + (dir / "b.json").string() + "' --json");
    ASSERT_EQ(i.exit_code, 0) << i.err;
    EXPECT_EQ(nlohmann::json::parse(i.out)["counts"]["hsvs"], 8 * 8 * 4 * 8);
    const test::RunResult e = test::run_coif("style export-strands '" + (dir / "b.json").string() + "' -o '" + (dir / "b.hair").string() + "'");
    ASSERT_EQ(e.exit_code, 0) << e.err;
    EXPECT_GT(read_strands(dir / "b.hair").strand_count(), 50u);
    std::filesystem::remove_all(dir);
}

TEST(StyleFit, GaussianWidthIsCheckedAgainstTheModel) {
    // Two straight strands 1 apart, 10 long: bounding-box diagonal √101.
    Strands s;
    for (int i = 0; i < 2; ++i) s.add_strand({glm::vec3(float(i), 0, 0), glm::vec3(float(i), -10, 0)});
    const double extent = std::sqrt(101.0);
    EXPECT_NO_THROW(check_gaussian_width(0.5, s, "w"));
    EXPECT_NO_THROW(check_gaussian_width(extent, s, "w"));
    for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL, 1e-300, 1.01 * extent})
        EXPECT_THROW(check_gaussian_width(bad, s, "w"), Error) << bad;
    FitOptions o;
    o.clusters = 1;
    o.progress = false;
    o.layout.gaussian_width = -1;  // only 0 means automatic
    EXPECT_THROW(fit_style(s, o), Error);
    o.layout.gaussian_width = 0;
    EXPECT_DOUBLE_EQ(fit_style(s, o).layout.gaussian_width, 1.0);  // the root spacing
}

TEST(StyleFit, ImportHonoursGaussianWidth) {
    COIF_SHARED_DATA(path, "Bangs_100.hair");
    const auto dir = test::scratch_dir("style-import-lambda");
    const auto out = dir / "b.json";
    const test::RunResult r = test::run_coif("style import '" + path.string() + "' --clusters 8 --gaussian-width 2.5 -o '" + out.string() + "' --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["gaussian_width"].get<double>(), 2.5);
    const HairStyle style = read_style(out);
    EXPECT_EQ(style.layout.gaussian_width, 2.5);
    // λ also floors the half-axes: a B-spline of values ≥ 2.5 stays ≥ 2.5 (convex hull), up to rounding
    // in the JSON (kDigits significant digits; 1e-6 relative).
    for (const Cluster& c : style.clusters)
        if (!c.instance_of)
            for (int q = 0; q <= 16; ++q) {
                EXPECT_GE(c.shape->a(q / 16.0), 2.5 * (1 - 1e-6));
                EXPECT_GE(c.shape->b(q / 16.0), 2.5 * (1 - 1e-6));
            }
    // Without the option: the automatic width, the median root spacing (24.36 CT units for this file).
    const test::RunResult a = test::run_coif("style import '" + path.string() + "' --clusters 8 -o '" + out.string() + "' --json");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_NEAR(nlohmann::json::parse(a.out)["gaussian_width"].get<double>(), 24.36, 0.01);
    std::filesystem::remove_all(dir);
}

TEST(StyleFit, ImportRefusesBadGaussianWidths) {
    COIF_SHARED_DATA(path, "Bangs_100.hair");
    const auto dir = test::scratch_dir("style-import-bad-lambda");
    const auto out = dir / "b.json";
    // 0 is no longer "automatic" on the command line (leave the option out); 1e6 exceeds the model's
    // 366-unit bounding-box diagonal, 1e-300 is below a millionth of it.
    for (const char* bad : {"0", "-1", "nan", "inf", "1e-300", "1e6"}) {
        const test::RunResult r = test::run_coif("style import '" + path.string() + "' --clusters 8 --gaussian-width " + bad + " -o '" + out.string() + "'");
        EXPECT_EQ(r.exit_code, 1) << bad;
        EXPECT_NE(r.err.find("--gaussian-width"), std::string::npos) << bad << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << bad;
    }
    const test::RunResult r = test::run_coif("style import '" + path.string() + "' --gaussian-width wide -o '" + out.string() + "'");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_TRUE(std::filesystem::is_empty(dir));
    std::filesystem::remove_all(dir);
}

TEST(StyleFit, SlowHarolongo128) {
    COIF_SHARED_DATA(path, "harolongo.data");
    const Strands s = read_strands(path);
    FitOptions o;
    o.clusters = 128;
    o.progress = false;
    o.layout.gaussian_width = 0;
    FitReport rep;
    const HairStyle style = fit_style(s, o, &rep);
    std::printf("harolongo N=128: inside %.4f, RMS outside %.3g, assigned %.3f\n", rep.error.inside_fraction(),
                rep.error.rms_outside, rep.error.assigned_share());
    EXPECT_EQ(rep.rotation, glm::dmat3(1.0));  // already y-up
    EXPECT_GT(rep.error.inside_fraction(), 0.85);  // measured 0.92
    EXPECT_EQ(rep.error.assigned_share(), 1.0);
    EXPECT_LT(rep.error.rms_outside, 1.0);  // cm; measured 0.35
}

}  // namespace
}  // namespace coif
