// The cooked hair and its `.coif` asset (online/shells/hair_asset.h, online/scene/cook.h): an asset draws
// bit-identically to its style cooked live; the atlas of the records a style uses draws as the whole database's;
// truncated, corrupt, hostile and other-version files are refused with an error naming the file and the place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "models/core/checksum.h"
#include "models/core/error.h"
#include "models/style_edit.h"
#include "online/gl_context.h"
#include "online/scene/cook.h"
#include "online/shell_renderer.h"
#include "online/shells/hair_asset.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

using test::one_cluster_style;
using test::prototype_and_instance;
using test::test_db;
using test::test_index;
using test::two_lights;


Image draw(CookedShells cooked) {
    gl::ShellRenderer r(std::move(cooked));
    r.set_lights(two_lights());
    const Camera camera = Camera::orbit(r.bounds_min(), r.bounds_max(), 0.4f, 0.2f, 96, 64);
    gl::ShellSettings s;
    s.samples = 1;
    return r.render(camera, s);
}

const CookedShells& cooked() {
    static const CookedShells c = cook_shells(prototype_and_instance(), test_index(), glm::mat3(1.0f));
    return c;
}

// The bytes with the header's checksum rewritten over them (so that a hostile edit reaches the checks behind it).
std::vector<std::byte> resealed(std::vector<std::byte> b) {
    const std::uint64_t sum = checksum(std::span<const std::byte>(b).subspan(32));
    std::memcpy(b.data() + 24, &sum, 8);
    return b;
}

std::string refusal(const std::vector<std::byte>& bytes) {
    try {
        (void)parse_hair_asset(bytes, "hair.coif");
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "hair.coif");
        return e.what();
    }
    return "accepted";
}

TEST(HairAsset, DrawsBitIdenticallyToItsStyleCookedLive) {
    auto context = gl::Context::headless();
    const std::vector<std::byte> bytes = hair_asset_bytes(cooked());
    const CookedShells read = parse_hair_asset(bytes, "hair.coif");
    EXPECT_EQ(read.shells.clusters(), 2u);
    EXPECT_EQ(read.atlas.re_norm, cooked().atlas.re_norm);
    EXPECT_EQ(read.database_records, test_db().size());
    // Written again, the same bytes: nothing is lost or rounded on the way.
    EXPECT_EQ(hair_asset_bytes(read), bytes);
    const Image live = draw(cooked()), loaded = draw(read);
    double sum = 0;
    for (float v : live.pixels) sum += v;
    ASSERT_GT(sum, 0.0) << "the hair must show";
    // No tolerance: the same data through the same code on a deterministic rasteriser.
    EXPECT_EQ(live.pixels, loaded.pixels);
}

TEST(HairAsset, HoldsOnlyTheRecordsItsSectorsUseAndDrawsAsTheWholeDatabase) {
    auto context = gl::Context::headless();
    const CookedShells& c = cooked();
    EXPECT_LE(c.atlas.mean_alpha.size(), test_db().size());
    // The same hair with every record of the database in the atlas and the database's own ids.
    CookedShells whole = c;
    const DatabaseAtlasStats stats = database_atlas_stats(test_db());
    whole.shells = prepare_shells(prototype_and_instance(), test_index(), stats.mean_alpha, glm::mat3(1.0f));
    whole.shells.samples = c.shells.samples;  // with the measured tilts
    whole.atlas = pack_record_atlas(test_db());
    EXPECT_EQ(whole.atlas.re_norm, c.atlas.re_norm);
    EXPECT_EQ(whole.atlas.lo, c.atlas.lo);
    EXPECT_EQ(whole.atlas.scale, c.atlas.scale);
    const Image a = draw(c), b = draw(whole);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double diff = 0, mean = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        diff = std::max(diff, double(std::abs(a.pixels[i] - b.pixels[i])));
        mean += b.pixels[i] / a.pixels.size();
    }
    std::printf("subset atlas (%zu records) vs the whole database's (%zu): max |diff| %.3g, mean value %.3g\n",
                c.atlas.mean_alpha.size(), test_db().size(), diff, mean);
    // The texels are the same; only the atlas's size, and with it the rounding of the normalised fetch coordinate,
    // differs. The bilinear filter weighs texels to 1/256 of a texel, so a coordinate rounded the other way moves a
    // weight by 1/256, and the unsmoothed records (offline/planar_tracer.h) step by up to their range from one texel
    // to the next: measured 1.3e-3 of the mean at one pixel (0 with the records smoothed at 1.5 λ); bound 3e-3.
    EXPECT_LE(diff, 3e-3 * mean);
}

TEST(HairAsset, ACookThatKeepsWhatAnEditDidNotChangeIsTheSameCook) {
    // coif view's edits cook again keeping what did not change (CookCache: prototypes, clusters' strands and tilts, the
    // grid's sums, the atlas's tiles): after every edit, the same bytes as a cook from nothing. The skinned style's asset
    // holds the grid's strands too.
    HairStyle s = test::two_cluster_style(true);
    CookCache cache;
    std::pair<glm::vec3, glm::vec3> bounds;  // the last cook's strands' (its grid's frame)
    const auto same_as_from_nothing = [&](const char* what) {
        SCOPED_TRACE(what);
        const CookedShells kept = cook_shells(s, test_index(), glm::mat3(1.0f), 0, nullptr, &cache);
        bounds = {kept.grid.strands_min, kept.grid.strands_max};
        EXPECT_EQ(hair_asset_bytes(kept), hair_asset_bytes(cook_shells(s, test_index(), glm::mat3(1.0f))));
        return cache.timings();
    };
    CookCache::Timings t = same_as_from_nothing("first cook");
    EXPECT_EQ(t.prototypes_made, 2u);
    EXPECT_EQ(t.clusters_sampled, 2u);
    EXPECT_TRUE(t.grid_rebuilt);
    EXPECT_GT(t.records_packed, 0u);
    EXPECT_EQ(t.records_packed, t.records);
    // The right cluster's middle point moved along its straight axis: its strands cross the same places, so the bounds
    // stay, and the grid takes its old strands out and its new ones in.
    move_control_point(s, 1, 1, {0.0, 0.5, 0.0});
    t = same_as_from_nothing("right cluster's middle moved along it");
    EXPECT_EQ(t.prototypes_made, 1u);
    EXPECT_EQ(t.clusters_sampled, 1u);
    EXPECT_FALSE(t.grid_rebuilt) << "this edit was chosen to keep the bounds; if sampling changed, choose another";
    EXPECT_LT(t.records_packed, t.records);
    // The right cluster's middle point moved out: the bounds change, but not the voxel size: the grid is framed anew.
    const auto before = bounds;
    move_control_point(s, 1, 1, {0.5, -0.5, 0.3});
    t = same_as_from_nothing("right cluster bent");
    EXPECT_NE(bounds, before);
    EXPECT_EQ(t.clusters_sampled, 1u);
    EXPECT_FALSE(t.grid_rebuilt);
    // Its tip moved 6 down: the longest side grows, and with it the voxel: the grid is voxelized again.
    move_control_point(s, 1, 2, {0.0, -6.0, 0.0});
    t = same_as_from_nothing("right cluster longer");
    EXPECT_TRUE(t.grid_rebuilt);
    // A cook that throws (here: a density calling for more strands than the sampling allows, found after the
    // prototypes were made) leaves the cache as the last cook left it.
    HairStyle dense = s;
    auto d = std::make_shared<DensitySource>(*dense.clusters[0].density);
    d->value = 1e9;
    dense.clusters[0].density = d;
    EXPECT_THROW(cook_shells(dense, test_index(), glm::mat3(1.0f), 0, nullptr, &cache), Error);
    // Undone back to the first style: the right cluster as it was is made again (the cache holds the last cook's only).
    s = test::two_cluster_style(true);
    t = same_as_from_nothing("undone");
    EXPECT_EQ(t.prototypes_made, 1u);
    EXPECT_EQ(t.clusters_sampled, 1u);
    // A deleted cluster: the remaining one's index changes, so its strands are sampled again.
    const std::vector<std::size_t> first{0};
    delete_clusters(s, first);
    t = same_as_from_nothing("left deleted");
    EXPECT_EQ(t.clusters, 1u);
}

TEST(HairAsset, AClusterOfItsOwnLayerCountDrawsAsAStyleOfThatLayoutDoes) {
    // The left cluster with 2 layered shells, the right with the layout's 4 (HairStyle::layout_of): each prototype's
    // meshes and sectors are of its own layout, the asset keeps the counts, and each half of the picture is its cluster
    // as a style whose layout has its count draws it (without the shadows between clusters, which count both
    // clusters' strands; with them the halves are the mixed style's own).
    auto context = gl::Context::headless();
    HairStyle mixed = test::two_cluster_style();
    set_layers(mixed, 0, 2);
    ASSERT_EQ(mixed.layout_of(0).layers, 2);
    ASSERT_EQ(mixed.layout_of(1).layers, 4);
    HairStyle two = test::two_cluster_style();
    two.layout.layers = 2;
    const HairStyle four = test::two_cluster_style();
    const CookedShells m = cook_shells(mixed, test_index(), glm::mat3(1.0f));
    ASSERT_EQ(m.shells.meshes.size(), 2u);
    EXPECT_EQ(m.shells.meshes[0].size(), 2u);
    EXPECT_EQ(m.shells.meshes[1].size(), 4u);
    EXPECT_EQ(m.shells.sectors.size(), 5u * 8u * (2u + 4u));  // (s_t + 1) · s_u per layer
    EXPECT_EQ(m.shells.instances[1].info.x, 5u * 8u * 2u);     // the right cluster's sectors follow the left's
    const std::vector<std::byte> bytes = hair_asset_bytes(m);
    const CookedShells read = parse_hair_asset(bytes, "hair.coif");
    EXPECT_EQ(hair_asset_bytes(read), bytes);
    EXPECT_EQ(read.shells.meshes[0].size(), 2u);
    const CookedShells c4 = cook_shells(four, test_index(), glm::mat3(1.0f));
    const Camera camera = Camera::orbit(c4.shells.bounds_min, c4.shells.bounds_max, 0.0f, 0.1f, 96, 64);
    const auto image = [&](CookedShells c) {
        gl::ShellRenderer r(std::move(c));
        r.set_lights(two_lights());
        gl::ShellSettings s;
        s.samples = 1;
        s.shadows = false;
        return r.render(camera, s);
    };
    const Image a = image(read), b = image(cook_shells(two, test_index(), glm::mat3(1.0f))), d = image(c4);
    // Over each half: the same pixels; and some hair there, differing between the two layouts, or the test shows nothing.
    const auto half = [&](const Image& x, const Image& y, bool left, double* hair = nullptr) {
        double diff = 0, sum = 0;
        for (int py = 0; py < x.height; ++py)
            for (int px = left ? 0 : x.width / 2; px < (left ? x.width / 2 : x.width); ++px)
                for (int ch = 0; ch < 3; ++ch) {
                    diff += std::abs(x.at(px, py)[ch] - y.at(px, py)[ch]);
                    sum += x.at(px, py)[ch];
                }
        if (hair) *hair = sum;
        return diff;
    };
    // Within 1e-6 of the half's radiance: what the whole style shares, the auto fibre radius of its strands' bounds,
    // differs by a rounding between the mixed style and the uniform ones (measured: 0 on the left, 1e-6 on the right).
    double left_hair = 0, right_hair = 0;
    const double left_diff = half(a, b, true, &left_hair), right_diff = half(a, d, false, &right_hair);
    EXPECT_LE(left_diff, 1e-6 * left_hair);
    EXPECT_LE(right_diff, 1e-6 * right_hair);
    EXPECT_GT(left_hair, 0.0);
    EXPECT_GT(right_hair, 0.0);
    EXPECT_GT(half(b, d, true), 0.0) << "2 and 4 layers must draw differently";
}

TEST(HairAsset, RefusesTruncatedCorruptAndOtherVersionFiles) {
    const std::vector<std::byte> good = hair_asset_bytes(cooked());
    EXPECT_EQ(refusal(good), "accepted");
    for (std::size_t n : {std::size_t{0}, std::size_t{7}, std::size_t{31}, std::size_t{32}, good.size() / 2, good.size() - 1}) {
        std::vector<std::byte> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
        EXPECT_NE(refusal(cut).find("truncated"), std::string::npos) << n << ": " << refusal(cut);
    }
    std::vector<std::byte> flipped = good;
    flipped[good.size() / 2] ^= std::byte{0x40};
    EXPECT_NE(refusal(flipped).find("checksum"), std::string::npos) << refusal(flipped);
    std::vector<std::byte> other = good;
    other[8] = std::byte{1};
    EXPECT_NE(refusal(other).find("version 1 (this coif reads version 5"), std::string::npos) << refusal(other);
    std::vector<std::byte> magic = good;
    magic[3] = std::byte{'X'};
    EXPECT_NE(refusal(magic).find("bad magic"), std::string::npos);
    std::vector<std::byte> longer = good;
    longer.resize(good.size() + 8);
    EXPECT_NE(refusal(longer).find("header says"), std::string::npos);
}

TEST(HairAsset, RefusesHostileCountsAndIndicesWithTheChecksumRight) {
    const CookedShells& c = cooked();
    {  // a sector naming a record beyond the atlas
        CookedShells h = c;
        h.shells.sectors[3].id[1] = static_cast<std::uint32_t>(h.atlas.mean_alpha.size());
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("record id outside the atlas"), std::string::npos);
    }
    {  // an index beyond its mesh
        CookedShells h = c;
        h.shells.indices.vector()[5] = 1u << 30;
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("an index outside its mesh"), std::string::npos);
    }
    {  // a NaN in a lighting sample
        CookedShells h = c;
        h.shells.samples[2].tangent.y = std::nanf("");
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("SAMP 2: not finite"), std::string::npos);
    }
    {  // an instance pointing at another prototype's sectors
        CookedShells h = c;
        h.shells.instances[1].info.x += 1;
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("INST 1"), std::string::npos);
    }
    // Skinned: the grid's strands (written for every hair, the key lights' fine grid is made from them) moved with
    // the bone weights.
    CookedShells skinned = c;
    skinned.skinning = StyleSkinning{{"head"}, std::vector<BoneInfluence>(c.shells.clusters())};
    EXPECT_EQ(refusal(hair_asset_bytes(skinned)), "accepted");
    {  // a still hair's asset carries them too
        const CookedShells still = parse_hair_asset(hair_asset_bytes(c), "hair.coif");
        ASSERT_FALSE(c.shadow_source.points.empty());
        EXPECT_TRUE(std::ranges::equal(still.shadow_source.points, c.shadow_source.points));
        EXPECT_TRUE(std::ranges::equal(still.shadow_source.offsets, c.shadow_source.offsets));
        EXPECT_EQ(still.shadow_strand_cluster, c.shadow_strand_cluster);
    }
    {  // a shadow strand of a cluster that is not there
        CookedShells h = skinned;
        h.shadow_strand_cluster[0] = static_cast<std::uint32_t>(h.shells.clusters());
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("SCLU: a cluster index out of range"), std::string::npos);
    }
    {  // shadow strands whose offsets run past their points
        CookedShells h = skinned;
        h.shadow_source.offsets.vector().back() += 1;
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("SOFF"), std::string::npos);
    }
    {  // a NaN root
        CookedShells h = c;
        h.roots[0].z = std::nanf("");
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("ROOT: not finite"), std::string::npos);
    }
    {  // bone weights naming a bone beyond the skeleton, and weights without bones
        CookedShells h = skinned;
        h.skinning->clusters[0].bone.y = 1;
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("SKIN 0"), std::string::npos);
        h.skinning->bones.clear();
        EXPECT_NE(refusal(hair_asset_bytes(h)).find("bone weights and bone names go together"), std::string::npos);
    }
    {  // an absurd element count in the first section after META, checksum resealed
        std::vector<std::byte> b = hair_asset_bytes(c);
        std::uint64_t meta = 0;
        std::memcpy(&meta, b.data() + 32 + 8, 8);
        const std::size_t vert = 32 + 16 + (meta + 7) / 8 * 8;
        const std::uint64_t absurd = 1ull << 40;
        std::memcpy(b.data() + vert + 8, &absurd, 8);
        EXPECT_NE(refusal(resealed(b)).find("absurd element count"), std::string::npos) << refusal(resealed(b));
    }
}

TEST(HairAsset, FileIsWrittenAtomicallyAndReadBack) {
    const auto dir = std::filesystem::temp_directory_path() / ("coif-asset-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    write_hair_asset(dir / "hair.coif", cooked());
    EXPECT_TRUE(is_hair_asset(dir / "hair.coif"));
    const CookedShells r = read_hair_asset(dir / "hair.coif");
    EXPECT_EQ(hair_asset_bytes(r), hair_asset_bytes(cooked()));
    EXPECT_THROW((void)read_hair_asset(dir / "missing.coif"), Error);
    // The large arrays are viewed in the mapping, not copied (how the asset loads fast: docs/renderer.md), and the
    // mapping outlives the file's name: a re-bake replaces the file atomically while a renderer still reads it.
    EXPECT_TRUE(r.shells.vertices.viewed() && r.shells.indices.viewed() && r.atlas.texels.viewed() &&
                r.grid.diagonal_xy.viewed() && r.grid.off_diagonal.viewed() && r.shadow_source.points.viewed() &&
                r.shadow_source.offsets.viewed());
    EXPECT_FALSE(parse_hair_asset(hair_asset_bytes(cooked()), "hair.coif").shells.vertices.viewed())
        << "bytes without an owner are copied";
    write_hair_asset(dir / "hair.coif", cooked());
    {
        auto context = gl::Context::headless();
        EXPECT_EQ(draw(r).pixels, draw(cooked()).pixels);
    }
    // Only the file itself is left: no temporaries.
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
    EXPECT_EQ(files, 1u);
    std::filesystem::remove_all(dir);
    // The fuzz target's seed (tests/fuzz/corpus/hair_asset/), written when asked: a valid asset kept small, one
    // cluster of one layer with one record and a 2 × 2 × 2 shadow grid.
    if (const char* seed = std::getenv("COIF_WRITE_HAIR_ASSET_SEED")) {
        HairStyle tiny = parse_style(R"({"format": "coif-style", "version": 1,
          "layout": {"core_radius": 0.2, "layers": 1, "s_t": 1, "s_u": 3, "grid": [2, 2], "mesh": [1, 1], "gaussian_width": 0.05},
          "clusters": [{"name": "c0", "trajectory": [[0, 0, 0], [0, -10, 0]], "a": [1.0], "b": [1.0],
                        "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}}]})", "<tiny>");
        CookedShells t = cook_shells(tiny, test_index(), glm::mat3(1.0f));
        for (ShellSector& q : t.shells.sectors) q.id = glm::uvec4(0);
        const float a0 = t.atlas.mean_alpha[0], m0 = t.atlas.mean_a0[0];
        const RecordAtlas& a = t.atlas;
        t.atlas = pack_atlas(1, a.views, a.hrir_length, a.lo, a.scale, [&](std::size_t, int, int) {
            AtlasTexels v{};
            for (int i = 0; i < 4 * kAtlasParts; ++i) v[i] = a.lo[i / 4][i % 4] + 0.5f * a.scale[i / 4][i % 4];
            return v;
        });
        t.atlas.mean_alpha = {a0};
        t.atlas.mean_a0 = {m0};
        t.atlas.re_norm = cooked().atlas.re_norm;
        t.grid.dims = glm::ivec3(2);
        t.grid.diagonal_xy.vector().assign(8, glm::vec4(1.0f, 1.0f, 1.0f, 0.0f));
        t.grid.off_diagonal.vector().assign(8, glm::vec2(0.0f));
        // Two shadow strands of two points, and the cluster skinned to one bone.
        t.shadow_source.points =
            std::vector<glm::vec3>{glm::vec3(0.0f), glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(0.5f), glm::vec3(0.5f, -1.0f, 0.5f)};
        t.shadow_source.offsets = std::vector<std::uint32_t>{0, 2, 4};
        t.shadow_strand_cluster = {0, 0};
        t.shadow_strands = 2;
        BoneInfluence on_head;
        on_head.weight = {1, 0, 0, 0};
        t.skinning = StyleSkinning{{"head"}, {on_head}};
        write_hair_asset(seed, t);
    }
}

}  // namespace
}  // namespace coif
