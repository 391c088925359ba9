// The shells under lighting that no one tuned for (issue 16): one narrow SRBF light from 26 directions around
// the default style, `coif render` against `coif reference` of the same style's strands, through the command
// line as a user runs them (docs/quality.md, "The fibres' tangents about the axis"). Slow: 26 × 2 renders,
// about 2 minutes on 2 cores.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "tests/common/run.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using test::run_coif;

// What this checks today is the lighting at the shells' axes: single scattering, no shadows in either renderer,
// and the shells' `debug` 3 (the lighting C₀ · α, without the records' re). That is the part that the fibres'
// measured tilts made right; the full model (re, shadows, multiple scattering) still departs from the reference
// under single lights (45 of 78 channel ratios in the band with full meshes, 54 with the level of detail at this size;
// docs/quality.md, "The shadows from the fibres the camera sees"), and issue 16 stays open for it.
//
// Tolerances. The issue's band is [0.8, 1.25] per channel. Measured: 73 of the 78 channel ratios in it, all in
// 0.82–1.37 (the worst, 1.37, for a light from −x); measured again later, 72 in 0.800–1.352. The test asks for at
// least 70 in the band and every ratio in [0.75, 1.45], so that it fails on a return to the isotropic ring (49 in the
// band, 0.33–2.40) or to widened lobes, and not on the reference's noise: at 64 samples per pixel a mean over the
// ~1 500 hair pixels moves by well under 1 % between seeds.
TEST(LightSweepSlow, LightingAtTheAxesFollowsTheReferenceUnderOneNarrowLightFrom26Directions) {
    const fs::path dir = test::scratch_dir("light-sweep");
    {
        std::ofstream p(dir / "p.json");
        // Full meshes: at 96 × 64 the default level of detail draws every cluster at its coarsest level, whose longer
        // rows interpolate the axis tangents that this test holds over spans 4 times as long (with them, under the light
        // from straight above, the ratios were 0.79 / 0.75 / 0.72, the blue one outside the bound; 71 of 78 in the band).
        p << R"({"multiple": false, "shadows": false, "kappa_shadow": 0, "debug": 3, "lod_pixels": 0})";
    }
    const std::string size = " --width 96 --height 64 --background 0 0 0";
    int in_band = 0, ratios = 0;
    double lo = 1e9, hi = 0;
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) {
                if (x == 0 && y == 0 && z == 0) continue;
                const double n = std::sqrt(double(x * x + y * y + z * z));
                const fs::path lights = dir / "l.json";
                {
                    std::ofstream l(lights);
                    l << nlohmann::json{{"format", "coif-srbf-lights"},
                                        {"version", 1},
                                        {"lights", {{{"L", {300, 300, 300}}, {"omega", {x / n, y / n, z / n}}, {"lambda", 0.1}}}}}
                             .dump();
                }
                const std::string where = "light (" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + ")";
                const auto f = run_coif("reference --lights '" + lights.string() + "' --max-depth 1 --no-shadows --spp 64" + size +
                                        " -o '" + (dir / "f.exr").string() + "'");
                ASSERT_EQ(f.exit_code, 0) << where << ": " << f.err;
                const auto r = run_coif("render --env '" + lights.string() + "' --params '" + (dir / "p.json").string() + "'" + size +
                                        " -o '" + (dir / "r.exr").string() + "'");
                ASSERT_EQ(r.exit_code, 0) << where << ": " << r.err;
                const auto c = run_coif("compare '" + (dir / "f.exr").string() + "' '" + (dir / "r.exr").string() + "' --json");
                ASSERT_EQ(c.exit_code, 0) << where << ": " << c.err;
                const auto ratio = nlohmann::json::parse(c.out)["appearance"]["radiance_ratio"];
                std::printf("%s: %.3f %.3f %.3f\n", where.c_str(), ratio[0].get<double>(), ratio[1].get<double>(),
                            ratio[2].get<double>());
                for (int ch = 0; ch < 3; ++ch) {
                    const double v = ratio[ch].get<double>();
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                    ++ratios;
                    if (v >= 0.8 && v <= 1.25) ++in_band;
                    EXPECT_GE(v, 0.75) << where << ", channel " << ch;
                    EXPECT_LE(v, 1.45) << where << ", channel " << ch;
                }
            }
    std::printf("%d of %d channel ratios in [0.8, 1.25]; range %.3f - %.3f\n", in_band, ratios, lo, hi);
    EXPECT_EQ(ratios, 78);
    EXPECT_GE(in_band, 70);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace coif
