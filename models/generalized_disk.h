#pragma once
// The generalized disk structure of a hair cluster (004 §3.2, eq. 3, Figure 1): an interior core and
// L layered shells, cut into Hair Shell Volumes (HSVs) by sampling (t, v, u) uniformly; each HSV
// is bounded along t by two generalized sectors, β⊤ (toward the root) and β⊥ (toward the tip).
//
// Sampling (eq. 3, with the core made explicit):
//   t_i = i / s_t,                         i = 0 .. s_t        (s_t + 1 sector planes)
//   v_j = v_core + (1 − v_core) · j / L,   j = 0 .. L          (layer boundaries; shell j is [v_j, v_j+1])
//   u_k = 2π k / s_u,                      k = 0 .. s_u − 1    (tracks are cut into s_u sectors)
//   With v_core = 0 and L = s_v this is exactly eq. 3. The core v < v_core is the paper's
//   "homogeneous transparent interior core": it has no sectors and no density grid.
//
// Indices: sector (i, j, k) ↦ (i·L + j)·s_u + k;  HSV (i, j, k), i < s_t, ↦ the same formula; the HSV's
// β⊤ is sector (i, j, k) and its β⊥ is sector (i+1, j, k). Layer j = 0 is the innermost shell.
//
// Sector coordinates (DESIGN.md): a sector lies in the normal plane at t_i. Its own 2D coordinates
// are s along the track (following u, from u_k to u_k+1) and r across it (following v, from v_j on
// the inner side to v_j+1 on the outer side). Metric extents: width = arc length of the track at the
// sector's middle radius, depth = radial length at the sector's middle phase (world units). The
// density grid treats the sector as the rectangle [0, width] × [0, depth]: r = depth is the layer's
// outer surface, the side a viewer outside the cluster sees.
//
// Layer meshes (004 §6.1): layer j's outer surface v = v_j+1, tessellated on a regular (t, u) grid
// with `mesh_t` rows per HSV along t and `mesh_u` columns per HSV around; the u seam is duplicated
// so that texcoords run u/2π ∈ [0, 1] and t ∈ [0, 1]. P_(u,t),j and P_(u,t),j+1 share texcoords.
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "models/generalized_cylinder.h"
#include "models/similarity.h"

namespace coif {

// Bounds on the layout, far above any sensible hairstyle, that keep every count allocatable.
inline constexpr int kMaxLayers = 256;
inline constexpr int kMaxSamplesT = 4096;
inline constexpr int kMaxSamplesU = 4096;
inline constexpr int kMaxGridCells = 256;  // per side of a sector's density grid
inline constexpr int kMaxMeshSubdivision = 64;

struct DiskLayout {
    double core_radius = 0.2;  // v_core ∈ [0, 1)
    int layers = 4;            // L ≥ 1
    int s_t = 8;               // HSVs along t
    int s_u = 8;               // HSVs around the ellipse
    int grid_s = 8;            // density grid cells along s (per sector)
    int grid_r = 4;            // density grid cells along r (per sector)
    int mesh_t = 4;            // layer-mesh rows per HSV along t
    int mesh_u = 2;            // layer-mesh columns per HSV around
    double gaussian_width = 0.05;  // λ of each strand's Gaussian exp(−d²/λ²), world units

    double layer_v(int j) const { return core_radius + (1.0 - core_radius) * j / layers; }
    double plane_t(int i) const { return static_cast<double>(i) / s_t; }
    double sector_u(int k) const;  // u_k = 2π k / s_u
    std::size_t sector_count() const { return static_cast<std::size_t>(s_t + 1) * layers * s_u; }
    std::size_t hsv_count() const { return static_cast<std::size_t>(s_t) * layers * s_u; }
    std::size_t sectors_per_plane() const { return static_cast<std::size_t>(layers) * s_u; }
    std::size_t sector_index(int i, int j, int k) const {
        return (static_cast<std::size_t>(i) * layers + j) * s_u + k;
    }
};

struct SectorRef {
    int plane = 0, layer = 0, sector = 0;  // i, j, k
};
SectorRef sector_ref(const DiskLayout& layout, std::size_t index);

struct Hsv {
    int i = 0, layer = 0, k = 0;
    std::size_t top = 0;     // β⊤: sector (i, j, k), toward the root
    std::size_t bottom = 0;  // β⊥: sector (i+1, j, k), toward the tip
};
// Every HSV of the layout, in index order.
std::vector<Hsv> hsv_index(const DiskLayout& layout);

// A generalized sector placed on a cylinder.
struct SectorShape {
    double t = 0, v0 = 0, v1 = 0, u0 = 0, u1 = 0;
    double width = 0;  // metric extent along s (track arc length at the middle radius)
    double depth = 0;  // metric extent along r (radial length at the middle phase)
};
SectorShape sector_shape(const GeneralizedCylinder& c, const DiskLayout& layout, int i, int j, int k);

// Volume of HSV (i, j, k): ∫∫∫ |det[∂P/∂t ∂P/∂v ∂P/∂u]| by 4-point Gauss–Legendre per axis.
double hsv_volume(const GeneralizedCylinder& c, const DiskLayout& layout, int i, int j, int k);
// Volume of the core v < v_core over t ∈ [0, 1], same quadrature per HSV-sized cell.
double core_volume(const GeneralizedCylinder& c, const DiskLayout& layout);

struct LayerMesh {
    int layer = 0;
    double v = 1.0;      // the surface's relative radius v_j+1
    int rows = 0;        // vertices along t
    int columns = 0;     // vertices around (the seam duplicated)
    std::vector<glm::vec3> position;
    std::vector<glm::vec3> tangent;   // hair direction: ∂P/∂t normalised (root → tip)
    std::vector<glm::vec3> normal;    // outward surface normal: ∂P/∂u × ∂P/∂t normalised
    std::vector<glm::vec2> texcoord;  // (u / 2π, t)
    std::vector<std::uint32_t> indices;  // triangles, counter-clockwise seen from outside
};
// Layer j's outer surface, placed by `place` (an instance's similarity transform).
LayerMesh layer_mesh(const GeneralizedCylinder& c, const DiskLayout& layout, int j, const Similarity& place = {});

// Rows and columns of a layer mesh's grid joined: every t-th row and u-th column (the shells' level of detail,
// online/shells/shell_lod.h; (1, 1): all of them).
struct GridStride {
    int t = 1, u = 1;
};
// The rows (or columns) a stride keeps: 0, s, 2s, …, and the last.
std::vector<int> strided(int count, int stride);
// The triangles of a rows × columns grid (row-major vertices) on the rows and columns `s` keeps, counter-clockwise seen
// from outside: layer_mesh's triangle list at stride (1, 1).
std::vector<std::uint32_t> grid_triangles(int rows, int columns, GridStride s = {});

}  // namespace coif
