// The records per sector and their smoothing, chosen by fibre detail (issue 16, item 4; docs/quality.md "Fibre
// detail"): the default render (records traced without smoothing, the nearest one per sector) against `coif
// reference` of the same style's strands, beside what it replaced (records smoothed at the paper's 1.5 λ, the 2 nearest
// blended), through the command line as a user runs them. Slow: a 1024-spp reference and a database build, about a
// minute on 2 cores.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <string>

#include "tests/common/run.h"
#include "tests/common/test_data.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using test::run_coif;

// Tolerances. Measured at 180 × 120 under the embedded courtyard lights: the default's detail ratio 0.809 and
// blurred PSNR 24.45 dB; the smoothed blend's 0.721 and 24.38 dB (at 360 × 240 0.578 against 0.433, 22.45 against
// 22.38 dB). The reference's own noise at 1024 spp moves the detail ratio by about 1 % between seeds. The test asks
// for 8 % more detail than the smoothed blend (measured 12 %) at no more than 0.3 dB less blurred PSNR (measured 0.07
// dB more), so it fails on a return to smoothed records or to blending. With one tangent and one sector's records per
// strip (docs/quality.md) the default's detail ratio here was 0.996 at 25.83 dB, the smoothed blend's 0.850 at 25.67 dB;
// with the own cluster's forward-scattered light and the neighbours in its ellipse (a darker, less contrasted hair),
// 0.941 at 25.41 dB and 0.802 at 25.29 dB; with each strip's tangent lit where its records take the light, 0.961 at
// 25.37 dB and 0.815 at 25.27 dB. The test asks the default for at least 0.9 at this size (0.807 at 360 × 240, against
// the issue's goal 0.8: docs/quality.md, "Each strip's tangent where the records take the light").
TEST(FibreDetailSlow, TheDefaultRecordsKeepMoreFibreDetailThanTheSmoothedBlendAtTheSameBlurredPsnr) {
    const fs::path dir = test::scratch_dir("fibre-detail");
    const std::string size = " --width 180 --height 120 --background 0 0 0";
    const std::string lights = (test::source_dir() / "tools/assets/default_lights.json").string();
    const auto f = run_coif("reference --lights '" + lights + "' --spp 1024" + size + " -o '" + (dir / "f.exr").string() + "'");
    ASSERT_EQ(f.exit_code, 0) << f.err;
    const auto db = run_coif("db build --sectors 1000 --smoothing 1.5 --save-index -o '" + (dir / "smoothed.db").string() + "'");
    ASSERT_EQ(db.exit_code, 0) << db.err;
    std::ofstream(dir / "blend.json") << R"({"neighbours": 2})";
    struct Look {
        double detail, blurred_psnr;
    };
    const auto look = [&](const std::string& options, const char* name) {
        const fs::path out = dir / (std::string(name) + ".exr");
        const auto r = run_coif("render" + options + size + " -o '" + out.string() + "'");
        EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
        const auto c = run_coif("compare '" + (dir / "f.exr").string() + "' '" + out.string() + "' --json");
        EXPECT_EQ(c.exit_code, 0) << name << ": " << c.err;
        const auto a = nlohmann::json::parse(c.out)["appearance"];
        const Look l{a["detail_ratio"].get<double>(), a["blurred_psnr_db"].get<double>()};
        std::printf("%s: detail ratio %.3f, blurred PSNR %.2f dB\n", name, l.detail, l.blurred_psnr);
        return l;
    };
    const Look now = look("", "default");
    const Look before = look(" --db '" + (dir / "smoothed.db").string() + "' --params '" + (dir / "blend.json").string() + "'",
                             "smoothed records, 2 blended");
    EXPECT_GE(now.detail, 1.08 * before.detail);
    EXPECT_GE(now.blurred_psnr, before.blurred_psnr - 0.3);
    EXPECT_GE(now.detail, 0.9);
    // Each strip of a sector lit at one fibre tangent (docs/quality.md "One tangent per strip"), against every fibre at the
    // four tangents' mean: at 360 × 240 13–19 % more detail at −0.02 to +0.08 dB. Asked: 6 % more, within 0.3 dB.
    std::ofstream(dir / "mean.json") << R"({"tilt_per_strip": false})";
    const Look mean = look(" --params '" + (dir / "mean.json").string() + "'", "every fibre at the mean of the tangents");
    EXPECT_GE(now.detail, 1.06 * mean.detail);
    EXPECT_GE(now.blurred_psnr, mean.blurred_psnr - 0.3);
    // Each strip with one sector's records (docs/quality.md "One sector's records per strip"), against both sectors'
    // mixed by γ: at 360 × 240 19–23 % more detail and 0.04–0.23 dB more. Asked: 10 % more, within 0.3 dB.
    std::ofstream(dir / "mix.json") << R"({"sector_per_strip": false})";
    const Look mix = look(" --params '" + (dir / "mix.json").string() + "'", "the records of both sectors mixed by gamma");
    EXPECT_GE(now.detail, 1.10 * mix.detail);
    EXPECT_GE(now.blurred_psnr, mix.blurred_psnr - 0.3);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace coif
