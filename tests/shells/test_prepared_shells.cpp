// The shell renderer's GL-free half (online/shells/): the scene preparation and the record atlas, checked on
// the CPU without a GL context.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/quaternion.hpp>

#include "db/coverage.h"
#include "db/hrir_db.h"
#include "models/core/error.h"
#include "models/sector_features.h"
#include "online/shells/prepared_shells.h"
#include "online/shells/record_atlas.h"
#include "online/scene/cook.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

using test::one_cluster_style;
using test::prototype_and_instance;
using test::test_db;
using test::test_index;


const RecordAtlas& test_atlas() {
    static const RecordAtlas atlas = pack_record_atlas(test_db());
    return atlas;
}

TEST(PreparedShells, OneClusterHasEveryLayerSectorAndLightingRow) {
    const HairStyle style = one_cluster_style();
    const PreparedShells p = prepare_shells(style, test_index(), test_atlas().mean_alpha, glm::mat3(1.0f));
    const DiskLayout& L = style.layout;
    ASSERT_EQ(p.prototypes.size(), 1u);
    ASSERT_EQ(p.clusters(), 1u);
    ASSERT_EQ(p.meshes[0].size(), static_cast<std::size_t>(L.layers));
    EXPECT_EQ(p.sectors.size(), L.sector_count());
    EXPECT_EQ(p.triangles * 3, p.indices.size());
    EXPECT_EQ(p.lighting_rows, L.s_t * L.mesh_t + 1);  // one lighting row per mesh row by default
    EXPECT_EQ(p.samples.size(), static_cast<std::size_t>(p.lighting_rows));
    // Every mesh range lies inside the shared arrays, one after the other.
    std::size_t indices = 0;
    for (const MeshRange& r : p.meshes[0]) {
        EXPECT_EQ(r.first, indices);
        indices += static_cast<std::size_t>(r.count);
        EXPECT_LE(static_cast<std::size_t>(r.base_vertex + r.vertex_count), p.vertices.size());
    }
    EXPECT_EQ(indices, p.indices.size());
    // The lighting samples run root → tip along the axis (0, 0, 0) → (0, −10, 0), radius 1 (the ellipse's a, b).
    EXPECT_NEAR(glm::distance(glm::vec3(p.samples.front().position), glm::vec3(0.0f)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::distance(glm::vec3(p.samples.back().position), glm::vec3(0.0f, -10.0f, 0.0f)), 0.0f, 1e-4f);
    EXPECT_NEAR(p.samples.front().position.w, 1.0f, 1e-5f);  // the cross-section's half-axes A, B and its turn θ
    EXPECT_NEAR(p.samples.front().tangent.w, 1.0f, 1e-5f);
    EXPECT_NEAR(p.samples.front().normal.w, 0.0f, 1e-6f);
    EXPECT_NEAR(p.samples.front().tangent.y, -1.0f, 1e-4f);
    EXPECT_NEAR(glm::distance(p.cluster_centre[0], glm::vec3(0.0f, -5.0f, 0.0f)), 0.0f, 1e-4f);
    // The outer layer's bounds: the cylinder of radius 1 around the axis, as a polygon of 16 sides
    // (cos(π/16) = 0.98 at worst between its corners).
    EXPECT_GE(p.bounds_max.x, 0.98f);
    EXPECT_LE(p.bounds_max.x, 1.0f + 1e-4f);
    EXPECT_LE(p.bounds_min.x, -0.98f);
    EXPECT_GE(p.bounds_min.x, -1.0f - 1e-4f);
    EXPECT_NEAR(p.bounds_min.y, -10.0f, 1e-3f);
    EXPECT_NEAR(p.bounds_max.y, 0.0f, 1e-3f);
}

TEST(PreparedShells, SectorLookupsAreBestFirstAndShadowSumsGrowInwards) {
    const HairStyle style = one_cluster_style();
    const PreparedShells p = prepare_shells(style, test_index(), test_atlas().mean_alpha, glm::mat3(1.0f));
    const DiskLayout& L = style.layout;
    for (const ShellSector& s : p.sectors) {
        for (int n = 0; n < gl::kMaxShellNeighbours; ++n) {
            EXPECT_LT(s.id[n], test_db().size());
            EXPECT_GE(s.weight[n], 0.0f);
            if (n > 0) {
                EXPECT_LE(s.weight[n], s.weight[n - 1]);
            }
        }
        EXPECT_GT(s.weight[0], 0.0f);
    }
    // 004 eq. 12: the outermost layer has nothing outside it; each layer further in adds the mean α of the
    // layer just outside it (a uniform density: the same every plane and sector, so strictly more inwards).
    for (int i = 0; i <= L.s_t; ++i)
        for (int k = 0; k < L.s_u; ++k) {
            EXPECT_EQ(p.sectors[L.sector_index(i, L.layers - 1, k)].shadow.x, 0.0f);
            for (int j = L.layers - 2; j >= 0; --j) {
                const float inner = p.sectors[L.sector_index(i, j, k)].shadow.x;
                const float outer = p.sectors[L.sector_index(i, j + 1, k)].shadow.x;
                EXPECT_GT(inner, outer) << "plane " << i << " layer " << j << " sector " << k;
                // The step is the outer sector's mean α over its look-up: Σ w ᾱ of a weight sum of at most 1.
                EXPECT_LE(inner - outer, 1.0f + 1e-5f);
            }
        }
}

// The records of a denser sector are thinned to the sector's own density (cook.h sector_thinning): c is the sector's
// mean density over its records' (weighted as the look-up weighs them), at most 1; the shadow sums are of the thinned
// mean α. A style of the same shape at a tenth of the density is looked up again: its sectors' records cannot be
// sparser than the database's sparsest, so every c falls, and the sums with it.
TEST(PreparedShells, RecordsAreThinnedToTheirSectorsDensity) {
    const auto density_of = [](double value) {
        const std::string text = R"({"format": "coif-style", "version": 1,
          "layout": {"core_radius": 0.2, "layers": 3, "s_t": 2, "s_u": 4, "grid": [8, 4], "mesh": [2, 2], "gaussian_width": 0.05},
          "clusters": [{"name": "c0", "trajectory": [[0, 0, 0], [0, -5, 0], [0, -10, 0]], "a": [1.0], "b": [1.0],
                        "theta_deg": [0], "density": {"kind": "uniform", "value": )" + std::to_string(value) + "}}]}";
        return parse_style(text, "<density " + std::to_string(value) + ">");
    };
    for (const double value : {0.5, 0.02}) {
        const HairStyle style = density_of(value);
        const PreparedShells p = prepare_shells(style, test_index(), test_atlas().mean_alpha, glm::mat3(1.0f));
        // The same look-ups, from the style's sector features (db/coverage.h, the rows the cook looks up).
        const DiskLayout& L = style.layout;
        const std::vector<float> rows = style_sector_features(style);
        const std::vector<SectorMatch> matches = test_index().match_all(rows);
        ASSERT_EQ(matches.size(), p.sectors.size());
        std::vector<double> thinned(p.sectors.size());  // each sector's thinned mean α
        double c_sum = 0;
        for (std::size_t s = 0; s < p.sectors.size(); ++s) {
            const SectorMatch& m = matches[s];
            double record = 0, weights = 0, alpha = 0;
            for (int n = 0; n < m.k; ++n) {
                record += m.weight[n] * test_db().features(m.id[n])[kMeanDensityColumn];
                alpha += m.weight[n] * test_atlas().mean_alpha[m.id[n]];
                weights += m.weight[n];
            }
            const double c = std::clamp(rows[s * kRawFeatureCount + kMeanDensityColumn] / (record / weights), 0.0, 1.0);
            EXPECT_NEAR(p.sectors[s].shadow.z, c, 1e-5) << "density " << value << ", sector " << s;
            thinned[s] = 1.0 - std::pow(1.0 - alpha, c);
            c_sum += c;
        }
        // 004 eq. 12's sums, of the thinned mean α: the layers outside (x) and every layer (y).
        for (int i = 0; i <= L.s_t; ++i)
            for (int k = 0; k < L.s_u; ++k) {
                double outer = 0;
                for (int j = L.layers - 1; j >= 0; --j) {
                    const std::size_t s = L.sector_index(i, j, k);
                    EXPECT_NEAR(p.sectors[s].shadow.x, outer, 1e-5);
                    outer += thinned[s];
                }
                EXPECT_NEAR(p.sectors[L.sector_index(i, 0, k)].shadow.y, outer, 1e-5);
            }
        const double mean_c = c_sum / static_cast<double>(p.sectors.size());
        std::printf("density %.2f: the records' mean thinning c %.3f over %zu sectors\n", value, mean_c, p.sectors.size());
        if (value < 0.1) {
            EXPECT_LT(mean_c, 0.5);  // a twenty-fifth of the density: thinned
        }
    }
    EXPECT_EQ(thinned_alpha(0.5f, 1.0f), 0.5f);
    EXPECT_NEAR(thinned_alpha(0.5f, 0.5f), 1.0f - std::sqrt(0.5f), 1e-6f);
    EXPECT_EQ(thinned_alpha(0.7f, 0.0f), 0.0f);
}

TEST(PreparedShells, InstancesShareTheirPrototypeAndFollowTheirPlacement) {
    const HairStyle style = prototype_and_instance();
    const PreparedShells p = prepare_shells(style, test_index(), test_atlas().mean_alpha, glm::mat3(1.0f));
    ASSERT_EQ(p.clusters(), 2u);
    EXPECT_EQ(p.prototypes.size(), 1u);  // one set of meshes and sectors
    EXPECT_EQ(p.cluster_proto[0], p.cluster_proto[1]);
    EXPECT_EQ(p.instances[0].info.x, p.instances[1].info.x);  // the same first sector
    EXPECT_EQ(p.instances[1].info.y, 1u);
    EXPECT_EQ(p.cluster_ids, (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(p.samples.size(), 2u * static_cast<std::size_t>(p.lighting_rows));
    // The instance's axis is the prototype's moved by 5 along x (a turn about y leaves the vertical axis).
    const LightingSample& tip = p.samples[2 * static_cast<std::size_t>(p.lighting_rows) - 1];
    EXPECT_NEAR(glm::distance(glm::vec3(tip.position), glm::vec3(5.0f, -10.0f, 0.0f)), 0.0f, 1e-4f);
    EXPECT_GE(p.bounds_max.x, 5.98f);
    EXPECT_LE(p.bounds_max.x, 6.0f + 1e-4f);
}

TEST(PreparedShells, LightingSamplesCarryTheCrossSectionsEllipse) {
    // A flat cluster (A 2, B 0.5) whose ellipse turns by 90° from root to tip, placed by an instance turned 90° about y
    // and scaled by 1.5: each sample's e1 as the shadow pass builds it, cos θ n + sin θ (t × n), is the placed shape's
    // own first ellipse axis, and A, B are in world units (shaders/gl/shell_shadow.comp, own_cluster_exit).
    const char* text = R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 4, "s_t": 4, "s_u": 8, "grid": [8, 4], "mesh": [2, 2], "gaussian_width": 0.05},
      "clusters": [{"name": "c0", "trajectory": [[0, 0, 0], [1, -5, 0], [0, -10, 1]], "a": [2.0], "b": [0.5],
                    "theta_deg": [0, 45, 90], "density": {"kind": "uniform", "value": 0.5}},
                   {"name": "c1", "instance_of": "c0",
                    "transform": {"scale": 1.5, "rotation": [0.70710678, 0, 0.70710678, 0], "translation": [5, 0, 0]}}]})";
    const HairStyle style = parse_style(text, "<flat cluster>");
    const PreparedShells p = prepare_shells(style, test_index(), test_atlas().mean_alpha, glm::mat3(1.0f));
    ASSERT_EQ(p.clusters(), 2u);
    const std::size_t rows = static_cast<std::size_t>(p.lighting_rows);
    for (std::size_t c = 0; c < 2; ++c) {
        const Cluster& cl = style.clusters[c];
        const glm::mat3 turn = glm::mat3_cast(glm::quat(cl.placement.rotation));
        for (std::size_t r = 0; r < rows; ++r) {
            const LightingSample& q = p.samples[c * rows + r];
            const double t = static_cast<double>(r) / static_cast<double>(rows - 1);
            const glm::vec3 e1 = q.ellipse_axis();
            const glm::vec3 want = glm::normalize(turn * glm::vec3(cl.shape->ellipse_axes(t)[0]));
            EXPECT_NEAR(glm::distance(e1, want), 0.0f, 1e-4f) << c << " " << r;
            EXPECT_NEAR(q.position.w, cl.placement.scale * 2.0, 1e-5) << c << " " << r;
            EXPECT_NEAR(q.tangent.w, cl.placement.scale * 0.5, 1e-5) << c << " " << r;
        }
    }
}

TEST(PreparedShells, PlacingAgainMovesOnlyTheClusters) {
    // The motion seam: a new orientation re-runs place_clusters only; meshes and look-ups stay.
    const HairStyle style = one_cluster_style();
    PreparedShells p = prepare_shells(style, test_index(), test_atlas().mean_alpha, glm::mat3(1.0f));
    const std::vector<ShellVertex> vertices(p.vertices.begin(), p.vertices.end());
    const std::vector<ShellSector> sectors = p.sectors;
    const glm::mat3 turn = glm::mat3_cast(glm::angleAxis(1.5707963f, glm::vec3(0.0f, 0.0f, 1.0f)));  // −y → +x
    place_clusters(p, style, turn, 0);
    EXPECT_EQ(p.vertices.size(), vertices.size());
    EXPECT_EQ(std::memcmp(p.sectors.data(), sectors.data(), sectors.size() * sizeof(ShellSector)), 0);
    EXPECT_NEAR(glm::distance(glm::vec3(p.samples.back().position), glm::vec3(10.0f, 0.0f, 0.0f)), 0.0f, 1e-4f);
    EXPECT_NEAR(p.samples.back().tangent.x, 1.0f, 1e-4f);
    EXPECT_NEAR(p.bounds_max.x, 10.0f, 1e-3f);
    // More lighting rows per HSV: the samples follow.
    place_clusters(p, style, glm::mat3(1.0f), 3);
    EXPECT_EQ(p.lighting_rows, style.layout.s_t * 3 + 1);
    EXPECT_EQ(p.samples.size(), static_cast<std::size_t>(p.lighting_rows));
    EXPECT_THROW(place_clusters(p, style, glm::mat3(1.0f), -1), Error);
    EXPECT_THROW(place_clusters(p, style, glm::mat3(1.0f), kMaxMeshSubdivision + 1), Error);
}

TEST(PreparedShells, RefusesAStyleWithoutClusters) {
    HairStyle empty = one_cluster_style();
    empty.clusters.clear();
    EXPECT_THROW(prepare_shells(empty, test_index(), test_atlas().mean_alpha, glm::mat3(1.0f)), Error);
}

TEST(PreparedShells, StyleOrientationTurnsTheHangAxisDown) {
    // The test style already hangs along −y: identity.
    const glm::mat3 r = style_orientation(one_cluster_style());
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(r[i][j], i == j ? 1.0f : 0.0f, 1e-6f);
}

TEST(RecordAtlas, HoldsEveryRecordWithinItsQuantisation) {
    const HrirDatabase& db = test_db();
    const RecordAtlas& a = test_atlas();
    const AngleGrids& g = db.params().grids;
    ASSERT_EQ(a.texels.size(), static_cast<std::size_t>(a.width) * a.height * 4);
    ASSERT_EQ(a.mean_alpha.size(), db.size());
    double sum_alpha = 0, sum_a0 = 0;
    for (std::size_t rec = 0; rec < db.size(); ++rec) {
        const std::vector<float> r = db.record(rec);
        double sa = 0;
        for (int v = 0; v < g.views; ++v)
            for (int x = 0; x < g.hrir_length; ++x) {
                // 8-bit unorm with a per-part, per-channel range: half a step of rounding at most.
                const float tol0 = 0.5f * a.scale[0][0] / 255.0f + 1e-6f, tol1 = 0.5f * a.scale[0][1] / 255.0f + 1e-6f;
                EXPECT_NEAR(a.value(rec, 0, 0, v, x), r[g.alpha_offset(v) + x], tol0);
                EXPECT_NEAR(a.value(rec, 0, 1, v, x), r[g.re_offset(v, 0) + x], tol1);
                sa += r[g.alpha_offset(v) + x];
            }
        EXPECT_NEAR(a.mean_alpha[rec], sa / (g.views * g.hrir_length), 1e-5);
        sum_alpha += a.mean_alpha[rec];
        sum_a0 += a.mean_a0[rec];
    }
    EXPECT_NEAR(a.re_norm, sum_a0 / sum_alpha, 1e-5);
}

TEST(RecordAtlas, BordersArePeriodic) {
    // One texel outside a tile repeats the opposite edge, so the bilinear fetch wraps x and θv.
    const RecordAtlas& a = test_atlas();
    const int X = a.hrir_length, V = a.views;
    for (std::size_t rec : {std::size_t{0}, test_db().size() - 1})
        for (int part = 0; part < kAtlasParts; ++part)
            for (int ch = 0; ch < 4; ++ch) {
                EXPECT_EQ(a.value(rec, part, ch, 3, -1), a.value(rec, part, ch, 3, X - 1));
                EXPECT_EQ(a.value(rec, part, ch, 3, X), a.value(rec, part, ch, 3, 0));
                EXPECT_EQ(a.value(rec, part, ch, -1, 5), a.value(rec, part, ch, V - 1, 5));
                EXPECT_EQ(a.value(rec, part, ch, V, 5), a.value(rec, part, ch, 0, 5));
            }
}

// lighting_step_within: lighting samples along a straight axis may all be skipped but the ends; an axis that bends by
// 10° at every other sample (a kink per HSV row) puts each skipped sample 10° from the interpolation, more than the 4°
// bound, so the step stays 1; a wider bound lets it skip.
TEST(PreparedShells, LightingStepFollowsTheAxisCurvature) {
    PreparedShells p;
    p.lighting_rows = 33;
    const auto add = [&](bool curled) {
        for (int r = 0; r < p.lighting_rows; ++r) {
            const float a = curled && r % 2 == 1 ? 0.174533f : 0.0f;  // 10°
            LightingSample s;
            s.tangent = glm::vec4(std::sin(a), std::cos(a), 0.0f, 0.0f);
            p.samples.push_back(s);
        }
    };
    const float four_degrees = 4.0f * 3.14159265f / 180.0f;
    add(false);
    EXPECT_EQ(lighting_step_within(p, 32, four_degrees), 32);
    EXPECT_EQ(lighting_step_within(p, 3, four_degrees), 2);  // the largest divisor of 32 up to 3
    add(true);  // the second cluster bends: the step of the whole style follows it
    std::vector<float> worst;
    EXPECT_EQ(lighting_step_within(p, 32, four_degrees, &worst), 1);
    ASSERT_EQ(worst.size(), 1u);
    EXPECT_NEAR(worst[0], 0.174533f, 1e-4f);
    EXPECT_EQ(lighting_step_within(p, 32, 0.2f), 32);
}

}  // namespace
}  // namespace coif
