// The shells' level of detail (online/shells/shell_lod.h), GL-free: coarser meshes are the full grid's vertices on
// every s-th row and column, covering the same surface; the level picked follows the projected edge with hysteresis.
#include <gtest/gtest.h>

#include <cmath>

#include "models/generalized_disk.h"
#include "online/shells/shell_lod.h"

namespace coif {
namespace {

TEST(ShellLod, CoarserMeshesJoinEverySthRowAndColumnOfTheSameGrid) {
    // Stride (1, 1) is layer_mesh's own triangle list.
    DiskLayout layout;
    layout.s_t = 4, layout.s_u = 8, layout.mesh_t = 2, layout.mesh_u = 2, layout.layers = 2;
    const GeneralizedCylinder g(Spline3({{0, 0, 0}, {0, -5, 1}, {1, -10, 0}}), Spline1({1.0, 0.6}), Spline1({0.8}), Spline1({0.2}));
    const LayerMesh m = layer_mesh(g, layout, 1);
    EXPECT_EQ(grid_triangles(m.rows, m.columns, GridStride{}), m.indices);
    // 9 rows × 17 columns: level 1 joins every 2nd row and column; level 2 every 4th row, and keeps 8 segments around.
    EXPECT_EQ(lod_stride(0, 9, 17).t, 1);
    EXPECT_EQ(lod_stride(1, 9, 17).t, 2);
    EXPECT_EQ(lod_stride(1, 9, 17).u, 2);
    EXPECT_EQ(lod_stride(2, 9, 17).t, 4);
    EXPECT_EQ(lod_stride(2, 9, 17).u, 2);
    EXPECT_EQ(lod_stride(2, 2, 9).t, 1);  // one segment along t stays one
    EXPECT_EQ(lod_stride(2, 2, 9).u, 1);  // 8 segments around stay 8
    // The last row and column are kept whatever the stride: every level covers the whole (u, t) square once. Summed
    // in the vertices' texture coordinates (u/2π, t), the triangles' areas are 1, each counter-clockwise (positive).
    for (const auto& [rows, columns] : {std::pair{9, 17}, std::pair{10, 7}, std::pair{33, 17}})
        for (const GridStride& s : {GridStride{1, 1}, GridStride{2, 2}, GridStride{4, 2}, GridStride{4, 4}}) {
            const std::vector<std::uint32_t> tri = grid_triangles(rows, columns, s);
            double area = 0;
            for (std::size_t i = 0; i < tri.size(); i += 3) {
                const auto uv = [&](std::uint32_t v) {
                    return glm::dvec2(double(v % columns) / (columns - 1), double(v / columns) / (rows - 1));
                };
                const glm::dvec2 a = uv(tri[i]), b = uv(tri[i + 1]), c = uv(tri[i + 2]);
                const double twice = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
                ASSERT_GT(twice, 0.0) << rows << "x" << columns << " stride " << s.t << "," << s.u;
                area += 0.5 * twice;
            }
            EXPECT_NEAR(area, 1.0, 1e-12) << rows << "x" << columns << " stride " << s.t << "," << s.u;
        }
    EXPECT_EQ(strided(10, 4), (std::vector<int>{0, 4, 8, 9}));
    EXPECT_EQ(strided(9, 4), (std::vector<int>{0, 4, 8}));
}

TEST(ShellLod, TheLevelFollowsTheProjectedEdgeWithHysteresis) {
    // Edges of 1, 2 and 4 units at levels 0, 1, 2, seen at p pixels per unit; a budget of 10 px.
    const auto at = [](float p) { return std::array<float, kLodLevels>{p, 2 * p, 4 * p}; };
    EXPECT_EQ(pick_lod(at(20.0f), 0, 10.0f), 0);
    EXPECT_EQ(pick_lod(at(2.0f), 0, 10.0f), 2);
    EXPECT_EQ(pick_lod(at(2.0f), 0, 0.0f), 0);  // no budget: full detail
    // Moving away (p falling) from level 0: coarser only once within 80 % of the budget.
    EXPECT_EQ(pick_lod(at(4.5f), 0, 10.0f), 0);  // level 1's edge 9 px > 8
    EXPECT_EQ(pick_lod(at(3.9f), 0, 10.0f), 1);  // 7.8 px
    // Back and forth by a few per cent about a threshold: the level stays.
    int level = 1;
    for (int i = 0; i < 20; ++i) {
        level = pick_lod(at(i % 2 ? 4.6f : 4.3f), level, 10.0f);
        EXPECT_EQ(level, 1) << i;
    }
    // Coming nearer: finer as soon as the level's edge exceeds the budget.
    EXPECT_EQ(pick_lod(at(5.1f), 1, 10.0f), 0);
    EXPECT_EQ(pick_lod(at(2.4f), 2, 10.0f), 2);  // 9.6 px within the budget
    EXPECT_EQ(pick_lod(at(2.6f), 2, 10.0f), 1);  // 10.4 px
}

}  // namespace
}  // namespace coif
