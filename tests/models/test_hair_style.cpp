// Style files (models/hair_style.h): the four-level hierarchy, the JSON round trip, every kind of bad
// input (library and `coif style` command), and strand export.
#include <fstream>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/hair_style.h"
#include "models/style_strands.h"
#include "tests/common/run.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using nlohmann::json;

// Three clusters: c0 with geometry, c1 an instance of c0, c2 an instance of c1 (a chain).
json example_style() {
    return json::parse(R"({
      "format": "coif-style", "version": 1, "name": "test",
      "layout": {"core_radius": 0.2, "layers": 2, "s_t": 4, "s_u": 6, "grid": [4, 2], "mesh": [2, 1], "gaussian_width": 0.05},
      "clusters": [
        {"name": "c0", "trajectory": [[0,0,0],[0.2,-2,0],[0.5,-4,0.3],[0.4,-6,0.5]],
         "a": [0.6, 0.5, 0.3], "b": [0.3], "theta_deg": [0, 45],
         "density": {"kind": "strands", "strand_weight": 2,
                     "strands": [[0, 0.5, 10, 0.5, 20, 0.6, 30, 0.6, 40, 0.5, 50], [1, 0.9, 200, 0.8, 210]]}},
        {"name": "c1", "instance_of": "c0",
         "transform": {"scale": 1.5, "rotation": [0.9238795, 0, 0.3826834, 0], "translation": [3, 0, 0]}},
        {"name": "c2", "instance_of": "c1",
         "transform": {"scale": 0.5, "rotation": [1, 0, 0, 0], "translation": [0, 1, 0]}}
      ]})");
}

HairStyle parse(const json& doc) { return parse_style(doc.dump(), "test.json"); }

// The error message of parsing `doc`, which must fail.
std::string error_of(const std::string& text) {
    try {
        parse_style(text, "bad.json");
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), fs::path("bad.json"));
        return e.what();
    }
    ADD_FAILURE() << "no error for " << text.substr(0, 200);
    return {};
}
std::string error_of(const json& doc) { return error_of(doc.dump()); }

TEST(HairStyle, HierarchyInstancesShareDataAndComposeTransforms) {
    const HairStyle s = parse(example_style());
    ASSERT_EQ(s.clusters.size(), 3u);
    EXPECT_EQ(s.prototype_count(), 1u);
    const auto macros = s.macro_clusters();
    ASSERT_EQ(macros.size(), 1u);
    EXPECT_EQ(macros[0].prototype, 0u);
    EXPECT_EQ(macros[0].members, (std::vector<std::size_t>{0, 1, 2}));
    // One geometry and one density object for the whole macro-cluster.
    EXPECT_EQ(s.clusters[1].shape.get(), s.clusters[0].shape.get());
    EXPECT_EQ(s.clusters[2].shape.get(), s.clusters[0].shape.get());
    EXPECT_EQ(s.clusters[2].density.get(), s.clusters[0].density.get());
    // c2 = T2 ∘ T1 applied to c0's geometry (1e-12: rounding).
    const glm::dvec3 p0 = s.clusters[0].shape->point(0.4, 0.7, 1.0);
    const glm::dvec3 direct = s.clusters[2].transform.apply(s.clusters[1].transform.apply(p0));
    EXPECT_LT(glm::length(s.clusters[2].placement.apply(p0) - direct), 1e-12);
    EXPECT_DOUBLE_EQ(s.clusters[2].placement.scale, 0.75);
    const StyleCounts c = style_counts(s);
    EXPECT_EQ(c.hsvs, 3u * 4 * 2 * 6);
    EXPECT_EQ(c.sectors, 3u * 5 * 2 * 6);
    EXPECT_EQ(c.shared_macro_clusters, 1u);
}

TEST(HairStyle, JsonRoundTrip) {
    const HairStyle a = parse(example_style());
    const HairStyle b = parse_style(style_text(a), "again.json");
    ASSERT_EQ(b.clusters.size(), a.clusters.size());
    EXPECT_EQ(b.layout.s_u, 6);
    EXPECT_EQ(b.layout.grid_s, 4);
    for (std::size_t c = 0; c < a.clusters.size(); ++c) {
        EXPECT_EQ(b.clusters[c].name, a.clusters[c].name);
        for (double t : {0.0, 0.3, 1.0}) {
            const glm::dvec3 pa = a.clusters[c].placement.apply(a.clusters[c].shape->point(t, 0.8, 2.0));
            const glm::dvec3 pb = b.clusters[c].placement.apply(b.clusters[c].shape->point(t, 0.8, 2.0));
            EXPECT_LT(glm::length(pa - pb), 1e-5);  // 7 significant digits in the file
        }
    }
    const DensitySource& d = *b.clusters[0].density;
    ASSERT_EQ(d.strands.size(), 2u);
    EXPECT_EQ(d.strands[1].first_plane, 1);
    EXPECT_NEAR(d.strands[1].vu[0].y, 200 * std::numbers::pi / 180, 1e-6);
    EXPECT_EQ(d.strand_weight, 2.0);
}

TEST(HairStyle, BadFilesNameTheJsonPath) {
    {
        json d = example_style();
        d["clusters"][0].erase("a");
        EXPECT_THAT(error_of(d), HasSubstr("bad.json: JSON /clusters/0/a: missing field"));
    }
    {
        json d = example_style();
        d["layout"].erase("layers");
        EXPECT_THAT(error_of(d), HasSubstr("JSON /layout/layers: missing field"));
    }
    {
        json d = example_style();
        d["clusters"][0]["b"] = {0.3, -0.1};
        EXPECT_THAT(error_of(d), HasSubstr("JSON /clusters/0/b/1: radius"));
        EXPECT_THAT(error_of(d), HasSubstr("negative"));
    }
    {
        json d = example_style();
        d["clusters"][0]["a"][0] = 0;
        EXPECT_THAT(error_of(d), HasSubstr("JSON /clusters/0/a/0: radius is zero"));
    }
    {  // NaN is not JSON; it is still reported at its path.
        std::string text = example_style().dump();
        text.replace(text.find("[0.2,-2,0]"), 10, "[NaN,-2,0]");
        EXPECT_THAT(error_of(text), HasSubstr("JSON /clusters/0/trajectory/1/0: NaN or infinity"));
    }
    {  // An overflowing literal parses to infinity.
        std::string text = example_style().dump();
        text.replace(text.find("[0.2,-2,0]"), 10, "[0.2,-1e999,0]");
        EXPECT_THAT(error_of(text), HasSubstr("JSON /clusters/0/trajectory/1/1: NaN or infinity"));
    }
    {
        json d = example_style();
        d["clusters"][0]["instance_of"] = "c2";
        d["clusters"][0]["transform"] = d["clusters"][1]["transform"];
        for (const char* k : {"trajectory", "a", "b", "theta_deg", "density"}) d["clusters"][0].erase(k);
        EXPECT_THAT(error_of(d), HasSubstr("cycle"));
        EXPECT_THAT(error_of(d), HasSubstr("/instance_of"));
    }
    {
        json d = example_style();
        d["clusters"][1]["instance_of"] = "c1";
        EXPECT_THAT(error_of(d), HasSubstr("JSON /clusters/1/instance_of: instance references form a cycle: c1 → c1"));
    }
    {
        json d = example_style();
        d["clusters"][1]["instance_of"] = "nobody";
        EXPECT_THAT(error_of(d), HasSubstr("JSON /clusters/1/instance_of: no cluster is named \"nobody\""));
    }
    {
        json d = example_style();
        d["version"] = 2;
        EXPECT_THAT(error_of(d), HasSubstr("JSON /version: unknown version 2"));
    }
    {
        json d = example_style();
        d["format"] = "something-else";
        EXPECT_THAT(error_of(d), HasSubstr("JSON /format: unknown format"));
    }
    {  // Each count in range, but together far more than memory.
        json d = example_style();
        d["layout"]["s_t"] = 4096;
        d["layout"]["s_u"] = 4096;
        d["layout"]["grid"] = {256, 256};
        EXPECT_THAT(error_of(d), HasSubstr("JSON /layout: the density grids of 3 clusters would need"));
    }
    {
        json d = example_style();
        d["layout"]["s_t"] = 1e12;
        EXPECT_THAT(error_of(d), HasSubstr("JSON /layout/s_t: 1e+12 is out of range"));
    }
    {  // beyond a long long: the message must not cast it (undefined behaviour, found by the style fuzz target)
        json d = example_style();
        d["layout"]["layers"] = 2.88889e21;
        EXPECT_THAT(error_of(d), HasSubstr("JSON /layout/layers: 2.88889e+21 is out of range [1, 256]"));
    }
    {
        json d = example_style();
        d["clusters"][0]["density"]["strands"][0][0] = 3;  // a 5-plane run from plane 3 of 0..4
        EXPECT_THAT(error_of(d), HasSubstr("JSON /clusters/0/density/strands/0: runs past the last sector plane"));
    }
    {
        json d = example_style();
        d["clusters"][2]["name"] = "c0";
        EXPECT_THAT(error_of(d), HasSubstr("JSON /clusters/2/name: duplicate cluster name"));
    }
    {
        json d = example_style();
        d["clusters"][0]["density"] = {{"kind", "grids"}, {"sectors", json::array({json::array({1, 2})})}};
        EXPECT_THAT(error_of(d), HasSubstr("JSON /clusters/0/density/sectors: has 1 entries; at least 60 needed"));
    }
    {
        json d = example_style();
        d["clusters"][0]["trajectory"] = {{1, 2, 3}, {1, 2, 3}};
        EXPECT_THAT(error_of(d), HasSubstr("JSON /clusters/0/trajectory: generalized cylinder: the trajectory has zero"));
    }
    EXPECT_THAT(error_of(std::string("{\"format\": \"coif-style\", ")), HasSubstr("bad.json: byte"));
}

TEST(HairStyle, CommandRejectsBadFilesAndWritesNothing) {
    const fs::path dir = test::scratch_dir("style-bad");
    json d = example_style();
    d["clusters"][0]["a"] = {0.5, -1.0};
    const fs::path bad = dir / "bad.json";
    std::ofstream(bad) << d.dump();
    const fs::path out = dir / "out.hair";
    for (const std::string& verb : {"inspect '" + bad.string() + "'", "export-strands '" + bad.string() + "' -o '" + out.string() + "'"}) {
        const test::RunResult r = test::run_coif("style " + verb);
        EXPECT_EQ(r.exit_code, 1) << verb << "\n" << r.err;
        EXPECT_THAT(r.err, HasSubstr("bad.json: JSON /clusters/0/a/1"));
    }
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // only bad.json
    fs::remove_all(dir);
}

TEST(HairStyle, ExportStrandsFromDensityAndMembers) {
    const HairStyle s = parse(example_style());
    StrandSampling o;
    o.from = StrandSampling::From::Members;
    const Strands members = sample_strands(s, o);
    EXPECT_EQ(members.strand_count(), 2u * 3);  // two stored runs, three clusters
    o.from = StrandSampling::From::Density;
    const Strands dense = sample_strands(s, o);
    // Plane 0 has 1 stored crossing of weight 2, planes 1–2 two: each cluster gets 4 strands.
    EXPECT_EQ(dense.strand_count(), 3u * 4);
    // Every sampled point lies inside its cluster's envelope (instances through their placement).
    const Cluster& c0 = s.clusters[0];
    for (std::size_t i = 0; i < 4; ++i)
        for (std::uint32_t k = dense.offsets[i]; k < dense.offsets[i + 1]; ++k)
            EXPECT_LT(c0.shape->distance_outside(glm::dvec3(dense.points[k])), 1e-4);
}

}  // namespace
}  // namespace coif
