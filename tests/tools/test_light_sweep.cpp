// The shells under lighting and views that no one tuned for (issue 16, item 1): `coif render` against `coif reference`
// of the same style's strands, through `coif bench sweep` as a user runs it. One narrow SRBF light from 26 directions
// around the default style (docs/quality.md, "The fibres' tangents about the axis"; 26 × 2 renders, about 2 minutes on
// 2 cores), and the shared maps turned and the ring of views ("The sweeps as tests"; about 4 minutes).
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

// `coif bench sweep ARGS --json` (the sweeps of docs/quality.md, as a user runs them), its cases' channel ratios printed
// and each expected in [low, high]; returns its JSON.
nlohmann::json sweep(const std::string& args, double low, double high) {
    const auto r = run_coif("bench sweep " + args + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    if (r.exit_code != 0) return {};
    const auto j = nlohmann::json::parse(r.out);
    for (const auto& c : j["cases"]) {
        const auto& ratio = c["radiance_ratio"];
        std::printf("%s: %.3f %.3f %.3f\n", c["name"].get<std::string>().c_str(), ratio[0].get<double>(), ratio[1].get<double>(),
                    ratio[2].get<double>());
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_GE(ratio[ch].get<double>(), low) << c["name"] << ", channel " << ch;
            EXPECT_LE(ratio[ch].get<double>(), high) << c["name"] << ", channel " << ch;
        }
    }
    for (const auto& [set, t] : j["sets"].items())
        std::printf("%s: %d of %d channel ratios in [0.8, 1.25]; range %.3f - %.3f\n", set.c_str(), t["in_band"].get<int>(),
                    t["ratios"].get<int>(), t["min_ratio"].get<double>(), t["max_ratio"].get<double>());
    return j;
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
    const auto j = sweep("--set lights --max-depth 1 --no-shadows --params '" + (dir / "p.json").string() + "'", 0.75, 1.45);
    EXPECT_EQ(j["sets"]["lights"]["ratios"], 78);
    EXPECT_GE(j["sets"]["lights"]["in_band"].get<int>(), 70);
    fs::remove_all(dir);
}

// The full model with a key light (ShellSettings::key_lights 1: the light lit per fragment with the fibres met from the
// fragment itself, docs/quality.md "Key lights") against the full reference, under one narrow light from 26 directions,
// and the same sweep without it (the references rendered once, kept in the test's folder for the second run): about 4
// minutes on 2 cores.
//
// What the key light is for is the picture: the reference's shapes (a lit rim, a dark inside) under a strong light, which
// the shadow from the clusters' axes does not draw. Measured: the worst blurred PSNR of the 26 is 22.47 dB with the key
// light and 14.85 dB without (the light from behind, −z); the means 27.48 and 27.37 dB; 46 and 45 of the 78 channel ratios
// in the band, all in 0.78–2.17 with the key light. With its light taken per vertex (since): 22.39 dB, mean 27.51 dB, 48
// of 78 in 0.81–2.22. Over the layer's slab (since, docs/quality.md "A key light's shadow over the layer's slab"):
// 24.09 dB, mean 27.86 dB, 54 of 78 in 0.63–1.99 (the lights from above and behind the darkest). With the records
// thinned, the lights' hot spot and the key light read toward the camera and the light (since, docs/quality.md "The
// records thinned to their sectors' density, and the lights' hot spot"): 24.89 dB against 15.66 dB without the key
// light, 68 of 78 in 0.83–1.62 (62 without). The test asks for a worst of at least 20 dB with the key light and at
// least 5 dB above the worst without, every ratio in [0.5, 2.5], and at least 66 of 78 in the band: it fails if the key
// light's shadow stops drawing the shapes (a shadow from the axes again, a volume read in the wrong frame) or the
// single lights fall back toward the 54–59 of before, and not on the references' noise, which moves a blurred PSNR by
// well under 1 dB at 64 samples per pixel and a ratio by well under 1 %.
TEST(LightSweepSlow, AKeyLightDrawsTheReferencesShapesUnderOneNarrowLightFrom26Directions) {
    const fs::path dir = test::scratch_dir("key-light-sweep");
    {
        std::ofstream p(dir / "key.json");
        p << R"({"lod_pixels": 0, "key_lights": 1})";  // full meshes, as above
        std::ofstream q(dir / "axes.json");
        q << R"({"lod_pixels": 0, "key_lights": 0})";
    }
    const std::string refs = " --references '" + (dir / "refs").string() + "'";
    const auto key = sweep("--set lights --params '" + (dir / "key.json").string() + "'" + refs, 0.5, 2.5);
    const auto axes = sweep("--set lights --params '" + (dir / "axes.json").string() + "'" + refs, 0.5, 2.5);
    ASSERT_EQ(key["sets"]["lights"]["ratios"], 78);
    const double worst = key["sets"]["lights"]["blurred_psnr_db_worst"].get<double>();
    const double worst_axes = axes["sets"]["lights"]["blurred_psnr_db_worst"].get<double>();
    std::printf("worst blurred PSNR: %.2f dB with the key light, %.2f dB without\n", worst, worst_axes);
    EXPECT_GE(worst, 20.0);
    EXPECT_GE(worst, worst_axes + 5.0);
    EXPECT_GE(key["sets"]["lights"]["in_band"].get<int>(), 66);
    fs::remove_all(dir);
}

// The full model (the renderer's defaults: re, shadows between clusters, the own cluster's shadow, multiple scattering,
// one key light)
// against the full reference, under the lights of every map in ../shared/data (40 SRBF lights each, `coif env fit`),
// each turned about +y by 0°, 90°, 180° and 270° (`--rotate-lights` on both renderers), and from a ring of views
// (azimuth every 45° at elevations −20°, 10° and 40°) under the courtyard's lights: issue 16's sweeps 2 to 4. About
// 4 minutes on 2 cores.
//
// Tolerances. The issue's band is [0.8, 1.25] per channel. Measured (docs/quality.md, "The sweeps as tests"): 46 of the
// 48 channel ratios of the maps in it, all in 0.87–1.46 (out: the courtyard turned 270°, 1.46 / 1.33 in red and green,
// its sun from −x, where the single light is 1.51–1.63 too); 71 of the 72 of the ring, in 0.80–1.27 (out: azimuth 270°,
// elevation −20°, blue 1.27). With one key light, the default since: 47 of 48 in 0.889–1.284 (the courtyard turned 270°,
// red 1.28) and 71 of 72 in 0.818–1.261. With its shadow over the layer's slab (since): 47 of 48 in 0.84–1.26 and 69 of
// 72 in 0.79–1.25 (out: azimuth 315°, elevation 40°, 0.79 in red and green; 270°, −20°, blue 1.2505; azimuth 0°,
// elevation 40° is in at 0.805). With the shadows from the cluster's outer side and its side toward the hair's inside
// (since; docs/quality.md, "The cluster's side toward the hair's inside"): 48 of 48 in 0.84–1.19 and 72 of 72 in
// 0.85–1.22 (46 and 71 with `own_cluster_inner` 0: the courtyard turned 90° and 270° at 1.31 and 1.28 in red, the view
// from 270° below at 1.27 in blue). With the records thinned and the lights' hot spot (since): 48 of 48 in 0.87–1.23
// and 71 of 72 in 0.86–1.26 (270° below, blue 1.26), the mean |ln ratio| 0.061 and 0.066 (docs/quality.md, "The
// records thinned to their sectors' density, and the lights' hot spot"). Ratios lie within
// 0.03–0.04 of the band's edges, so the test asks for 47 of 48 and 71
// of 72, and every ratio in [0.7, 1.6]: it fails on a return to the maps' 2–6× of the issue, or on two ratios leaving
// the band, and not on one ratio at the edge moving by the references' noise (well under 1 % of a mean over ~1 500 hair
// pixels at 64 samples per pixel). Issue 16 stays open until the single lights are in the band too.
TEST(LightSweepSlow, TheFullModelFollowsTheReferenceUnderEveryMapTurnedAndFromARingOfViews) {
    for (const char* name : {"courtyard", "city", "night", "studio"}) {
        COIF_SHARED_DATA(map, std::string("blender_studiolight_") + name + ".exr");
    }
    const fs::path dir = test::scratch_dir("map-sweep");
    {
        std::ofstream p(dir / "p.json");
        p << R"({"lod_pixels": 0})";  // full meshes, as the single-light sweep above says why
    }
    const auto j = sweep("--set maps --set ring --data '" + test::shared_data_dir().string() + "' --params '" +
                             (dir / "p.json").string() + "'",
                         0.7, 1.6);
    EXPECT_EQ(j["sets"]["maps"]["ratios"], 48);
    EXPECT_EQ(j["sets"]["ring"]["ratios"], 72);
    EXPECT_GE(j["sets"]["maps"]["in_band"].get<int>(), 47);
    EXPECT_GE(j["sets"]["ring"]["in_band"].get<int>(), 71);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace coif
