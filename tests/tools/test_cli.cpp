// The coif command as users meet it: help, exit codes, errors on stderr, no partial output files.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <numeric>
#include <set>

#include "models/absorption_map.h"
#include "models/core/atomic_file.h"
#include "models/core/camera.h"
#include "models/core/image.h"
#include "models/core/image_metrics.h"
#include "tests/common/run.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using test::run_coif;

TEST(Cli, HelpListsEveryNounAndExitsZero) {
    const auto r = run_coif("--help");
    EXPECT_EQ(r.exit_code, 0);
    for (const char* noun : {"hair", "render", "view", "bench"}) EXPECT_THAT(r.out, HasSubstr(noun));
    EXPECT_THAT(r.out, HasSubstr("Exit status"));
}

// Every leaf subcommand's help has a description and an example.
TEST(Cli, EverySubcommandHelpTeaches) {
    for (const char* cmd : {"hair inspect", "hair convert", "render", "bake", "view", "bench gl", "bench load", "bench edit", "bench shadows"}) {
        const auto r = run_coif(std::string(cmd) + " --help");
        EXPECT_EQ(r.exit_code, 0) << cmd;
        EXPECT_THAT(r.out, HasSubstr("Examples:")) << cmd;
        EXPECT_THAT(r.out, HasSubstr("OPTIONS")) << cmd;
    }
}

TEST(Cli, VersionPrintsTheGlRenderer) {
    const auto r = run_coif("--version");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_THAT(r.out, HasSubstr("coif "));
    EXPECT_THAT(r.out, HasSubstr("GL_RENDERER: "));
}

TEST(Cli, BadUsageExitsTwo) {
    EXPECT_EQ(run_coif("").exit_code, 2);
    EXPECT_EQ(run_coif("no-such-command").exit_code, 2);
    EXPECT_EQ(run_coif("hair inspect").exit_code, 2);
    EXPECT_EQ(run_coif("render --width 0").exit_code, 2);
    EXPECT_EQ(run_coif("render --width 100000 --height 100000").exit_code, 2);
}

TEST(Cli, HairInspectMatchesProvenanceAsJson) {
    COIF_SHARED_DATA(path, "harolongo.data");
    const auto r = run_coif("hair inspect --json '" + path.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["strands"], 7905);
    EXPECT_EQ(j["points"], 166005);
    EXPECT_NEAR(j["strand_length"]["mean"].get<double>(), 23.5, 0.05);  // PROVENANCE.md, 1 decimal
    EXPECT_THAT(j["axis_convention"].get<std::string>(), HasSubstr("-y"));
}

TEST(Cli, HairInspectMatchesProvenanceForTheGameAssets) {
    // The four game and tool files of PROVENANCE.md in one call. Its figures are metres to 3 decimals for the TressFX
    // files (coif reports centimetres: one unit of the last digit is 0.1 cm) and 2 for the PLY's box.
    COIF_SHARED_DATA(tfx, "Ratboy_mohawk.tfx");
    COIF_SHARED_DATA(bone, "Ratboy_mohawk.tfxbone");
    COIF_SHARED_DATA(mesh, "Ratboy_body.tfxmesh");
    COIF_SHARED_DATA(ply, "Curly_100.ply");
    const auto r = run_coif("hair inspect --json '" + tfx.string() + "' '" + bone.string() + "' '" + mesh.string() + "' '" + ply.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j.size(), 4u);
    EXPECT_EQ(j[0]["strands"], 2228);
    EXPECT_EQ(j[0]["points"], 71296);
    EXPECT_NEAR(j[0]["bbox"]["max"][1].get<double>(), 111.0, 0.1);
    EXPECT_NEAR(j[0]["strand_length"]["max"].get<double>(), 29.5, 0.05);
    EXPECT_EQ(j[1]["bones"], 105);
    EXPECT_EQ(j[1]["strands"], 2228);
    EXPECT_EQ(j[1]["weights_renormalised"], 72);  // the issue: 72 strands sum below 0.99, down to 0.92
    EXPECT_NEAR(j[1]["min_weight_sum"].get<double>(), 0.92, 0.005);
    EXPECT_EQ(j[1]["main_bones"][0]["bone"], "frenchHornMonster_head_JNT");
    EXPECT_EQ(j[2]["bones"], 86);
    EXPECT_EQ(j[2]["vertices"], 12909);
    EXPECT_EQ(j[2]["triangles"], 25814);
    const double lo[3] = {-24.8, 0.01, -10.8}, hi[3] = {24.8, 91.3, 34.4};
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(j[2]["bbox"]["min"][k].get<double>(), lo[k], 0.1) << k;
        EXPECT_NEAR(j[2]["bbox"]["max"][k].get<double>(), hi[k], 0.1) << k;
    }
    EXPECT_EQ(j[3]["strands"], 100);
    EXPECT_EQ(j[3]["points"], 2528);
    EXPECT_NEAR(j[3]["bbox"]["max"][2].get<double>(), 253.26, 0.01);
    EXPECT_NEAR(j[3]["chord_over_length_mean"].get<double>(), 0.74, 0.005);
}

TEST(Cli, AnimateRefusesBadInputAndWritesNothing) {
    const auto dir = test::scratch_dir("cli-animate-bad");
    const auto spec = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    };
    const std::string good = spec("good.json", R"({"frames": 2, "bones": ["head"], "keys": [{"frame": 0, "rotate_deg": [0, 10, 0]}]})");
    const std::string out = (dir / "turn.png").string();
    const struct {
        std::string args, what;
    } cases[] = {
        {"--animate '" + spec("wind.json", R"({"frames": 2, "bones": ["head"], "wind": [1, 0, 0], "keys": [{"frame": 0}]})") + "'", "unknown key \"wind\""},
        {"--animate '" + spec("nan.json", R"({"frames": 2, "bones": ["head"], "keys": [{"frame": 0, "rotate_deg": [NaN, 0, 0]}]})") + "'", "not valid JSON"},
        {"--animate '" + spec("zero.json", R"({"frames": 0, "bones": ["head"], "keys": [{"frame": 0}]})") + "'", "/frames"},
        {"--animate '" + spec("fps.json", R"({"frames": 2, "fps": -1, "bones": ["head"], "keys": [{"frame": 0}]})") + "'", "/fps"},
        {"--animate '" + good + "'", "no bone weights"},  // the default style was not imported with --skinning
        {"--animate '" + good + "' --preview-strands", "do not apply"},
    };
    for (const auto& c : cases) {
        const auto r = run_coif("render " + c.args + " -o '" + out + "'");
        EXPECT_EQ(r.exit_code, 1) << c.args << "\n" << r.err;
        EXPECT_THAT(r.err, HasSubstr(c.what)) << c.args;
        for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().extension(), ".png") << e.path();
    }
    EXPECT_EQ(run_coif("render --animate '" + (dir / "missing.json").string() + "' -o '" + out + "'").exit_code, 2);  // CLI11: no such file
    fs::remove_all(dir);
}

TEST(Cli, AScalpIsDrawnForHairWithoutAHead) {
    const auto dir = test::scratch_dir("cli-scalp");
    const std::string size = " --width 96 --height 72 --samples 1 ";
    auto r = run_coif("render --scalp" + size + "-o '" + (dir / "scalp.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(run_coif("render" + size + "-o '" + (dir / "bare.exr").string() + "'").exit_code, 0);
    const coif::Image a = coif::read_image(dir / "scalp.exr"), b = coif::read_image(dir / "bare.exr");
    EXPECT_NE(a.pixels, b.pixels) << "the scalp shows, and shadows the hair";
    std::ofstream(dir / "box.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    r = run_coif("render --scalp --body '" + (dir / "box.obj").string() + "'" + size + "-o '" + (dir / "both.png").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("either --body or --scalp"));
    ASSERT_EQ(run_coif("bake @default -o '" + (dir / "hair.coif").string() + "'").exit_code, 0);
    r = run_coif("render --scalp --style '" + (dir / "hair.coif").string() + "'" + size + "-o '" + (dir / "asset.png").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("not a baked .coif asset"));
    EXPECT_FALSE(fs::exists(dir / "both.png"));
    EXPECT_FALSE(fs::exists(dir / "asset.png"));
    fs::remove_all(dir);
}

TEST(Cli, AnimateTurnsTheRatboysHeadAndTheMohawkStaysOnIt) {
    // The done-when of issue 19 at a small size: the mohawk imported with its skinning, on the Ratboy body, through a
    // head turn; every frame and the contact sheet written, and the clusters' roots on the skin as at rest.
    COIF_SHARED_DATA(tfx, "Ratboy_mohawk.tfx");
    COIF_SHARED_DATA(bone, "Ratboy_mohawk.tfxbone");
    COIF_SHARED_DATA(mesh, "Ratboy_body.tfxmesh");
    const auto dir = test::scratch_dir("cli-animate");
    auto r = run_coif("style import '" + tfx.string() + "' --skinning '" + bone.string() + "' --clusters 64 -o '" + (dir / "mohawk.json").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("--strands-per-guide"));  // the note: a TressFX file holds guide strands
    // With followers, each takes its guide's weights: every cluster is skinned.
    r = run_coif("style import '" + tfx.string() + "' --skinning '" + bone.string() + "' --strands-per-guide 2 --clusters 16 -o '" +
                 (dir / "followed.json").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir / "followed.json"))["skinning"]["clusters"].size(), 16u);
    std::ofstream(dir / "turn.json") << R"({"frames": 3, "bones": ["frenchHornMonster_head_JNT", "frenchHornMonster_jaw_JNT"],
        "keys": [{"frame": 0, "rotate_deg": [0, -30, 0]}, {"frame": 2, "rotate_deg": [0, 30, 0]}]})";
    r = run_coif("render --style '" + (dir / "mohawk.json").string() + "' --body '" + mesh.string() + "' --animate '" +
                 (dir / "turn.json").string() + "' --width 96 --height 96 --samples 1 --json -o '" + (dir / "turn.png").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* name : {"turn_0000.png", "turn_0001.png", "turn_0002.png", "turn_sheet.png"}) EXPECT_TRUE(fs::exists(dir / name)) << name;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["frames"], 3);
    const auto rest = j["root_offset"]["rest"], animated = j["root_offset"]["animated"];
    // Roots keep to the skin: the extremes of their offsets along the body's normals move by at most 0.2 cm (measured:
    // 0.04 over a ±30° turn at 128 clusters); a root left behind by the head would be centimetres off.
    EXPECT_NEAR(animated[0].get<double>(), rest[0].get<double>(), 0.2);
    EXPECT_NEAR(animated[1].get<double>(), rest[1].get<double>(), 0.2);
    const coif::Image sheet = coif::read_image(dir / "turn_sheet.png");
    EXPECT_EQ(sheet.width, 2 * 96);  // 2 to a row
    EXPECT_EQ(sheet.height, 2 * 96);
    // The frames differ: the head turned.
    EXPECT_NE(coif::read_file_bytes(dir / "turn_0000.png"), coif::read_file_bytes(dir / "turn_0002.png"));
    // Simulated in a wind: the same bounds hold for the roots (they are pinned to the skin), and the hair moved.
    std::ofstream(dir / "windy.json") << R"({"frames": 3, "bones": ["frenchHornMonster_head_JNT"],
        "keys": [{"frame": 0, "rotate_deg": [0, -30, 0]}, {"frame": 2, "rotate_deg": [0, 30, 0]}], "dynamics": {"wind": [800, 0, 0]}})";
    r = run_coif("render --style '" + (dir / "mohawk.json").string() + "' --body '" + mesh.string() + "' --animate '" +
                 (dir / "windy.json").string() + "' --width 96 --height 96 --samples 1 --json -o '" + (dir / "windy.png").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto w = nlohmann::json::parse(r.out)["root_offset"]["animated"];
    EXPECT_NEAR(w[0].get<double>(), rest[0].get<double>(), 0.2);
    EXPECT_NEAR(w[1].get<double>(), rest[1].get<double>(), 0.2);
    EXPECT_NE(coif::read_file_bytes(dir / "windy_0002.png"), coif::read_file_bytes(dir / "turn_0002.png"));
    // coif bench animate: every frame's breakdown and the medians, beside the still frame (no figure bounded: a benchmark).
    r = run_coif("bench animate --style '" + (dir / "mohawk.json").string() + "' --body '" + mesh.string() + "' --animate '" +
                 (dir / "windy.json").string() + "' --width 64 --height 48 --samples 1 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto b = nlohmann::json::parse(r.out);
    EXPECT_EQ(b["per_frame_milliseconds"].size(), 3u);
    for (const char* k : {"skinning", "deformation", "shadow_grid", "shadow_pass", "lighting", "shells", "frame"})
        EXPECT_GE(b["median_milliseconds"][k].get<double>(), 0.0) << k;
    EXPECT_GT(b["still_frame_milliseconds"].get<double>(), 0.0);
    fs::remove_all(dir);
}

TEST(Cli, StrandsPerGuideFillSparseHairToTheDatabasesDensity) {
    // Issue 16's sparse styles: Curly_100's 100 strands fitted as they are lie wholly beyond the database's held-out p95
    // distance (measured: 100 % of its non-empty sectors at 64 clusters); filled with 16 strands per guide, as TressFX
    // fills its guides, almost none do (0.2 %). The bound 5 % leaves room for the fit and the database's seed.
    COIF_SHARED_DATA(curly, "Curly_100.hair");
    const auto dir = test::scratch_dir("cli-follow");
    const auto share = [&](const std::string& extra, const std::string& name) {
        auto r = run_coif("style import '" + curly.string() + "' --clusters 64" + extra + " -o '" + (dir / (name + ".json")).string() + "'");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        r = run_coif("render --style '" + (dir / (name + ".json")).string() + "' --width 48 --height 32 --samples 1 --json -o '" +
                     (dir / (name + ".png")).string() + "'");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return nlohmann::json::parse(r.out)["coverage"]["share_beyond_held_out_p95_nonempty"].get<double>();
    };
    EXPECT_GT(share("", "guides"), 0.9);
    EXPECT_LT(share(" --strands-per-guide 16", "filled"), 0.05);
    const auto style = nlohmann::json::parse(std::ifstream(dir / "filled.json"));
    EXPECT_EQ(style["source"]["follow"]["guides"], 100);
    EXPECT_EQ(style["source"]["strands"], 1600);
    // Bad counts are refused before anything is written.
    const auto r = run_coif("style import '" + curly.string() + "' --strands-per-guide 0 -o '" + (dir / "bad.json").string() + "'");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_FALSE(fs::exists(dir / "bad.json"));
    fs::remove_all(dir);
}

TEST(Cli, StyleEditsMoveCopyMirrorAndDeleteClustersWithTheirPaintedRows) {
    // coif style transform | duplicate | mirror | delete | set | add on the default style (models/style_edit.h; its exactness
    // is models.StyleEdit.*): the clusters asked for change, the painted absorption rows follow, bad input writes nothing.
    const auto dir = test::scratch_dir("cli-style-edit");
    const auto p = [&](const char* name) { return "'" + (dir / name).string() + "'"; };
    // Cluster c10 (index 10) painted black, the rest left at the default.
    auto r = run_coif("style paint-absorption @default --streak 10:0.02,0.02,0.02 -o " + p("paint.exr"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_coif("style delete @default --clusters c3 c4 --absorption " + p("paint.exr") + " --absorption-out " + p("paint2.exr") +
                 " -o " + p("fewer.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto fewer = nlohmann::json::parse(std::ifstream(dir / "fewer.json"));
    EXPECT_EQ(fewer["clusters"].size(), 62u);
    const AbsorptionMap rows = read_absorption_map(dir / "paint2.exr", 62);
    EXPECT_EQ(rows.at(8, 0), glm::vec3(0.02f));  // c10's row, two up
    EXPECT_NE(rows.at(7, 0), glm::vec3(0.02f));
    r = run_coif("style duplicate " + p("fewer.json") + " --clusters c25 --translate 6 0 0 -o " + p("more.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto more = nlohmann::json::parse(std::ifstream(dir / "more.json"));
    ASSERT_EQ(more["clusters"].size(), 63u);
    EXPECT_EQ(more["clusters"][62]["name"], "c25_copy");
    EXPECT_EQ(more["clusters"][62]["instance_of"], "c25");
    r = run_coif("style mirror " + p("more.json") + " --clusters c7 c8 --at 0 -o " + p("mirrored.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("mirrored 2 clusters across x = 0"));
    r = run_coif("style transform " + p("mirrored.json") + " --clusters c7_mirror --rotate-deg 0 20 0 --scale 1.1 -o " + p("moved.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_coif("style set " + p("moved.json") + " --cluster c10 --a 1.2 1 0.8 --point 1 --move 0 0 2 --layers 2 -o " + p("set.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir / "set.json"))["clusters"][8]["a"].size(), 3u);
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir / "set.json"))["clusters"][8]["layers"], 2);
    r = run_coif("style add " + p("set.json") + " --root 0 13 -6 --name crown -o " + p("added.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("added crown"));
    const auto added = nlohmann::json::parse(std::ifstream(dir / "added.json"));
    ASSERT_EQ(added["clusters"].size(), 66u);
    EXPECT_EQ(added["clusters"][65]["trajectory"][0], nlohmann::json::array({0.0, 13.0, -6.0}));
    // The result draws (c10 with 2 layered shells, the rest with 4, and the cluster added).
    r = run_coif("render --style " + p("added.json") + " --width 48 --height 32 --samples 1 -o " + p("set.png"));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    // Bad input: a name the style lacks, a map without its output, nothing to set, a bad scale. No file written.
    r = run_coif("style delete @default --clusters c3 nope -o " + p("bad.json"));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("no cluster is named \"nope\""));
    r = run_coif("style delete @default --clusters c3 --absorption " + p("paint.exr") + " -o " + p("bad.json"));
    EXPECT_EQ(r.exit_code, 1);
    r = run_coif("style set @default --cluster c3 -o " + p("bad.json"));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("nothing to set"));
    r = run_coif("style add @default --root 0 nan 0 -o " + p("bad.json"));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("root"));
    r = run_coif("style transform @default --clusters c3 --scale -1 -o " + p("bad.json"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_FALSE(fs::exists(dir / "bad.json"));
    fs::remove_all(dir);
}

TEST(Cli, FailuresExitOneNameTheFileAndWriteNothing) {
    const auto dir = test::scratch_dir("cli-fail");
    std::ofstream(dir / "bad.hair") << "HAIRtruncated";
    auto r = run_coif("hair inspect '" + (dir / "bad.hair").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("bad.hair"));
    EXPECT_THAT(r.err, HasSubstr("truncated"));

    r = run_coif("hair convert '" + (dir / "bad.hair").string() + "' '" + (dir / "out.hair").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_FALSE(fs::exists(dir / "out.hair"));

    r = run_coif("render --strands '" + (dir / "bad.hair").string() + "' -o '" + (dir / "out.png").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_FALSE(fs::exists(dir / "out.png"));

    for (const char* bad : {"--background nan 0 0", "--background 1 1"}) {
        r = run_coif(std::string("render ") + bad + " -o '" + (dir / "out.png").string() + "'");
        EXPECT_TRUE(r.exit_code == 1 || r.exit_code == 2) << bad;
        EXPECT_THAT(r.err, HasSubstr("--background")) << bad;
        EXPECT_FALSE(fs::exists(dir / "out.png"));
    }

    r = run_coif("render -o '" + (dir / "image.xyz").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("unknown image extension"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // only bad.hair
    fs::remove_all(dir);
}

TEST(Cli, PaintAbsorptionWritesAMapAndRefusesBadStrokes) {
    const auto dir = test::scratch_dir("cli-paint");
    const auto map = dir / "dyed.exr";
    auto r = run_coif("style paint-absorption @default --tip 0.05 0.1 0.3 --tip-from 0.5 --streak 1,3-4:2,2,2 -o '" +
                      map.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("64 clusters x 16 samples"));
    const AbsorptionMap m = read_absorption_map(map, 64);
    EXPECT_FLOAT_EQ(m.at(0, 0).x, 0.432f) << "roots keep 000's brown";
    EXPECT_FLOAT_EQ(m.at(0, 15).z, 0.3f) << "tips as asked";
    EXPECT_FLOAT_EQ(m.at(4, 15).x, 2.0f) << "streaked cluster, whole length";
    for (const char* bad : {"--streak 64:1,1,1", "--streak 1:1,1", "--streak x:1,1,1", "--root -1 0 0", "--tip nan 1 1"}) {
        r = run_coif(std::string("style paint-absorption @default ") + bad + " -o '" + (dir / "bad.exr").string() + "'");
        EXPECT_NE(r.exit_code, 0) << bad;
        EXPECT_FALSE(fs::exists(dir / "bad.exr")) << bad;
    }
    // A map of another style's cluster count is refused by render before anything is written.
    write_absorption_map(dir / "three.exr", AbsorptionMap(3, 2, glm::vec3(0.5f)));
    r = run_coif("render --absorption '" + (dir / "three.exr").string() + "' -o '" + (dir / "out.png").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("64 clusters"));
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    fs::remove_all(dir);
}

TEST(Cli, RenderAovsWritesEveryTermBesideTheImage) {
    const auto dir = test::scratch_dir("cli-aovs");
    auto r = run_coif("render --aovs --width 64 --height 48 -o '" + (dir / "h.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"h.exr", "h.R.exr", "h.TT.exr", "h.TRT.exr", "h.multiple.exr", "h.shadow.exr"})
        EXPECT_TRUE(fs::exists(dir / f)) << f;
    EXPECT_EQ(read_image(dir / "h.R.exr").width, 64);
    r = run_coif("render --aovs --width 64 --height 48 -o '" + (dir / "x.tiff").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 6) << "nothing more written";
    fs::remove_all(dir);
}

TEST(Cli, RenderWarnsWhenTheDatabaseDoesNotCoverTheStyle) {
    // 100 CT-scanned strands fitted to 16 clusters: sparse sectors, most beyond the default database's
    // held-out p95 distance (measured 48 %; > 25 % warns), said on stderr and in --json.
    COIF_SHARED_DATA(path, "Curly_100.hair");
    const auto dir = test::scratch_dir("cli-coverage");
    ASSERT_EQ(run_coif("style import '" + path.string() + "' --clusters 16 -o '" + (dir / "c.json").string() + "'").exit_code, 0);
    const auto r = run_coif("render --style '" + (dir / "c.json").string() + "' --width 48 --height 32 --samples 1 --json -o '" +
                            (dir / "c.png").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("warning"));
    EXPECT_THAT(r.err, HasSubstr("beyond the database's held-out p95"));
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_GT(doc["coverage"]["share_beyond_held_out_p95_nonempty"].get<double>(), 0.25);
    EXPECT_EQ(doc["warnings"].size(), 1u);
    fs::remove_all(dir);
}

TEST(Cli, ConvertDataToHairPreservesStrands) {
    COIF_SHARED_DATA(path, "Bangs_100.data");
    const auto dir = test::scratch_dir("cli-convert");
    const auto r = run_coif("hair convert '" + path.string() + "' '" + (dir / "b.hair").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(run_coif("hair inspect --json '" + (dir / "b.hair").string() + "'").out);
    EXPECT_EQ(j["strands"], 100);
    EXPECT_EQ(j["points"], 1165);
    fs::remove_all(dir);
}

TEST(Cli, MsaaSamplesOfTheShellsShadeWithinTheirTriangles) {
    // With MSAA (the blended compositings) a fragment covering only some of a pixel's samples is shaded once; at the
    // pixel centre, outside its triangle, the interpolated inputs extrapolate past the mesh. The default scene at
    // 720 x 480 then had pixels at 1063 (its brightest otherwise 0.77). The shells' inputs are centroid-sampled, so
    // every sample is shaded within its triangle and the resolve only averages: no pixel of the MSAA image is brighter
    // than the single-sample image's brightest (bound 1.05x: half floats, and edges the one sample missed).
    const auto dir = test::scratch_dir("cli-msaa");
    float brightest[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
        const auto out = dir / (std::to_string(i) + ".exr");
        const auto r = run_coif(std::string("render --compositing sorted --samples ") + (i ? "4" : "1") + " -o '" + out.string() + "'");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const Image img = read_image(out);
        for (std::size_t k = 0; k < img.pixels.size(); ++k)
            if (k % 4 != 3) brightest[i] = std::max(brightest[i], img.pixels[k]);
    }
    std::printf("brightest channel: 1 sample %.4f, 4 samples (MSAA) %.4f\n", brightest[0], brightest[1]);
    EXPECT_LE(brightest[1], 1.05f * brightest[0]);
    fs::remove_all(dir);
}

TEST(Cli, RenderDefaultSceneWritesARealImage) {
    const auto dir = test::scratch_dir("cli-render");
    const auto r = run_coif("render --width 160 --height 120 -o '" + (dir / "a.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Image img = read_image(dir / "a.exr");
    ASSERT_EQ(img.width, 160);
    // The default head of hair fills a good part of the frame: count pixels that differ from the background
    // (kDefaultBackground; dark brown hair is both darker and brighter than it) by more than 0.01.
    int hair = 0;
    for (int i = 0; i < img.width * img.height; ++i)
        for (int c = 0; c < 3; ++c)
            if (std::abs(img.pixels[size_t(i) * 4 + c] - kDefaultBackground[c]) > 0.01f) {
                ++hair;
                break;
            }
    EXPECT_GT(hair, img.width * img.height / 20) << "no hair visible in the default render";
    // --background sets what both renderers draw behind the hair (the shells here, the strand lines below;
    // the EXR is half float: 1e-3).
    for (const char* which : {"", " --preview-strands"}) {
        const auto b = run_coif(std::string("render --width 64 --height 48 --samples 1 --json --background 0.3 0.1 0.2") + which +
                                " -o '" + (dir / "b.exr").string() + "'");
        ASSERT_EQ(b.exit_code, 0) << b.err;
        const auto doc = nlohmann::json::parse(b.out);
        EXPECT_EQ(doc["width"], 64);
        if (std::string(which).empty()) {  // the default style is covered by the default database: no warning
            EXPECT_LT(doc["coverage"]["share_beyond_held_out_p95_nonempty"].get<double>(), 0.25);
            EXPECT_TRUE(doc["warnings"].empty()) << doc.dump();
            // The shadows between clusters count fibres of the reference's own auto radius of the same strands.
            const auto ref = run_coif("reference --width 8 --height 8 --spp 1 --json -o '" + (dir / "f.exr").string() + "'");
            ASSERT_EQ(ref.exit_code, 0) << ref.err;
            EXPECT_EQ(doc["fiber_radius"].get<float>(), nlohmann::json::parse(ref.out)["fiber_radius"].get<float>());
            // The own cluster's depth both ways is printed (measured 14.9 fibres, depth 4.3; docs/quality.md).
            EXPECT_GT(doc["own_cluster_across"]["reference_fibres"].get<double>(), 1.0) << doc.dump();
            EXPECT_GT(doc["own_cluster_across"]["shells_depth"].get<double>(), 0.1) << doc.dump();
        }
        const Image bg = read_image(dir / "b.exr");
        EXPECT_NEAR(bg.at(0, 0)[0], 0.3f, 1e-3f) << which;
        EXPECT_NEAR(bg.at(0, 0)[1], 0.1f, 1e-3f) << which;
        EXPECT_NEAR(bg.at(0, 0)[2], 0.2f, 1e-3f) << which;
    }
    fs::remove_all(dir);
}

// The exact compositing's fragment storage has a limit (the GPU's shader-storage block size; 128 MiB, 16.8 M
// fragments, on llvmpipe). `coif render` draws a frame beyond it in tiles (online/shell_renderer.h render), and exits 0
// with every fragment held (it once wrote 2560 x 1440 with holes and exit 0, then failed). The default scene at 2048 x
// 2048 needs 4 tiles. The image is the hair, not holes: its 16 x 16 box filter against the same view rendered at 128 x
// 128 (which needs no tiles): blurred PSNR over 30 dB, radiance within 5 %, and no pixel of the hair's silhouette empty
// (mask IoU over 0.9; measured 37.5 dB, radiance 1.016-1.035, IoU 0.978). A size over the command line's maximum
// (8192) is refused with exit 2. Slow: one 2048 x 2048 frame, about 30 s on 2 cores (4096 x 4096 took 31 tiles and
// 120 s, 8192 x 8192 118 tiles and 310 s).
TEST(CliSlow, FramesBeyondTheFragmentStorageAreDrawnInTiles) {
    const auto dir = test::scratch_dir("cli-render-big");
    const fs::path out = dir / "big.exr";
    auto r = run_coif("render --width 2048 --height 2048 --samples 1 --background 0 0 0 --json -o '" + out.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find(" (0 dropped)"), std::string::npos) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_GT(j["tiles"].get<int>(), 1) << "a frame beyond the fragment storage is drawn in more than one tile";
    std::printf("2048 x 2048: %d tiles, %.0f s\n", j["tiles"].get<int>(), j["render_milliseconds"].get<double>() / 1e3);
    const Image big = read_image(out);
    fs::remove(out);
    Image small(128, 128, 4, 0.0f);
    const int box = big.width / small.width;  // 16
    for (int y = 0; y < big.height; ++y)
        for (int x = 0; x < big.width; ++x)
            for (int c = 0; c < 4; ++c) small.at(x / box, y / box)[c] += big.at(x, y)[c] / static_cast<float>(box * box);
    r = run_coif("render --width 128 --height 128 --samples 16 --background 0 0 0 -o '" + (dir / "small.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CompareResult c = compare_images(read_image(dir / "small.exr"), small, CompareOptions{}, "128 x 128", "2048 x 2048 / 16");
    std::printf("2048 x 2048 reduced against 128 x 128: blurred PSNR %.1f dB, radiance %.3f %.3f %.3f, IoU %.3f\n",
                c.appearance.blurred_psnr_db, c.appearance.radiance_ratio[0], c.appearance.radiance_ratio[1],
                c.appearance.radiance_ratio[2], c.appearance.mask_iou);
    EXPECT_GT(c.appearance.blurred_psnr_db, 30.0);
    for (double v : c.appearance.radiance_ratio) EXPECT_NEAR(v, 1.0, 0.05);
    EXPECT_GT(c.appearance.mask_iou, 0.9);
    EXPECT_EQ(run_coif("render --width 8193 --height 64 -o '" + (dir / "x.png").string() + "'").exit_code, 2);
    fs::remove_all(dir);
}

// Quality presets: each one's image of the default scene against full's (coif compare's appearance metrics), within
// bounds set from what it is for. high, the default, must hold the rule that chose it (blurred PSNR >= 35 dB at 720x480,
// detail ratio within 10 %, radiance within 3 %); medium and low are cheaper and looser, and low blends clusters sorted,
// whose order errors brighten the hair (measured at 720x480: 24.2 dB, radiance 1.003-1.245). Here, at 240x160, each
// strip of a sector draws its fibre tangent and sector by a hash (docs/quality.md, "One tangent per strip"), which the
// coarser levels of detail move onto other pixels: high measures 34.9 dB (39.0 at 720x480, `coif bench render`) / detail
// 1.024 / radiance 1.000-1.006 / mask IoU 0.979 (since the records' thinning 34.8 dB / 1.038 / 1.015-1.020 / 0.969); medium 33.7 / 1.046 / 1.003-1.008 / 0.961; low 28.2 / 0.866 /
// 0.893-1.082 / 0.950 (its coarse meshes and sorted blending move the silhouette). high is asked for 34 dB here, and a
// mask IoU of 0.95 (low 0.94).
// An unknown preset is refused (exit 2 on the command line, 1 in a parameters file, as every bad key there).
TEST(Cli, QualityPresetsStayWithinTheirBoundsOfFull) {
    const auto dir = test::scratch_dir("cli-quality");
    const std::string common = " --width 240 --height 160 --samples 1 --background 0 0 0 ";
    const auto render = [&](const std::string& quality) {
        const auto out = dir / (quality + ".exr");
        const auto r = run_coif("render" + common + "--quality " + quality + " -o '" + out.string() + "'");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return read_image(out);
    };
    const Image full = render("full");
    struct Bound {
        const char* quality;
        double min_blurred_psnr, detail_lo, detail_hi, radiance_lo, radiance_hi, min_iou;
    };
    for (const Bound& b : {Bound{"high", 34.0, 0.9, 1.1, 0.97, 1.03, 0.95}, Bound{"medium", 30.0, 0.8, 1.25, 0.95, 1.05, 0.95},
                           Bound{"low", 20.0, 0.7, 1.5, 0.8, 1.35, 0.94}}) {
        const CompareResult c = compare_images(full, render(b.quality), CompareOptions{}, "full", b.quality);
        const AppearanceMetrics& a = c.appearance;
        EXPECT_GE(a.blurred_psnr_db, b.min_blurred_psnr) << b.quality;
        EXPECT_GE(a.detail_ratio, b.detail_lo) << b.quality;
        EXPECT_LE(a.detail_ratio, b.detail_hi) << b.quality;
        for (double r : a.radiance_ratio) {
            EXPECT_GE(r, b.radiance_lo) << b.quality;
            EXPECT_LE(r, b.radiance_hi) << b.quality;
        }
        EXPECT_GT(a.mask_iou, b.min_iou) << b.quality;
        EXPECT_LT(a.blurred_psnr_db, 1e3) << b.quality << " draws what full draws: the preset changed nothing";
    }
    EXPECT_EQ(run_coif("render --quality ultra -o '" + (dir / "x.png").string() + "'").exit_code, 2);
    {
        std::ofstream p(dir / "ultra.json");
        p << R"({"quality": "ultra"})";
    }
    const auto r = run_coif("render --params '" + (dir / "ultra.json").string() + "' -o '" + (dir / "x.png").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, ::testing::HasSubstr("JSON /quality"));
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// `coif bench render --params`: the file's keys apply over each preset's choices (here the level of detail off), so that
// a preset can be measured with one of its choices changed; without it the preset's own choice stands.
TEST(Cli, BenchRenderParamsApplyOverEachPreset) {
    const auto dir = test::scratch_dir("cli-bench-params");
    {
        std::ofstream p(dir / "full_meshes.json");
        p << R"({"lod_pixels": 0})";
    }
    const auto bench = [&](const std::string& params) {
        const auto r = run_coif("bench render --no-models --frames 1 --width 48 --height 32 --quality high --json" + params);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return r.exit_code == 0 ? nlohmann::json::parse(r.out)["scenes"][0] : nlohmann::json{};
    };
    const auto own = bench(""), changed = bench(" --params '" + (dir / "full_meshes.json").string() + "'");
    ASSERT_EQ(own["quality"], "high");
    EXPECT_EQ(own["lod_pixels"].get<double>(), 24.0);
    EXPECT_EQ(changed["lod_pixels"].get<double>(), 0.0);
    EXPECT_EQ(changed["clusters_at_level"][0], changed["clusters"]) << "every cluster's full meshes";
    EXPECT_LT(own["clusters_at_level"][0].get<int>(), own["clusters"].get<int>()) << "48 x 32 px coarsens the preset's";
    fs::remove_all(dir);
}

// The default preset holds the rule it was chosen by (blurred PSNR ≥ 35 dB, detail ratio in [0.9, 1.1], radiance ratio
// in [0.97, 1.03] of full) beyond the default lights and view: under the city map fitted to 40 lights, seen from behind,
// where the lights it culls per sample are another sky's (docs/renderer.md "Lights culled per lighting sample": at
// 360 × 240 39.8 dB, detail 1.017, radiance 0.989–1.000; culling 20 % instead of 5 % fell to 34.0 dB and 0.952. Here,
// at 240 × 160: 38.9 dB, detail 1.070, radiance 0.983–0.996; with one key light, the default since, 37.5 dB, detail
// 1.006, radiance 0.979–0.997, and without it now 36.9 dB, 1.027, 0.973–0.992: docs/renderer.md "Key lights").
// At 360 × 240 since the records' thinning: 39.3 dB, detail 1.017, radiance 0.994–1.005. At 240 × 160 the coarsest
// level of detail, which draws most clusters there, darkens the thinned hair to 0.957–0.972 of full: off the rule, and
// an open end of docs/renderer.md ("Level of detail"); a finer budget that holds it there (14 px) brightens the default
// view past it instead (1.038–1.044 at 240 × 160, QualityPresetsStayWithinTheirBoundsOfFull).
TEST(Cli, TheDefaultPresetHoldsItsRuleOfFullUnderTheCityMapFromBehind) {
    COIF_SHARED_DATA(map, "blender_studiolight_city.exr");
    const auto dir = test::scratch_dir("cli-quality-city");
    const auto lights = dir / "city.json";
    const auto fit = run_coif("env fit '" + map.string() + "' --lights 40 -o '" + lights.string() + "'");
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const std::string common = " --width 360 --height 240 --samples 1 --background 0 0 0 --azimuth 200 --elevation 10 "
                               "--env '" + lights.string() + "' ";
    const auto render = [&](const std::string& quality) {
        const auto out = dir / (quality + ".exr");
        const auto r = run_coif("render" + common + "--quality " + quality + " -o '" + out.string() + "'");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return read_image(out);
    };
    const CompareResult c = compare_images(render("full"), render("high"), CompareOptions{}, "full", "high");
    const AppearanceMetrics& a = c.appearance;
    std::printf("high against full, city from behind: blurred PSNR %.2f dB, detail %.3f, radiance %.3f %.3f %.3f\n",
                a.blurred_psnr_db, a.detail_ratio, a.radiance_ratio[0], a.radiance_ratio[1], a.radiance_ratio[2]);
    EXPECT_GE(a.blurred_psnr_db, 35.0);
    EXPECT_LT(a.blurred_psnr_db, 1e3) << "high draws what full draws";
    EXPECT_GE(a.detail_ratio, 0.9);
    EXPECT_LE(a.detail_ratio, 1.1);
    for (double r : a.radiance_ratio) {
        EXPECT_GE(r, 0.97);
        EXPECT_LE(r, 1.03);
    }
}

}  // namespace
}  // namespace coif

namespace coif {
namespace {

// coif bake: the default style cooked once into an asset; coif render of the asset draws the same pixels as coif
// render of the style (and starts from the asset's baked parameters); a damaged asset is refused with exit code 1
// and no image.
TEST(Cli, BakedAssetRendersAsItsStyleAndDamagedAssetsAreRefused) {
    namespace fs = std::filesystem;
    const auto dir = test::scratch_dir("cli-bake");
    {
        std::ofstream p(dir / "look.json");
        p << R"({"sigma_a": [0.6, 0.8, 1.2]})";
    }
    const fs::path asset = dir / "hair.coif";
    auto r = run_coif("bake @default --json -o '" + asset.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["clusters"], 64);
    EXPECT_LE(doc["records"].get<int>(), doc["database_records"].get<int>());
    const std::string size = " --width 96 --height 64 --samples 1 ";
    r = run_coif("render" + size + "-o '" + (dir / "style.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_coif("render --style '" + asset.string() + "'" + size + "--json -o '" + (dir / "asset.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(nlohmann::json::parse(r.out)["load"]["asset"].get<bool>());
    // Bit-identical: the same cooked data through the same renderer.
    EXPECT_EQ(read_image(dir / "style.exr").pixels, read_image(dir / "asset.exr").pixels);

    // Baked with other parameters, the asset starts from them (and --params on top would change them again).
    ASSERT_EQ(run_coif("bake @default --params '" + (dir / "look.json").string() + "' -o '" + (dir / "look.coif").string() + "'").exit_code, 0);
    r = run_coif("render --style '" + (dir / "look.coif").string() + "'" + size + "-o '" + (dir / "look.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_coif("render --params '" + (dir / "look.json").string() + "'" + size + "-o '" + (dir / "look_style.exr").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_image(dir / "look.exr").pixels, read_image(dir / "look_style.exr").pixels);
    EXPECT_NE(read_image(dir / "look.exr").pixels, read_image(dir / "asset.exr").pixels);

    // Truncated, corrupted, another version: exit 1, the file named, nothing written.
    const std::vector<std::byte> good = read_file_bytes(asset);
    const auto damaged = [&](const std::string& name, std::vector<std::byte> bytes, const std::string& why) {
        const fs::path bad = dir / (name + ".coif");
        write_file_atomic(bad, bytes);
        const fs::path out = dir / (name + ".png");
        const auto res = run_coif("render --style '" + bad.string() + "'" + size + "-o '" + out.string() + "'");
        EXPECT_EQ(res.exit_code, 1) << name;
        EXPECT_THAT(res.err, HasSubstr(bad.string())) << name;
        EXPECT_THAT(res.err, HasSubstr(why)) << name;
        EXPECT_FALSE(fs::exists(out)) << name;
    };
    damaged("truncated", std::vector<std::byte>(good.begin(), good.begin() + good.size() / 3), "truncated");
    std::vector<std::byte> corrupt = good;
    corrupt[corrupt.size() / 2] ^= std::byte{1};
    damaged("corrupt", corrupt, "checksum");
    std::vector<std::byte> other = good;
    other[8] = std::byte{7};
    damaged("version", other, "version 7");
    // Bake refuses a bad style or parameters before writing anything.
    r = run_coif("bake @default --params '" + (dir / "missing.json").string() + "' -o '" + (dir / "x.coif").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_FALSE(fs::exists(dir / "x.coif"));
    fs::remove_all(dir);
}

// The entries of the temporary folder whose names start with `prefix` (a benchmark's work folders).
std::set<fs::path> temporary_folders(const std::string& prefix) {
    std::set<fs::path> found;
    for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
        if (e.path().filename().string().rfind(prefix, 0) == 0) found.insert(e.path());
    return found;
}

TEST(Cli, BenchLoadTimesTheAssetBesideTheStyle) {
    // The figures vary; what is checked is that each phase is measured and the temporary asset is removed.
    const auto temporaries = [] { return temporary_folders("coif-bench-load-"); };
    const std::set<fs::path> before = temporaries();
    const auto r = run_coif("bench load --repeats 2 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_GT(j["asset_bytes"].get<double>(), 1e6);
    for (const char* key : {"asset_first", "asset_later_median", "style_and_database_first", "style_and_database_later_median"}) {
        EXPECT_GT(j[key]["upload_ms"].get<double>(), 0.0) << key;
        EXPECT_GT(j[key]["read_ms"].get<double>(), 0.0) << key;
    }
    EXPECT_EQ(j["asset_first"]["cook_ms"].get<double>(), 0.0);
    EXPECT_GT(j["style_and_database_first"]["cook_ms"].get<double>(), 0.0);
    EXPECT_EQ(temporaries(), before);
}

TEST(Cli, BenchShadowsSetsTheGridsFibreCountBesideTheTracedGaps) {
    // Along camera rays through the default style, the shadow grid's Poisson exp(-n) against the share of rays that
    // pass between the traced fibres. Fibres gathered into clusters leave at least the gaps that Poisson fibres of the
    // same count leave (measured at 360 x 240, 256 rays: 0.50 against 0.23 at n 1..2, 0.09 against 0.004 at 4..8). A
    // grid that counted the strands in the wrong place (turned or shifted against the drawn fibres) puts fibre-covered
    // pixels in its low bins and shows more light there than the fibres let through; so would one that lost more than
    // about half of them. (A smaller loss hides in the clusters' margin: the bench prints the figures to judge it by.)
    // Tolerance 0.05: three standard errors of a bin's traced mean at 32 rays a pixel and at least 30 pixels.
    const auto r = run_coif("bench shadows --width 96 --height 64 --spp 32 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    int pixels = 0, dense = 0;
    for (const auto& b : j["bins"]) {
        pixels += b["pixels"].get<int>();
        const double n = b["mean_fibres"].get<double>();
        EXPECT_GE(n, b["fibres_from"].get<double>());
        if (!b["fibres_to"].is_null()) {
            EXPECT_LT(n, b["fibres_to"].get<double>());
        }
        if (b["pixels"].get<int>() < 30) continue;
        EXPECT_LE(b["grid_unoccluded"].get<double>(), b["traced_gaps"].get<double>() + 0.05) << "n " << n;
        if (n > 1.0) ++dense;
    }
    EXPECT_EQ(pixels, j["pixels"].get<int>());
    EXPECT_GE(dense, 3);  // the check covers the hair's inside, not only its fringe
    EXPECT_EQ(run_coif("bench shadows --spp 0").exit_code, 2);
    const auto nan = run_coif("bench shadows --radius nan");
    EXPECT_EQ(nan.exit_code, 1);
    EXPECT_THAT(nan.err, HasSubstr("--radius"));
}

TEST(Cli, BenchShadowsTowardALightCountsFromTheFibresTheCameraSees) {
    // --light: at the first fibre of each camera ray, the grid's exp(-n) toward the light beside whether the traced ray
    // toward it leaves the hair. A light at the camera (its direction from the hair, azimuth 20 deg, elevation 10 deg)
    // reaches most of the fibres the camera sees (measured 0.78 at 96 x 64, 16 rays a pixel: the perspective camera's
    // rays part from the light's parallel ones by up to ~15 deg), one from the opposite side few (0.036), and the grid
    // orders them alike. Over the 26 directions of docs/quality.md the grid lets through 0.28-0.84 of the traced share:
    // the visible fibres lie at the hair's surface, where the grid's trilinear density reaches past them. The bounds:
    // 0.6 and 0.1 for the traced shares (several standard errors off at ~11 000 points), and the grid at most the traced
    // share plus 0.05, as along the camera rays. A light ray that did not start at the fibres the camera sees, or a
    // grid turned against them, breaks one of them.
    const std::string size = " --width 96 --height 64 --spp 16 --json";
    const auto front = run_coif("bench shadows --light 0.3368 0.1736 0.9254" + size);
    const auto back = run_coif("bench shadows --light -0.3368 -0.1736 -0.9254" + size);
    ASSERT_EQ(front.exit_code, 0) << front.err;
    ASSERT_EQ(back.exit_code, 0) << back.err;
    const auto f = nlohmann::json::parse(front.out), b = nlohmann::json::parse(back.out);
    for (const auto* j : {&f, &b}) {
        int points = 0;
        for (const auto& bin : (*j)["bins"]) points += bin["points"].get<int>();
        EXPECT_EQ(points, (*j)["points"].get<int>());
        EXPECT_GT(points, 1000);
        EXPECT_LE((*j)["grid_unoccluded"].get<double>(), (*j)["traced_gaps"].get<double>() + 0.05);
    }
    EXPECT_EQ(f["points"], b["points"]);  // the same camera rays
    EXPECT_GT(f["traced_gaps"].get<double>(), 0.6);
    EXPECT_LT(b["traced_gaps"].get<double>(), 0.1);
    EXPECT_GT(f["grid_unoccluded"].get<double>(), b["grid_unoccluded"].get<double>());
    const auto zero = run_coif("bench shadows --light 0 0 0");
    EXPECT_EQ(zero.exit_code, 1);
    EXPECT_THAT(zero.err, HasSubstr("--light"));
    EXPECT_EQ(run_coif("bench shadows --light 1 2").exit_code, 2);
}

TEST(Cli, BenchShadowsWritesItsFiguresPerPixelOnTheGridAsked) {
    // --image: per pixel, the means over its rays of the grid's exp(-n) (R), the traced ray's reaching the light (G) and
    // the coverage (B), a ray that meets no fibre counting 0. So over the image ΣR / ΣB and ΣG / ΣB are the table's means
    // over the fibre points, and ΣB · spp is their count: exactly, up to float sums over ~6 000 pixels (1e-4). --grid
    // sets the voxels along the hair's longest axis: the key lights' 128 makes a grid of twice the shadow pass's 64.
    const fs::path dir = test::scratch_dir("bench-shadows-image");
    const fs::path image = dir / "keep.exr";
    const int spp = 8;
    const auto r = run_coif("bench shadows --light 0 1 -1 --grid 128 --width 96 --height 64 --spp " + std::to_string(spp) +
                            " --json --image '" + image.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const auto coarse = nlohmann::json::parse(run_coif("bench shadows --light 0 1 -1 --width 96 --height 64 --spp 1 --json").out);
    EXPECT_NEAR(j["grid"][1].get<double>(), 2.0 * coarse["grid"][1].get<double>(), 4.0);  // the hair's long axis is y
    const coif::Image img = coif::read_image(image);
    ASSERT_EQ(img.width, 96);
    ASSERT_EQ(img.height, 64);
    ASSERT_EQ(img.channels, 4);
    double sr = 0, sg = 0, sb = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* p = img.at(x, y);
            EXPECT_LE(p[0], p[2] + 1e-6f);  // a fibre's exp(-n) is at most 1 per ray that meets one
            EXPECT_LE(p[1], p[2] + 1e-6f);
            sr += p[0];
            sg += p[1];
            sb += p[2];
        }
    EXPECT_NEAR(sb * spp, j["points"].get<double>(), 1e-3 * j["points"].get<double>());
    EXPECT_NEAR(sr / sb, j["grid_unoccluded"].get<double>(), 1e-4);
    EXPECT_NEAR(sg / sb, j["traced_gaps"].get<double>(), 1e-4);
    const auto no_light = run_coif("bench shadows --image '" + (dir / "x.exr").string() + "'");
    EXPECT_EQ(no_light.exit_code, 1);
    EXPECT_THAT(no_light.err, HasSubstr("--light"));
    EXPECT_FALSE(fs::exists(dir / "x.exr"));
    const auto no_folder = run_coif("bench shadows --light 0 1 0 --image '" + (dir / "none" / "x.exr").string() + "'");
    EXPECT_EQ(no_folder.exit_code, 1);
    EXPECT_THAT(no_folder.err, HasSubstr("x.exr"));
    EXPECT_EQ(run_coif("bench shadows --grid 4").exit_code, 2);
    fs::remove_all(dir);
}

TEST(Cli, BenchSweepComparesEachCaseAsTheCommandsDo) {
    // coif bench sweep: each case is `coif reference` and `coif render` with the same lights, compared as `coif compare`
    // compares them. One case is run by hand here and must give the bench's figures exactly (the same seed, the same
    // deterministic render); the set's tally must add up its cases; --references must reuse a reference for other shell
    // parameters (the reference reads only the fibre's keys) and make a new one for other fibre keys.
    const fs::path dir = test::scratch_dir("bench-sweep");
    const fs::path refs = dir / "refs";
    {
        std::ofstream(dir / "full.json") << R"({"lod_pixels": 0})";
        std::ofstream(dir / "single.json") << R"({"lod_pixels": 0, "multiple": false})";
        std::ofstream(dir / "eta.json") << R"({"lod_pixels": 0, "eta": 1.6})";
        std::ofstream(dir / "bad.json") << R"({"lod_pixels": -3})";
        std::ofstream(dir / "light.json") << nlohmann::json{
            {"format", "coif-srbf-lights"}, {"version", 1}, {"lights", {{{"L", {300, 300, 300}}, {"omega", {0, 0, 1}}, {"lambda", 0.1}}}}}.dump();
    }
    const std::string common = " --spp 4 --references '" + refs.string() + "' --json";
    const auto count_refs = [&] { return std::distance(fs::directory_iterator(refs), fs::directory_iterator{}); };
    const auto r = run_coif("bench sweep --case 'light 0 0 1' --case 'light -1 0 0' --params '" + (dir / "full.json").string() + "'" +
                            common + " --keep '" + (dir / "keep").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["cases"].size(), 2u);
    EXPECT_EQ(j["cases"][0]["name"], "light 0 0 1");
    EXPECT_EQ(count_refs(), 2);
    int in_band = 0;
    std::vector<double> ln;
    for (const auto& c : j["cases"])
        for (const auto& v : c["radiance_ratio"]) {
            EXPECT_TRUE(std::isfinite(v.get<double>()) && v.get<double>() > 0);
            if (v.get<double>() >= 0.8 && v.get<double>() <= 1.25) ++in_band;
            ln.push_back(std::log(v.get<double>()));
        }
    EXPECT_EQ(j["sets"]["lights"]["ratios"], 6);
    EXPECT_TRUE(fs::exists(dir / "keep" / "case1_render.exr"));  // --keep keeps the renders
    EXPECT_EQ(j["sets"]["lights"]["in_band"], in_band);
    // The level is the ratios' geometric mean; with it divided out, the count of the shape alone.
    const double mean_ln = std::accumulate(ln.begin(), ln.end(), 0.0) / double(ln.size());
    int in_band_shape = 0;
    for (double v : ln) in_band_shape += std::exp(v - mean_ln) >= 0.8 && std::exp(v - mean_ln) <= 1.25;
    EXPECT_NEAR(j["sets"]["lights"]["level"].get<double>(), std::exp(mean_ln), 1e-12);
    EXPECT_EQ(j["sets"]["lights"]["in_band_level_removed"], in_band_shape);

    // The same case by hand.
    const std::string size = " --width 96 --height 64 --background 0 0 0 --params '" + (dir / "full.json").string() + "'";
    ASSERT_EQ(run_coif("reference --lights '" + (dir / "light.json").string() + "'" + size + " --spp 4 --max-depth 10 -o '" +
                       (dir / "f.exr").string() + "'").exit_code, 0);
    ASSERT_EQ(run_coif("render --env '" + (dir / "light.json").string() + "'" + size + " -o '" + (dir / "r.exr").string() + "'").exit_code, 0);
    const auto c = run_coif("compare '" + (dir / "f.exr").string() + "' '" + (dir / "r.exr").string() + "' --json");
    ASSERT_EQ(c.exit_code, 0) << c.err;
    const auto by_hand = nlohmann::json::parse(c.out)["appearance"];
    for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(j["cases"][0]["radiance_ratio"][ch].get<double>(), by_hand["radiance_ratio"][ch].get<double>(), 1e-12) << ch;
    EXPECT_NEAR(j["cases"][0]["blurred_psnr_db"].get<double>(), by_hand["blurred_psnr_db"].get<double>(), 1e-9);

    // Other shell parameters reuse the references; another fibre makes its own.
    const auto single = run_coif("bench sweep --case 'light 0 0 1' --params '" + (dir / "single.json").string() + "'" + common);
    ASSERT_EQ(single.exit_code, 0) << single.err;
    EXPECT_EQ(count_refs(), 2);
    const auto again = run_coif("bench sweep --case 'light 0 0 1' --params '" + (dir / "full.json").string() + "'" + common);
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(nlohmann::json::parse(again.out)["cases"][0]["radiance_ratio"], j["cases"][0]["radiance_ratio"]);
    ASSERT_EQ(run_coif("bench sweep --case 'light 0 0 1' --params '" + (dir / "eta.json").string() + "'" + common).exit_code, 0);
    EXPECT_EQ(count_refs(), 3);

    // Bad input: a clear error before any rendering.
    const auto unknown = run_coif("bench sweep --case 'light 2 0 0'");
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_THAT(unknown.err, HasSubstr("--case"));
    EXPECT_EQ(run_coif("bench sweep --set planets").exit_code, 2);
    const auto no_data = run_coif("bench sweep --set maps --data '" + (dir / "none").string() + "'");
    EXPECT_EQ(no_data.exit_code, 1);
    EXPECT_THAT(no_data.err, HasSubstr("none"));
    const auto bad = run_coif("bench sweep --case 'light 0 0 1' --params '" + (dir / "bad.json").string() + "'");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_THAT(bad.err, HasSubstr("bad.json"));
    fs::remove_all(dir);
}

TEST(Cli, BenchSweepWhereLitWeighsTheUnshadowedRatioByASecondShadowedReference) {
    // --where-lit: each case's ratio is lit_weighted_ratio of the unshadowed reference, the shadowed one and the render,
    // all three kept (--keep without --references keeps the references there too); only with --no-shadows.
    const fs::path dir = test::scratch_dir("bench-sweep-lit");
    std::ofstream(dir / "u.json") << R"({"debug": 6, "multiple": false, "fourier_order": 0})";
    const auto r = run_coif("bench sweep --case 'light -1 0 0' --max-depth 1 --no-shadows --where-lit --spp 4 --width 48 --height 32 "
                            "--params '" + (dir / "u.json").string() + "' --json --keep '" + (dir / "keep").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["where_lit"], true);
    const fs::path k = dir / "keep";
    const std::array<double, 3> by_hand =
        coif::lit_weighted_ratio(coif::read_image(k / "case0_reference.exr"), coif::read_image(k / "case0_reference_shadowed.exr"),
                                 coif::read_image(k / "case0_render.exr"), 4, "kept");
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(j["cases"][0]["radiance_ratio"][ch].get<double>(), by_hand[ch], 1e-12) << ch;
    const auto shadowed = run_coif("bench sweep --case 'light -1 0 0' --where-lit");
    EXPECT_EQ(shadowed.exit_code, 1);
    EXPECT_THAT(shadowed.err, HasSubstr("--no-shadows"));
    fs::remove_all(dir);
}

TEST(Cli, BenchQualityRunsEverySceneAndRemovesItsTemporaryFolder) {
    // coif bench quality runs coif reference and coif render per scene (tools/subprocess.h): the default style's shells
    // and the three lighting-only rows, without the models (--data names no folder). The figures are the benchmark's to
    // print (none is bounded here); what is checked is that every scene ran and was compared, and that the temporary
    // folder is gone afterwards.
    const auto temporaries = [] { return temporary_folders("coif-bench-quality-"); };
    const std::set<fs::path> before = temporaries();
    const auto r = run_coif("bench quality --no-fit --width 96 --height 64 --spp 4 --no-convergence --lighting-spp 8 --data '" +
                            (fs::temp_directory_path() / "coif-no-such-folder").string() + "' --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["scenes"].size(), 4u);
    EXPECT_EQ(j["scenes"][0]["renderer"], "SATF shells");
    for (const auto& scene : j["scenes"]) EXPECT_TRUE(std::isfinite(scene["appearance"]["blurred_psnr_db"].get<double>()));
    EXPECT_EQ(temporaries(), before);
}

TEST(Cli, BenchEditTimesAnEditThatKeepsWhatItDidNotChange) {
    // coif bench edit: one dragged control point at a time, cooked keeping the rest, beside a cook from nothing. The
    // figures vary (none is bounded: a benchmark); what is checked is what the edits made anew, and that the last one's
    // cook is a cook from nothing's bytes.
    auto r = run_coif("bench edit --edits 2 --repeats 1 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["same_as_cook_from_nothing"].get<bool>());
    EXPECT_EQ(j["prototypes_made"].get<int>(), 1);
    EXPECT_GE(j["clusters_sampled"].get<int>(), 1);
    EXPECT_LT(j["clusters_sampled"].get<int>(), j["clusters"].get<int>());
    for (const char* key : {"baseline_cook_ms", "edit_ms", "edit_cook_ms", "edit_set_hair_ms"}) EXPECT_GT(j[key].get<double>(), 0.0) << key;
    r = run_coif("bench edit --cluster 100000");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.err, HasSubstr("clusters"));
}

}  // namespace
}  // namespace coif
