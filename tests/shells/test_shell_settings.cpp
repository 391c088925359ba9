// The shell renderer's parameters file (online/shells/shell_settings.h), GL-free: one file read through
// the hair's table and the renderer's, refusals naming the file and JSON path, and write → read.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "models/core/error.h"
#include "online/shells/shell_settings.h"
#include "tests/common/test_data.h"

namespace coif {
namespace {

class ShellSettingsFile : public ::testing::Test {
protected:
    void SetUp() override { dir_ = test::scratch_dir("shell-settings"); }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string write(const char* name, const std::string& text) {
        std::ofstream(dir_ / name) << text;
        return (dir_ / name).string();
    }
    // The message of the error reading `text` ("" if it was accepted).
    std::string refusal(const std::string& text) {
        const std::string path = write("refused.json", text);
        try {
            gl::read_shell_settings(path);
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), path);
            return e.place() + ": " + e.problem();
        }
        return "";
    }
    std::filesystem::path dir_;
};

// The own cluster's shadow variant the shading compiles: the forward-scattered light only with multiple scattering.
TEST(ShellSettings, TheOwnClustersForwardLightGoesWithMultipleScattering) {
    gl::ShellSettings s;
    EXPECT_EQ(gl::own_cluster_variant(s), 2);  // the defaults
    s.hair.multiple = false;
    EXPECT_EQ(gl::own_cluster_variant(s), 1);
    s.hair.multiple = true;
    s.own_cluster_forward = false;
    EXPECT_EQ(gl::own_cluster_variant(s), 1);
    s.own_cluster_shadow = false;
    EXPECT_EQ(gl::own_cluster_variant(s), 0);
}

TEST_F(ShellSettingsFile, BadFilesAreRefusedAtTheirKey) {
    EXPECT_EQ(refusal(R"({"neighbours": 9})"), "JSON /neighbours: must be an integer 1..4");
    EXPECT_EQ(refusal(R"({"eta": 0.5})").rfind("JSON /eta: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"sigma_a": [1, 2]})"), "JSON /sigma_a: expected [r, g, b]");
    EXPECT_EQ(refusal(R"({"nonsense": 1})").rfind("JSON /nonsense: unknown parameter", 0), 0u);
    EXPECT_EQ(refusal(R"({"kappa_shadow": -1})").rfind("JSON /kappa_shadow: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"fiber_radius": 101})").rfind("JSON /fiber_radius: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"fiber_radius": -0.1})").rfind("JSON /fiber_radius: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"debug": 1.5})"), "JSON /debug: must be an integer 0..6");
    EXPECT_EQ(refusal(R"({"fourier_order": 5})"), "JSON /fourier_order: must be an integer 0..4");
    EXPECT_EQ(refusal(R"({"shadows": "yes"})"), "JSON /shadows: expected true or false");
    EXPECT_EQ(refusal("not json").rfind("byte ", 0), 0u);
    // Each value alone is in range, but 000's link β_TRT = 2 β_R is not: the whole hair is validated too.
    EXPECT_NE(refusal(R"({"beta_R_deg": 60})").find("beta_TRT"), std::string::npos);
}

TEST_F(ShellSettingsFile, HairAndRendererKeysReadFromOneFile) {
    const gl::ShellSettings ok =
        gl::read_shell_settings(write("g.json", R"({"beta_R_deg": 10, "lobes": {"TT": false}, "neighbours": 3, "d_f": 0.5})"));
    EXPECT_EQ(ok.hair.fibre.beta_TRT, 2.0f * (10.0f * 0.017453292519943295f));  // 000's link β_TRT = 2 β_R
    EXPECT_EQ(ok.hair.lobes, shading::kLobes[0].bit | shading::kLobes[2].bit);
    EXPECT_EQ(ok.neighbours, 3);
    EXPECT_EQ(ok.hair.d_f, 0.5f);
}

TEST_F(ShellSettingsFile, CompositingModeByName) {
    EXPECT_EQ(gl::read_shell_settings(write("a.json", R"({"compositing": "unsorted"})")).compositing, gl::Compositing::unsorted);
    EXPECT_EQ(gl::read_shell_settings(write("b.json", R"({"compositing": "sorted"})")).compositing, gl::Compositing::sorted);
    EXPECT_EQ(gl::read_shell_settings(write("c.json", R"({"compositing": "exact"})")).compositing, gl::Compositing::exact);
    EXPECT_EQ(gl::read_shell_settings(write("d.json", R"({"compositing": "weighted"})")).compositing, gl::Compositing::weighted);
    EXPECT_EQ(gl::read_shell_settings(write("e.json", R"({"compositing": "kbuffer"})")).compositing, gl::Compositing::kbuffer);
    EXPECT_EQ(refusal(R"({"compositing": "peeled"})"),
              "JSON /compositing: 'peeled' is not sorted, unsorted, exact, weighted or kbuffer");
    EXPECT_EQ(refusal(R"({"kbuffer_slots": 17})").rfind("JSON /kbuffer_slots: ", 0), 0u);  // 1..kMaxKBufferSlots
    EXPECT_EQ(refusal(R"({"kbuffer_slots": 0})").rfind("JSON /kbuffer_slots: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"light_cull": 0.6})").rfind("JSON /light_cull: ", 0), 0u);  // 0..0.5
    EXPECT_EQ(refusal(R"({"shadow_outward": 1.5})").rfind("JSON /shadow_outward: ", 0), 0u);  // 0..1
    EXPECT_EQ(refusal(R"({"shadow_outward": -0.1})").rfind("JSON /shadow_outward: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"own_cluster_inner": 4.5})").rfind("JSON /own_cluster_inner: ", 0), 0u);  // 0..4
    EXPECT_EQ(refusal(R"({"own_cluster_inner": -1})").rfind("JSON /own_cluster_inner: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"hot_spot": 9})").rfind("JSON /hot_spot: ", 0), 0u);  // 0..8
    EXPECT_EQ(refusal(R"({"hot_spot": -1})").rfind("JSON /hot_spot: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"key_toward_camera": -0.5})").rfind("JSON /key_toward_camera: ", 0), 0u);  // 0..8 voxels
    EXPECT_EQ(refusal(R"({"key_toward_light": 9})").rfind("JSON /key_toward_light: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"key_re_mean": 1})").rfind("JSON /key_re_mean: ", 0), 0u);
    EXPECT_EQ(refusal(R"({"compositing": true})").rfind("JSON /compositing: ", 0), 0u);
}

TEST_F(ShellSettingsFile, WriteThenReadGivesTheSameSettings) {
    gl::ShellSettings s;
    // Angles as a file, a shorthand or a slider sets them: in degrees (models/core/param_table.h: an angle
    // set in radians comes back exactly only where a float number of degrees reaches it).
    for (const auto& [key, value] : {std::pair{"eta", 1.7}, {"alpha_R_deg", -5.7}, {"beta_R_deg", 8.6}, {"alpha_TT_deg", 2.3},
                                     {"ecc_a", 1.1}, {"w_c_deg", 11.5}})
        shading::set_hair_parameter(s.hair, key, value, "test");
    s.hair.fibre.sigma_a = glm::vec3(0.3f, 0.9f, 1.9f);
    s.hair.lobes = 3;
    s.hair.d_f = 0.4f;
    s.shadows = false;
    s.own_cluster_shadow = false;
    s.own_cluster_forward = !gl::ShellSettings{}.own_cluster_forward;
    s.shadow_neighbours = !gl::ShellSettings{}.shadow_neighbours;
    s.shadow_outward = 0.25f;
    s.own_cluster_inner = 0.5f;
    s.hot_spot = 4;
    s.key_re_mean = false;
    s.key_toward_camera = 0.5f;
    s.key_toward_light = 2.25f;
    s.tilt_per_strip = false;
    s.sector_per_strip = false;
    s.fiber_radius = 0.03f;
    s.kappa_shadow = 0.8f;
    s.neighbours = 4;
    s.fourier_order = 3;
    s.compositing = gl::Compositing::sorted;
    s.kbuffer_slots = 3;
    s.light_cull = 0.125f;
    s.debug = 2;
    s.lighting_per_fragment = true;
    const std::string path = (dir_ / "written.json").string();
    gl::write_shell_settings(path, s);
    const gl::ShellSettings back = gl::read_shell_settings(path);
    EXPECT_EQ(gl::shell_settings_json(back), gl::shell_settings_json(s));
    EXPECT_EQ(std::memcmp(&back.hair.fibre, &s.hair.fibre, sizeof s.hair.fibre), 0);
    EXPECT_EQ(back.fiber_radius, 0.03f);
    // The reference's auto radius (fiber_radius 0) is the key's absence.
    const nlohmann::ordered_json defaults = gl::shell_settings_json(gl::ShellSettings{});
    EXPECT_FALSE(defaults.contains("fiber_radius"));
    EXPECT_EQ(gl::read_shell_settings(write("d.json", defaults.dump())).fiber_radius, 0.0f);
    for (const auto& p : gl::shell_settings_table())  // the one list serves the writer: every key not optional
        EXPECT_TRUE(defaults.contains(p.key) || p.written) << p.key;
}

}  // namespace
}  // namespace coif
