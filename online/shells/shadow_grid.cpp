#include "online/shells/shadow_grid.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>

#include "models/core/error.h"

namespace coif {

float projected_length_density(glm::vec4 m, glm::vec2 o, glm::vec3 w) {
    const float trace = m.x + m.y + m.z;
    const float along = m.x * w.x * w.x + m.y * w.y * w.y + m.z * w.z * w.z + 2.0f * (m.w * w.x * w.y + o.x * w.x * w.z + o.y * w.y * w.z);
    return std::sqrt(std::max(trace * (trace - along), 0.0f));
}

float DensityGrid::length_density(int x, int y, int z) const {
    const glm::vec4 m = diagonal_xy[index(x, y, z)];
    return m.x + m.y + m.z;
}

float DensityGrid::projected(glm::vec3 p, glm::vec3 omega) const {
    const glm::vec3 g = (p - origin) / voxel - 0.5f;
    const glm::ivec3 i0 = glm::ivec3(glm::floor(g));
    const glm::vec3 f = g - glm::vec3(i0);
    glm::vec4 m(0.0f);
    glm::vec2 o(0.0f);
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 i = i0 + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        if (glm::any(glm::lessThan(i, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(i, dims))) continue;
        const float w = ((c & 1) ? f.x : 1 - f.x) * ((c & 2) ? f.y : 1 - f.y) * ((c & 4) ? f.z : 1 - f.z);
        m += w * diagonal_xy[index(i.x, i.y, i.z)];
        o += w * off_diagonal[index(i.x, i.y, i.z)];
    }
    return projected_length_density(m, o, omega);
}

float DensityGrid::integrate(glm::vec3 p, glm::vec3 d, float length, float step) const {
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    const float h = length / n;
    double sum = 0;
    for (int k = 0; k < n; ++k) sum += projected(p + d * ((k + 0.5f) * h), d);
    return static_cast<float>(sum * h);
}

DensityGrid voxelize_strands(const Strands& strands, const glm::mat3& orientation, int max_dim) {
    if (strands.points.empty()) throw Error::parameter("shadow grid", "the style gives no strands to voxelize");
    if (max_dim < 8 || max_dim > 512) throw Error::parameter("shadow grid", "voxels along the longest axis must be 8..512");
    std::vector<glm::vec3> p(strands.points.size());
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (std::size_t i = 0; i < p.size(); ++i) {
        p[i] = orientation * strands.points[i];
        lo = glm::min(lo, p[i]);
        hi = glm::max(hi, p[i]);
    }
    DensityGrid g;
    g.strands_min = lo;
    g.strands_max = hi;
    const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-6f));
    const float longest = std::max({size.x, size.y, size.z});
    g.voxel = longest / static_cast<float>(max_dim - 4);
    g.dims = glm::min(glm::ivec3(glm::ceil(size / g.voxel)) + 4, glm::ivec3(max_dim));
    g.origin = 0.5f * (lo + hi) - 0.5f * g.extent();
    const std::size_t voxels = static_cast<std::size_t>(g.dims.x) * g.dims.y * g.dims.z;
    std::vector<glm::vec4>& diagonal_xy = g.diagonal_xy.vector();
    std::vector<glm::vec2>& off_diagonal = g.off_diagonal.vector();
    diagonal_xy.assign(voxels, glm::vec4(0.0f));
    off_diagonal.assign(voxels, glm::vec2(0.0f));
    const float per_volume = 1.0f / (g.voxel * g.voxel * g.voxel);
    // One sub-segment of length `length` along the unit tangent t at q: ℓ t tᵀ / V spread over 8 voxels.
    const auto splat = [&](glm::vec3 q, glm::vec3 t, float length) {
        const float l = length * per_volume;
        const glm::vec4 m = l * glm::vec4(t.x * t.x, t.y * t.y, t.z * t.z, t.x * t.y);
        const glm::vec2 o = l * glm::vec2(t.x * t.z, t.y * t.z);
        const glm::vec3 f0 = (q - g.origin) / g.voxel - 0.5f;
        const glm::ivec3 i0 = glm::ivec3(glm::floor(f0));
        const glm::vec3 f = f0 - glm::vec3(i0);
        for (int c = 0; c < 8; ++c) {
            const glm::ivec3 i = i0 + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            if (glm::any(glm::lessThan(i, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(i, g.dims))) continue;
            const float w = ((c & 1) ? f.x : 1 - f.x) * ((c & 2) ? f.y : 1 - f.y) * ((c & 4) ? f.z : 1 - f.z);
            diagonal_xy[g.index(i.x, i.y, i.z)] += w * m;
            off_diagonal[g.index(i.x, i.y, i.z)] += w * o;
        }
    };
    for (std::size_t s = 0; s + 1 < strands.offsets.size(); ++s)
        for (std::uint32_t k = strands.offsets[s]; k + 1 < strands.offsets[s + 1]; ++k) {
            const glm::vec3 a = p[k], b = p[k + 1];
            const float len = glm::distance(a, b);
            if (!(len > 0)) continue;
            const glm::vec3 t = (b - a) / len;
            const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5f * g.voxel))));
            for (int q = 0; q < n; ++q) splat(a + (b - a) * ((q + 0.5f) / n), t, len / n);
        }
    return g;
}

}  // namespace coif

namespace coif {

DensityGrid extend_grid(const DensityGrid& grid, glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 extent = grid.extent();
    const float margin = 0.5f * std::max({extent.x, extent.y, extent.z});
    lo = glm::max(lo, grid.origin - margin);
    hi = glm::min(hi, grid.origin + extent + margin);
    // Whole voxels added below and above along each axis.
    const glm::ivec3 below = glm::max(glm::ivec3(glm::ceil((grid.origin - lo) / grid.voxel)), glm::ivec3(0));
    const glm::ivec3 above = glm::max(glm::ivec3(glm::ceil((hi - (grid.origin + extent)) / grid.voxel)), glm::ivec3(0));
    DensityGrid g;
    g.dims = grid.dims + below + above;
    g.voxel = grid.voxel;
    g.origin = grid.origin - glm::vec3(below) * grid.voxel;
    g.strands_min = grid.strands_min;
    g.strands_max = grid.strands_max;
    const std::size_t voxels = static_cast<std::size_t>(g.dims.x) * g.dims.y * g.dims.z;
    std::vector<glm::vec4>& d = g.diagonal_xy.vector();
    std::vector<glm::vec2>& o = g.off_diagonal.vector();
    d.assign(voxels, glm::vec4(0.0f));
    o.assign(voxels, glm::vec2(0.0f));
    for (int z = 0; z < grid.dims.z; ++z)
        for (int y = 0; y < grid.dims.y; ++y)
            for (int x = 0; x < grid.dims.x; ++x) {
                const std::size_t to = g.index(x + below.x, y + below.y, z + below.z), from = grid.index(x, y, z);
                d[to] = grid.diagonal_xy[from];
                o[to] = grid.off_diagonal[from];
            }
    return g;
}

std::vector<std::uint8_t> voxelize_body(const BodyMesh& body, const glm::mat3& orientation, const DensityGrid& grid) {
    const glm::ivec3 n = grid.dims;
    if (glm::any(glm::lessThan(n, glm::ivec3(1)))) throw Error::parameter("body", "the shadow grid is empty");
    std::vector<std::uint8_t> occ(static_cast<std::size_t>(n.x) * n.y * n.z, 0);
    const auto mark = [&](glm::vec3 p) {
        const glm::ivec3 i = glm::ivec3(glm::floor((p - grid.origin) / grid.voxel));
        if (glm::all(glm::greaterThanEqual(i, glm::ivec3(0))) && glm::all(glm::lessThan(i, n))) occ[grid.index(i.x, i.y, i.z)] = 1;
    };
    const float spacing = grid.voxel / 3.0f;
    const glm::vec3 lo = grid.origin - grid.voxel, hi = grid.origin + grid.extent() + grid.voxel;
    for (const glm::uvec3& t : body.triangles) {
        const glm::vec3 a = orientation * body.positions[t.x], b = orientation * body.positions[t.y], c = orientation * body.positions[t.z];
        if (glm::any(glm::lessThan(glm::max(a, glm::max(b, c)), lo)) || glm::any(glm::greaterThan(glm::min(a, glm::min(b, c)), hi)))
            continue;  // wholly outside the grid
        const float edge = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
        const int k = std::max(1, static_cast<int>(std::ceil(edge / spacing)));
        for (int i = 0; i <= k; ++i)
            for (int j = 0; i + j <= k; ++j) {
                const float u = static_cast<float>(i) / k, v = static_cast<float>(j) / k;
                mark(a + u * (b - a) + v * (c - a));
            }
    }
    // Enclosed voxels: flood the free voxels from the border; those the flood does not reach are inside.
    std::vector<std::uint8_t> outside(occ.size(), 0);
    std::vector<glm::ivec3> stack;
    const auto push = [&](int x, int y, int z) {
        if (x < 0 || y < 0 || z < 0 || x >= n.x || y >= n.y || z >= n.z) return;
        const std::size_t i = grid.index(x, y, z);
        if (occ[i] || outside[i]) return;
        outside[i] = 1;
        stack.push_back({x, y, z});
    };
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                if (x == 0 || y == 0 || z == 0 || x == n.x - 1 || y == n.y - 1 || z == n.z - 1) push(x, y, z);
    while (!stack.empty()) {
        const glm::ivec3 p = stack.back();
        stack.pop_back();
        push(p.x - 1, p.y, p.z), push(p.x + 1, p.y, p.z);
        push(p.x, p.y - 1, p.z), push(p.x, p.y + 1, p.z);
        push(p.x, p.y, p.z - 1), push(p.x, p.y, p.z + 1);
    }
    for (std::size_t i = 0; i < occ.size(); ++i) occ[i] = outside[i] ? occ[i] : 1;
    return occ;
}

}  // namespace coif
