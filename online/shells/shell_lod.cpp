#include "online/shells/shell_lod.h"

#include <algorithm>
#include <string>

#include "models/core/error.h"

namespace coif {

GridStride lod_stride(int level, int rows, int columns) {
    GridStride s;
    s.t = lod_row_stride(level, rows);
    for (int k = 0; k < level; ++k)
        if ((columns - 1) / (2 * s.u) >= kLodMinColumns) s.u *= 2;
    return s;
}

int lod_row_stride(int level, int rows) {
    int t = 1;
    for (int k = 0; k < level; ++k)
        if ((rows - 1) / (2 * t) >= 1) t *= 2;
    return t;
}

LodMeshes lod_meshes(const PreparedShells& shells) {
    LodMeshes m;
    m.indices.assign(shells.indices.data(), shells.indices.data() + shells.indices.size());
    m.ranges.resize(shells.meshes.size());
    m.edge.resize(shells.meshes.size());
    for (std::size_t slot = 0; slot < shells.meshes.size(); ++slot) {
        const DiskLayout L = shells.layout_of_slot(slot);
        const int rows = L.s_t * L.mesh_t + 1, columns = L.s_u * L.mesh_u + 1;
        const std::vector<MeshRange>& layers = shells.meshes[slot];
        m.ranges[slot].resize(layers.size());
        std::array<std::vector<std::uint32_t>, kLodLevels> coarse;  // each level's triangles, the same for every layer
        for (int level = 1; level < kLodLevels; ++level)
            coarse[static_cast<std::size_t>(level)] = grid_triangles(rows, columns, lod_stride(level, rows, columns));
        for (std::size_t j = 0; j < layers.size(); ++j) {
            const MeshRange& full = layers[j];
            if (full.vertex_count != rows * columns)
                throw Error::parameter("shells", "prototype slot " + std::to_string(slot) + " layer " + std::to_string(j) + " has " +
                                                     std::to_string(full.vertex_count) + " vertices, not its layout's " +
                                                     std::to_string(rows) + " x " + std::to_string(columns));
            m.ranges[slot][j][0] = full;
            for (int level = 1; level < kLodLevels; ++level) {
                const std::vector<std::uint32_t>& tri = coarse[static_cast<std::size_t>(level)];
                MeshRange r = full;
                r.first = static_cast<std::uint32_t>(m.indices.size());
                r.count = static_cast<std::int32_t>(tri.size());
                m.indices.insert(m.indices.end(), tri.begin(), tri.end());
                m.ranges[slot][j][static_cast<std::size_t>(level)] = r;
            }
        }
        // The outer layer's longest edge at each level: along t between kept rows, around between kept columns.
        const MeshRange& outer = layers.back();
        const auto at = [&](int row, int column) {
            return shells.vertices[static_cast<std::size_t>(outer.base_vertex + row * columns + column)].position;
        };
        for (int level = 0; level < kLodLevels; ++level) {
            const GridStride s = lod_stride(level, rows, columns);
            const std::vector<int> r = strided(rows, s.t), q = strided(columns, s.u);
            float longest = 0.0f;
            for (std::size_t a = 0; a < r.size(); ++a)
                for (std::size_t b = 0; b < q.size(); ++b) {
                    if (a + 1 < r.size()) longest = std::max(longest, glm::distance(at(r[a], q[b]), at(r[a + 1], q[b])));
                    if (b + 1 < q.size()) longest = std::max(longest, glm::distance(at(r[a], q[b]), at(r[a], q[b + 1])));
                }
            m.edge[slot][static_cast<std::size_t>(level)] = longest;
        }
    }
    return m;
}

int pick_lod(std::span<const float, kLodLevels> edge_px, int current, float budget_px) {
    int level = 0;
    if (!(budget_px > 0.0f)) return level;
    for (int k = 1; k < kLodLevels; ++k)
        if (edge_px[static_cast<std::size_t>(k)] <= budget_px * (k > current ? kLodHysteresis : 1.0f)) level = k;
    return level;
}

}  // namespace coif
