// `coif env fit|inspect`: the command's outputs, and bad input → message, exit code 1, no file left behind.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "models/core/atomic_file.h"
#include "models/core/image.h"
#include "offline/envmap.h"
#include "offline/srbf_fit.h"
#include "tests/common/run.h"

namespace {
namespace fs = std::filesystem;
using coif::test::run_coif;

// A small smooth map made of two lights (fits in well under a second).
fs::path write_map(const fs::path& dir, const std::string& name) {
    const std::vector<coif::SrbfLight> lights = {{{4, 3, 2}, glm::normalize(glm::vec3(1, 1, 0)), 0.3f},
                                                 {{0.5f, 0.7f, 1.0f}, {0, 1, 0}, 1.0f}};
    const fs::path path = dir / name;
    coif::write_image(path, coif::envmap_to_image(coif::render_srbf_lights(lights, 64)));
    return path;
}

// Only the inputs are left in dir: no output, no temporary.
void expect_only(const fs::path& dir, std::size_t files) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
    EXPECT_EQ(n, files);
}

TEST(EnvCli, FitWritesLightsAndPreviewAndInspectReadsThem) {
    const auto dir = coif::test::scratch_dir("env-cli-ok");
    const fs::path map = write_map(dir, "two.exr");
    const auto fit = run_coif("env fit '" + map.string() + "' --lights 2 --fit-width 32 -o '" + (dir / "l.json").string() +
                              "' --preview '" + (dir / "p.png").string() + "' --json");
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const auto doc = nlohmann::json::parse(fit.out);
    // Two lights for a two-light map: the fit is near exact (see SrbfFit.RecoversKnownLights).
    EXPECT_LT(doc["fit"]["relative_l2_error_fit_grid"].get<double>(), 0.02);
    EXPECT_LT(std::abs(doc["fit"]["energy_error"].get<double>()), 0.02);
    EXPECT_TRUE(fs::exists(dir / "l.json"));
    const coif::Image preview = coif::read_image(dir / "p.png");
    EXPECT_EQ(preview.width, 2 * 64);
    EXPECT_EQ(preview.height, 32);

    const auto inspect = run_coif("env inspect '" + (dir / "l.json").string() + "' --map '" + map.string() + "' --json");
    ASSERT_EQ(inspect.exit_code, 0) << inspect.err;
    const auto idoc = nlohmann::json::parse(inspect.out);
    EXPECT_EQ(idoc["lights"].get<int>(), 2);
    EXPECT_TRUE(idoc["source_matches"].get<bool>());
    EXPECT_EQ(idoc["source"]["checksum"], doc["checksum"]);

    const auto text = run_coif("env inspect '" + (dir / "l.json").string() + "'");
    EXPECT_EQ(text.exit_code, 0);
    EXPECT_NE(text.out.find("relative L2 error"), std::string::npos) << text.out;

    // The lights do not belong to another map: inspect --map says so and fails.
    const fs::path other = dir / "other.exr";
    coif::write_image(other, coif::Image(64, 32, 3, 1.0f));
    EXPECT_EQ(run_coif("env inspect '" + (dir / "l.json").string() + "' --map '" + other.string() + "'").exit_code, 1);
}

TEST(EnvCli, RotationIsTheSameInFitRenderAndReference) {
    // --rotate-lights turns the lights as a file of turned lights would (reference: bit-identical images, the
    // same function), and `env fit --rotate` fits the turned map and records the turn.
    const auto dir = coif::test::scratch_dir("env-cli-rotate");
    coif::SrbfLightSet set;
    set.lights = {{{40, 30, 20}, glm::normalize(glm::vec3(1, 0.3f, 0.2f)), 0.2f}};
    coif::write_srbf_lights(dir / "l.json", set);
    set.lights = coif::rotate_srbf_lights_y(set.lights, float(M_PI / 3));
    coif::write_srbf_lights(dir / "l60.json", set);
    const std::string common = " --width 24 --height 16 --spp 2 --max-depth 1 --threads 1 -o '";
    ASSERT_EQ(run_coif("reference --lights '" + (dir / "l.json").string() + "' --rotate-lights 60" + common + (dir / "a.exr").string() + "'").exit_code, 0);
    ASSERT_EQ(run_coif("reference --lights '" + (dir / "l60.json").string() + "'" + common + (dir / "b.exr").string() + "'").exit_code, 0);
    EXPECT_EQ(coif::read_image(dir / "a.exr").pixels, coif::read_image(dir / "b.exr").pixels);
    const auto bad = run_coif("reference --lights '" + (dir / "l.json").string() + "' --rotate-lights nan" + common + (dir / "c.exr").string() + "'");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find("--rotate-lights"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir / "c.exr"));
    const std::string lines = " --preview-strands --width 32 --height 24 --samples 1 -o '";
    ASSERT_EQ(run_coif("render --env '" + (dir / "l.json").string() + "' --rotate-lights 60" + lines + (dir / "d.exr").string() + "'").exit_code, 0);
    ASSERT_EQ(run_coif("render --env '" + (dir / "l60.json").string() + "'" + lines + (dir / "e.exr").string() + "'").exit_code, 0);
    EXPECT_EQ(coif::read_image(dir / "d.exr").pixels, coif::read_image(dir / "e.exr").pixels);

    const fs::path map = write_map(dir, "two.exr");
    const auto fit = run_coif("env fit '" + map.string() + "' --lights 2 --fit-width 32 --rotate 90 -o '" + (dir / "r.json").string() + "'");
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const coif::SrbfLightSet r = coif::read_srbf_lights(dir / "r.json");
    ASSERT_TRUE(r.source.has_value());
    EXPECT_EQ(r.source->rotation_y_deg, 90.0);
    // write_map's bright light at (1, 1, 0)/√2 turned by 90° about +y is at (0, 1, -1)/√2.
    const coif::SrbfLight& bright = r.lights[0].L.x > r.lights[1].L.x ? r.lights[0] : r.lights[1];
    EXPECT_GT(glm::dot(bright.omega, glm::normalize(glm::vec3(0, 1, -1))), 0.99f);
}

struct BadCase {
    std::string name;
    std::function<void(const fs::path&)> make;  // writes dir/"in.*"
    std::string file;
    std::string args;
    std::string message;
};

TEST(EnvCli, BadInputFailsWithExitCode1AndLeavesNothing) {
    const std::vector<BadCase> cases = {
        {"square", [](const fs::path& p) { coif::write_image(p, coif::Image(32, 32, 3, 1.0f)); }, "in.exr", "-n 4",
         "2 x height"},
        {"nan",
         [](const fs::path& p) {
             coif::Image img(32, 16, 3, 1.0f);
             img.at(3, 4)[0] = NAN;
             coif::write_image(p, img);
         },
         "in.exr", "-n 4", "pixel (col 3, row 4)"},
        {"inf",
         [](const fs::path& p) {
             coif::Image img(32, 16, 3, 1.0f);
             img.at(3, 4)[2] = INFINITY;
             coif::write_image(p, img);
         },
         "in.exr", "-n 4", "NaN or infinite"},
        {"negative",
         [](const fs::path& p) {
             coif::Image img(32, 16, 3, 1.0f);
             img.at(5, 6)[1] = -2.0f;
             coif::write_image(p, img, {.exposure = 0, .full_float = true, .description = ""});
         },
         "in.exr", "-n 4", "negative radiance"},
        {"empty", [](const fs::path& p) { coif::write_file_atomic(p, std::string_view()); }, "in.hdr", "-n 4",
         "empty file"},
        {"zero lights", [](const fs::path& p) { write_map(p.parent_path(), p.filename().string()); }, "in.exr",
         "--lights 0", "--lights"},
        {"absurd lights", [](const fs::path& p) { write_map(p.parent_path(), p.filename().string()); }, "in.exr",
         "--lights 1000000", "--lights"},
        {"more lights than the grid holds", [](const fs::path& p) { write_map(p.parent_path(), p.filename().string()); },
         "in.exr", "--lights 500 --fit-width 32", "--lights"},
        {"bad preview", [](const fs::path& p) { write_map(p.parent_path(), p.filename().string()); }, "in.exr",
         "-n 2 --preview out.jpg", "--preview"},
    };
    for (const BadCase& c : cases) {
        const auto dir = coif::test::scratch_dir("env-cli-bad");
        c.make(dir / c.file);
        std::string args = c.args;
        if (const auto at = args.find("out.jpg"); at != std::string::npos) args.replace(at, 7, (dir / "out.jpg").string());
        const auto r = run_coif("env fit '" + (dir / c.file).string() + "' " + args + " -o '" + (dir / "out.json").string() + "'");
        EXPECT_EQ(r.exit_code, 1) << c.name << ": " << r.err;
        EXPECT_NE(r.err.find("coif: error:"), std::string::npos) << c.name << ": " << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.name << ": " << r.err;
        expect_only(dir, 1);
    }
}

TEST(EnvCli, EightBitMapIsFittedWithAWarning) {
    const auto dir = coif::test::scratch_dir("env-cli-ldr");
    coif::write_image(dir / "ldr.png", coif::envmap_to_image(coif::render_srbf_lights(
                                           std::vector<coif::SrbfLight>{{{0.8f, 0.6f, 0.4f}, {0, 1, 0}, 0.5f}}, 32)));
    const auto r = run_coif("env fit '" + (dir / "ldr.png").string() + "' -n 1 -o '" + (dir / "l.json").string() + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("8-bit"), std::string::npos) << r.err;
}

TEST(EnvCli, InspectRefusesABrokenLightsFile) {
    const auto dir = coif::test::scratch_dir("env-cli-json");
    coif::write_file_atomic(dir / "bad.json", std::string_view("{\"format\": \"coif-srbf-lights\", \"version\": 1, \"lights\": []}"));
    const auto r = run_coif("env inspect '" + (dir / "bad.json").string() + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("JSON /lights"), std::string::npos) << r.err;
}

}  // namespace
