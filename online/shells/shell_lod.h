#pragma once
// Level of detail of the shells' tessellation (issue 18), GL-free. A layer mesh is a grid of rows along t and columns
// around (models/generalized_disk.h layer_mesh, the seam's column duplicated), so a coarser mesh is the same vertices
// joined by every s-th row and column: only its triangle list differs, and the shading (which reads t and u from the
// vertices) is unchanged at the vertices kept. Each cluster is drawn per frame at the coarsest level whose longest
// triangle edge projects within ShellSettings::lod_pixels, with hysteresis so that a camera moving back and forth
// across a threshold does not switch levels every frame.
//
// Levels: 0 the full grid; level k joins every 2^k-th row, and every 2^k-th column while at least kLodMinColumns
// segments stay around (fewer make a polygon of a ring: its silhouette would show). The last row and column are always
// kept, so any grid size works.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "online/shells/prepared_shells.h"

namespace coif {

inline constexpr int kLodLevels = 3;
inline constexpr int kLodMinColumns = 8;
// A coarser level is taken only when its edge projects within this share of lod_pixels; a finer one as soon as the
// current level's edge exceeds lod_pixels: a band of 20 % in which the level stays.
inline constexpr float kLodHysteresis = 0.8f;

// Level k's stride of a rows × columns layer grid (models/generalized_disk.h grid_triangles joins it).
GridStride lod_stride(int level, int rows, int columns);
// Its stride along t alone (which does not depend on the columns): the rows 0, stride, 2·stride, … and the last.
int lod_row_stride(int level, int rows);

// Every prototype's layer meshes at each level, in one index array: level 0's ranges are the shells' own (the array
// starts with shells.indices), the coarser levels' follow.
struct LodMeshes {
    std::vector<std::uint32_t> indices;
    std::vector<std::vector<std::array<MeshRange, kLodLevels>>> ranges;  // [slot][layer][level]
    // [slot][level]: the longest edge of the outer layer's triangles along t or around, in the prototype's coordinates
    // (a cluster's is this times its instance's scale).
    std::vector<std::array<float, kLodLevels>> edge;
};
// Throws coif::Error::parameter if a mesh is not the grid of its prototype's layout (layer_mesh's rows × columns).
LodMeshes lod_meshes(const PreparedShells& shells);

// The level to draw, from each level's longest edge in pixels (`edge_px`, growing with the level), the level drawn last
// (`current`) and the budget: the coarsest level within `budget_px` (within kLodHysteresis · budget_px when coarser than
// the current one). A budget ≤ 0 draws level 0.
int pick_lod(std::span<const float, kLodLevels> edge_px, int current, float budget_px);

}  // namespace coif
