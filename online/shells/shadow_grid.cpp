#include "online/shells/shadow_grid.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "models/core/parallel.h"

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

namespace {
// The sums' fixed point: a splat's ℓ t tᵀ in units of 2⁻²⁰ voxel of strand length (a splat is at most half a voxel: 2¹⁹
// units), shared among its 8 voxels by trilinear weights in steps of 1/256 along each axis (so the 8 shares sum to the
// splat exactly), 2⁻⁴⁴ voxel a unit of sum. A voxel's int64 sum holds 2²⁰ splats at the most.
constexpr double kLengthUnits = 1048576.0;  // 2^20 per voxel
constexpr int kWeightSteps = 256;
constexpr double kSumUnits = kLengthUnits * kWeightSteps * kWeightSteps * kWeightSteps;  // 2^44 per voxel
std::int64_t round_to_int(double x) { return static_cast<std::int64_t>(x < 0 ? x - 0.5 : x + 0.5); }
}  // namespace

std::pair<glm::vec3, glm::vec3> turned_bounds(const Strands& strands, const glm::mat3& orientation) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& q : strands.points) {
        const glm::vec3 p = orientation * q;
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return {lo, hi};
}

namespace {
// The voxel edge of a grid framing [lo, hi] with at most max_dim voxels along any axis: the longest side over
// max_dim − 6 (two voxels of margin on each side, and up to two for the lattice), rounded up to a power of 2^(1/8), so
// that bounds that move a little keep it.
float lattice_voxel(glm::vec3 lo, glm::vec3 hi, int max_dim) {
    const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-6f));
    const double longest = std::max({size.x, size.y, size.z});
    return static_cast<float>(std::exp2(std::ceil(8.0 * std::log2(longest / (max_dim - 6))) / 8.0));
}
}  // namespace

GridSums::GridSums(glm::vec3 lo, glm::vec3 hi, int max_dim) : max_dim_(max_dim) {
    if (max_dim < 8 || max_dim > 512) throw Error::parameter("shadow grid", "voxels along the longest axis must be 8..512");
    if (!glm::all(glm::lessThanEqual(lo, hi))) throw Error::parameter("shadow grid", "the style gives no strands to voxelize");
    frame_.voxel = lattice_voxel(lo, hi, max_dim);
    frame(lo, hi);
    sums_.assign(static_cast<std::size_t>(frame_.dims.x) * frame_.dims.y * frame_.dims.z, {});
}

void GridSums::frame(glm::vec3 lo, glm::vec3 hi) {
    DensityGrid& g = frame_;
    g.strands_min = lo;
    g.strands_max = hi;
    first_ = glm::ivec3(glm::floor(lo / g.voxel)) - 2;
    g.dims = glm::ivec3(glm::floor(hi / g.voxel)) + 2 - first_ + 1;
    g.origin = glm::vec3(first_) * g.voxel;
}

bool GridSums::can_reframe(glm::vec3 lo, glm::vec3 hi) const {
    return glm::all(glm::lessThanEqual(lo, hi)) && lattice_voxel(lo, hi, max_dim_) == frame_.voxel;
}

void GridSums::reframe(glm::vec3 lo, glm::vec3 hi) {
    if (!can_reframe(lo, hi)) throw Error::parameter("shadow grid", "the new bounds need another voxel size");
    const glm::ivec3 old_first = first_, old_dims = frame_.dims;
    std::vector<std::array<std::int64_t, 6>> old = std::move(sums_);
    frame(lo, hi);
    const DensityGrid& g = frame_;
    sums_.assign(static_cast<std::size_t>(g.dims.x) * g.dims.y * g.dims.z, {});
    // The voxels in both windows, in lattice coordinates [from, to).
    const glm::ivec3 from = glm::max(first_, old_first), to = glm::min(first_ + g.dims, old_first + old_dims);
    if (glm::any(glm::greaterThanEqual(from, to))) return;
    for (int z = from.z; z < to.z; ++z)
        for (int y = from.y; y < to.y; ++y) {
            const glm::ivec3 o = glm::ivec3(from.x, y, z) - old_first, n = glm::ivec3(from.x, y, z) - first_;
            const std::size_t src = (static_cast<std::size_t>(o.z) * old_dims.y + o.y) * old_dims.x + o.x;
            std::copy_n(old.begin() + static_cast<std::ptrdiff_t>(src), to.x - from.x,
                        sums_.begin() + static_cast<std::ptrdiff_t>(g.index(n.x, n.y, n.z)));
        }
}

namespace {
// GridSums::add of the strands [from, to) into `sums` (of grid g's voxels, whose voxel (0, 0, 0) is `first` on the lattice).
void splat_strands(const DensityGrid& g, glm::ivec3 first, std::vector<std::array<std::int64_t, 6>>& sums_,
                   const Strands& strands, const glm::mat3& orientation, int sign, std::size_t from, std::size_t to) {
    const double units = sign * kLengthUnits / g.voxel;  // per unit of strand length
    // One sub-segment of length `length` along the unit tangent t at q: ℓ t tᵀ spread over 8 voxels.
    const auto splat = [&](glm::vec3 q, glm::vec3 t, float length) {
        const double l = length * units;
        const std::int64_t m[6] = {round_to_int(l * t.x * t.x), round_to_int(l * t.y * t.y), round_to_int(l * t.z * t.z),
                                   round_to_int(l * t.x * t.y), round_to_int(l * t.x * t.z), round_to_int(l * t.y * t.z)};
        // On the lattice, not the window (first: its voxel (0, 0, 0)), so that a strand splats alike in any window.
        const glm::vec3 f0 = q / g.voxel - 0.5f;
        const glm::ivec3 l0 = glm::ivec3(glm::floor(f0)), i0 = l0 - first;
        const glm::ivec3 f = glm::ivec3(glm::round((f0 - glm::vec3(l0)) * float(kWeightSteps)));
        const std::int64_t wx[2] = {kWeightSteps - f.x, f.x}, wy[2] = {kWeightSteps - f.y, f.y}, wz[2] = {kWeightSteps - f.z, f.z};
        const auto add_to = [&](std::size_t at, std::int64_t w) {
            std::array<std::int64_t, 6>& s = sums_[at];
            for (int k = 0; k < 6; ++k) s[k] += w * m[k];
        };
        if (glm::all(glm::greaterThanEqual(i0, glm::ivec3(0))) && glm::all(glm::lessThan(i0 + 1, g.dims))) {  // all 8 inside
            const std::size_t at = g.index(i0.x, i0.y, i0.z), row = static_cast<std::size_t>(g.dims.x),
                              slice = row * static_cast<std::size_t>(g.dims.y);
            for (int z = 0; z < 2; ++z)
                for (int y = 0; y < 2; ++y) {
                    const std::size_t line = at + z * slice + y * row;
                    const std::int64_t wyz = wy[y] * wz[z];
                    add_to(line, wx[0] * wyz);
                    add_to(line + 1, wx[1] * wyz);
                }
            return;
        }
        for (int c = 0; c < 8; ++c) {
            const glm::ivec3 i = i0 + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            if (glm::any(glm::lessThan(i, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(i, g.dims))) continue;
            add_to(g.index(i.x, i.y, i.z), wx[c & 1] * wy[(c >> 1) & 1] * wz[(c >> 2) & 1]);
        }
    };
    for (std::size_t s = from; s < to; ++s)
        for (std::uint32_t k = strands.offsets[s]; k + 1 < strands.offsets[s + 1]; ++k) {
            const glm::vec3 a = orientation * strands.points[k], b = orientation * strands.points[k + 1];
            const float len = glm::distance(a, b);
            if (!(len > 0)) continue;
            const glm::vec3 t = (b - a) / len;
            const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5f * g.voxel))));
            for (int q = 0; q < n; ++q) splat(a + (b - a) * ((q + 0.5f) / n), t, len / n);
        }
}
}  // namespace

void GridSums::add(const Strands& strands, const glm::mat3& orientation, int sign) {
    const std::size_t n = strands.strand_count();
    // Integer sums add up alike in any order: a large set is split among threads, each into its own sums, added after.
    // Each thread's sums are a copy of the grid, so the split pays only where the points outnumber the voxels: the
    // default style's 254 564 points take 43 ms on 2 threads against 49 ms on one into its 64-voxel shadow grid (116 466
    // voxels), and 186 ms against 95 ms into the key lights' 128-voxel grid (998 976 voxels).
    const std::size_t points = strands.points.size();
    const std::size_t parts =
        points < 100000 || points < sums_.size() ? 1 : static_cast<std::size_t>(std::min(hardware_threads(), 4));
    if (parts == 1) {
        splat_strands(frame_, first_, sums_, strands, orientation, sign, 0, n);
        return;
    }
    std::vector<std::vector<std::array<std::int64_t, 6>>> own(parts - 1);
    parallel_for(parts, static_cast<int>(parts), [&](std::size_t i) {
        if (i > 0) own[i - 1].assign(sums_.size(), {});
        splat_strands(frame_, first_, i == 0 ? sums_ : own[i - 1], strands, orientation, sign, n * i / parts, n * (i + 1) / parts);
    });
    for (const auto& o : own)
        for (std::size_t v = 0; v < sums_.size(); ++v)
            for (int k = 0; k < 6; ++k) sums_[v][k] += o[v][k];
}

DensityGrid GridSums::grid() const {
    DensityGrid g = frame_;
    const double per_volume = 1.0 / (kSumUnits * g.voxel * g.voxel);  // a unit of sum's strand length per unit volume
    std::vector<glm::vec4>& diagonal_xy = g.diagonal_xy.vector();
    std::vector<glm::vec2>& off_diagonal = g.off_diagonal.vector();
    diagonal_xy.resize(sums_.size());
    off_diagonal.resize(sums_.size());
    for (std::size_t i = 0; i < sums_.size(); ++i) {
        const std::array<std::int64_t, 6>& s = sums_[i];
        const auto f = [&](int k) { return static_cast<float>(static_cast<double>(s[k]) * per_volume); };
        diagonal_xy[i] = glm::vec4(f(0), f(1), f(2), f(3));
        off_diagonal[i] = glm::vec2(f(4), f(5));
    }
    return g;
}

DensityGrid voxelize_strands(const Strands& strands, const glm::mat3& orientation, int max_dim) {
    if (strands.points.empty()) throw Error::parameter("shadow grid", "the style gives no strands to voxelize");
    const auto [lo, hi] = turned_bounds(strands, orientation);
    GridSums sums(lo, hi, max_dim);
    sums.add(strands, orientation);
    return sums.grid();
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
