// The shells under lighting and views that no one tuned for (issue 16, item 1): `coif render` against `coif reference`
// of the same style's strands, through the command line as a user runs them. One narrow SRBF light from 26 directions
// around the default style (docs/quality.md, "The fibres' tangents about the axis"; 26 × 2 renders, about 2 minutes on
// 2 cores), and the shared maps turned and the ring of views ("The sweeps as tests"; about 4 minutes).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "tests/common/run.h"
#include "tests/common/test_data.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using test::run_coif;

// One sweep's channel ratios, against the issue's band [0.8, 1.25] per channel.
struct Tally {
    int in_band = 0, ratios = 0;
    double lo = 1e9, hi = 0;
    void print(const char* what) const {
        std::printf("%s: %d of %d channel ratios in [0.8, 1.25]; range %.3f - %.3f\n", what, in_band, ratios, lo, hi);
    }
};

// One case of a sweep: `coif reference REFERENCE` against `coif render RENDER` (each at 96 × 64 over black, into `dir`),
// compared by `coif compare --json`. Each channel's radiance ratio is printed, tallied, and expected in [low, high].
void sweep_case(const fs::path& dir, const std::string& reference, const std::string& render, const std::string& where,
                double low, double high, Tally& t) {
    const std::string size = " --width 96 --height 64 --background 0 0 0";
    const auto f = run_coif("reference " + reference + size + " -o '" + (dir / "f.exr").string() + "'");
    ASSERT_EQ(f.exit_code, 0) << where << ": " << f.err;
    const auto r = run_coif("render " + render + size + " -o '" + (dir / "r.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << where << ": " << r.err;
    const auto c = run_coif("compare '" + (dir / "f.exr").string() + "' '" + (dir / "r.exr").string() + "' --json");
    ASSERT_EQ(c.exit_code, 0) << where << ": " << c.err;
    const auto ratio = nlohmann::json::parse(c.out)["appearance"]["radiance_ratio"];
    std::printf("%s: %.3f %.3f %.3f\n", where.c_str(), ratio[0].get<double>(), ratio[1].get<double>(), ratio[2].get<double>());
    for (int ch = 0; ch < 3; ++ch) {
        const double v = ratio[ch].get<double>();
        t.lo = std::min(t.lo, v);
        t.hi = std::max(t.hi, v);
        ++t.ratios;
        if (v >= 0.8 && v <= 1.25) ++t.in_band;
        EXPECT_GE(v, low) << where << ", channel " << ch;
        EXPECT_LE(v, high) << where << ", channel " << ch;
    }
}

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
    Tally t;
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
                sweep_case(dir, "--lights '" + lights.string() + "' --max-depth 1 --no-shadows --spp 64",
                           "--env '" + lights.string() + "' --params '" + (dir / "p.json").string() + "'", where, 0.75, 1.45,
                           t);
            }
    t.print("single lights");
    EXPECT_EQ(t.ratios, 78);
    EXPECT_GE(t.in_band, 70);
    fs::remove_all(dir);
}

// The full model (the renderer's defaults: re, shadows between clusters, the own cluster's shadow, multiple scattering)
// against the full reference, under the lights of every map in ../shared/data (40 SRBF lights each, `coif env fit`),
// each turned about +y by 0°, 90°, 180° and 270° (`--rotate-lights` on both renderers), and from a ring of views
// (azimuth every 45° at elevations −20°, 10° and 40°) under the courtyard's lights: issue 16's sweeps 2 to 4. About
// 4 minutes on 2 cores.
//
// Tolerances. The issue's band is [0.8, 1.25] per channel. Measured (docs/quality.md, "The sweeps as tests"): 46 of the
// 48 channel ratios of the maps in it, all in 0.87–1.46 (out: the courtyard turned 270°, 1.46 / 1.33 in red and green,
// its sun from −x, where the single light is 1.51–1.63 too); 71 of the 72 of the ring, in 0.80–1.27 (out: azimuth 270°,
// elevation −20°, blue 1.27). Five ratios lie within 0.05 of the band's edges, so the test asks for 45 of 48 and 68 of 72,
// and every ratio in [0.7, 1.6]: it fails on a return to the maps' 2–6× of the issue, and not on one ratio at the edge
// moving by the references' noise (well under 1 % of a mean over ~1 500 hair pixels at 64 samples per pixel). Issue 16
// stays open until every ratio is in the band.
TEST(LightSweepSlow, TheFullModelFollowsTheReferenceUnderEveryMapTurnedAndFromARingOfViews) {
    const char* names[] = {"courtyard", "city", "night", "studio"};
    std::vector<fs::path> maps;
    for (const char* name : names) {
        COIF_SHARED_DATA(map, std::string("blender_studiolight_") + name + ".exr");
        maps.push_back(map);
    }
    const fs::path dir = test::scratch_dir("map-sweep");
    {
        std::ofstream p(dir / "p.json");
        p << R"({"lod_pixels": 0})";  // full meshes, as the single-light sweep above says why
    }
    // One case: the same lights (and `how`: a rotation or a view) given to both renderers.
    const auto check = [&](const fs::path& lights, const std::string& how, const std::string& where, Tally& t) {
        sweep_case(dir, "--lights '" + lights.string() + "'" + how + " --spp 64",
                   "--env '" + lights.string() + "'" + how + " --params '" + (dir / "p.json").string() + "'", where, 0.7, 1.6, t);
    };
    Tally turned, ring;
    for (size_t m = 0; m < maps.size(); ++m) {
        const fs::path lights = dir / (std::string(names[m]) + ".json");
        const auto fit = run_coif("env fit '" + maps[m].string() + "' -n 40 -o '" + lights.string() + "'");
        ASSERT_EQ(fit.exit_code, 0) << names[m] << ": " << fit.err;
        for (int turn = 0; turn < 360; turn += 90)
            check(lights, " --rotate-lights " + std::to_string(turn),
                  std::string(names[m]) + " turned " + std::to_string(turn) + "°", turned);
    }
    for (int azimuth = 0; azimuth < 360; azimuth += 45)
        for (int elevation : {-20, 10, 40})
            check(dir / "courtyard.json", " --azimuth " + std::to_string(azimuth) + " --elevation " + std::to_string(elevation),
                  "view (" + std::to_string(azimuth) + "°, " + std::to_string(elevation) + "°)", ring);
    turned.print("maps turned");
    ring.print("ring of views");
    EXPECT_EQ(turned.ratios, 48);
    EXPECT_EQ(ring.ratios, 72);
    EXPECT_GE(turned.in_band, 45);
    EXPECT_GE(ring.in_band, 68);
}

}  // namespace
}  // namespace coif
