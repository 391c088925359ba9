#include "models/generalized_disk.h"

#include <cmath>

#include "models/core/units.h"

namespace coif {

namespace {

// 4-point Gauss–Legendre on [0, 1]: exact for polynomials of degree 7, so the volume of a straight
// elliptic cylinder (integrand linear in v) is exact to rounding.
constexpr double kGX[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
constexpr double kGW[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};

double box_volume(const GeneralizedCylinder& c, double t0, double t1, double v0, double v1, double u0, double u1) {
    double acc = 0;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int d = 0; d < 4; ++d) {
                const SurfacePoint p = c.surface(t0 + (t1 - t0) * kGX[a], v0 + (v1 - v0) * kGX[b], u0 + (u1 - u0) * kGX[d]);
                acc += kGW[a] * kGW[b] * kGW[d] * std::abs(glm::dot(p.d_dt, glm::cross(p.d_dv, p.d_du)));
            }
    return acc * (t1 - t0) * (v1 - v0) * (u1 - u0);
}

}  // namespace

double DiskLayout::sector_u(int k) const { return kTwoPi * k / s_u; }

SectorRef sector_ref(const DiskLayout& layout, std::size_t index) {
    SectorRef r;
    r.sector = static_cast<int>(index % static_cast<std::size_t>(layout.s_u));
    index /= static_cast<std::size_t>(layout.s_u);
    r.layer = static_cast<int>(index % static_cast<std::size_t>(layout.layers));
    r.plane = static_cast<int>(index / static_cast<std::size_t>(layout.layers));
    return r;
}

std::vector<Hsv> hsv_index(const DiskLayout& layout) {
    std::vector<Hsv> out;
    out.reserve(layout.hsv_count());
    for (int i = 0; i < layout.s_t; ++i)
        for (int j = 0; j < layout.layers; ++j)
            for (int k = 0; k < layout.s_u; ++k)
                out.push_back({i, j, k, layout.sector_index(i, j, k), layout.sector_index(i + 1, j, k)});
    return out;
}

SectorShape sector_shape(const GeneralizedCylinder& c, const DiskLayout& layout, int i, int j, int k) {
    SectorShape s;
    s.t = layout.plane_t(i);
    s.v0 = layout.layer_v(j);
    s.v1 = layout.layer_v(j + 1);
    s.u0 = layout.sector_u(k);
    s.u1 = layout.sector_u(k + 1);
    const double vm = 0.5 * (s.v0 + s.v1), um = 0.5 * (s.u0 + s.u1);
    for (int g = 0; g < 4; ++g) {
        s.width += kGW[g] * glm::length(c.surface(s.t, vm, s.u0 + (s.u1 - s.u0) * kGX[g]).d_du) * (s.u1 - s.u0);
        s.depth += kGW[g] * glm::length(c.surface(s.t, s.v0 + (s.v1 - s.v0) * kGX[g], um).d_dv) * (s.v1 - s.v0);
    }
    return s;
}

double hsv_volume(const GeneralizedCylinder& c, const DiskLayout& layout, int i, int j, int k) {
    return box_volume(c, layout.plane_t(i), layout.plane_t(i + 1), layout.layer_v(j), layout.layer_v(j + 1),
                      layout.sector_u(k), layout.sector_u(k + 1));
}

double core_volume(const GeneralizedCylinder& c, const DiskLayout& layout) {
    if (layout.core_radius <= 0) return 0;
    double acc = 0;
    for (int i = 0; i < layout.s_t; ++i)
        for (int k = 0; k < layout.s_u; ++k)
            acc += box_volume(c, layout.plane_t(i), layout.plane_t(i + 1), 0.0, layout.core_radius, layout.sector_u(k),
                              layout.sector_u(k + 1));
    return acc;
}

LayerMesh layer_mesh(const GeneralizedCylinder& c, const DiskLayout& layout, int j, const Similarity& place) {
    LayerMesh m;
    m.layer = j;
    m.v = layout.layer_v(j + 1);
    m.rows = layout.s_t * layout.mesh_t + 1;
    m.columns = layout.s_u * layout.mesh_u + 1;
    const std::size_t n = static_cast<std::size_t>(m.rows) * m.columns;
    m.position.reserve(n);
    m.tangent.reserve(n);
    m.normal.reserve(n);
    m.texcoord.reserve(n);
    for (int r = 0; r < m.rows; ++r) {
        const double t = static_cast<double>(r) / (m.rows - 1);
        for (int q = 0; q < m.columns; ++q) {
            const double fu = static_cast<double>(q) / (m.columns - 1);
            const SurfacePoint p = c.surface(t, m.v, kTwoPi * fu);
            m.position.emplace_back(place.apply(p.position));
            m.tangent.emplace_back(place.apply_direction(glm::normalize(p.d_dt)));
            m.normal.emplace_back(place.apply_direction(p.normal()));
            m.texcoord.emplace_back(static_cast<float>(fu), static_cast<float>(t));
        }
    }
    m.indices = grid_triangles(m.rows, m.columns);
    return m;
}

std::vector<int> strided(int count, int stride) {
    std::vector<int> kept;
    for (int i = 0; i < count; i += stride) kept.push_back(i);
    if (count > 0 && kept.back() != count - 1) kept.push_back(count - 1);
    return kept;
}

std::vector<std::uint32_t> grid_triangles(int rows, int columns, GridStride s) {
    const std::vector<int> r = strided(rows, s.t), q = strided(columns, s.u);
    std::vector<std::uint32_t> out;
    if (r.size() < 2 || q.size() < 2) return out;
    out.reserve((r.size() - 1) * (q.size() - 1) * 6);
    const auto id = [&](int rr, int qq) { return static_cast<std::uint32_t>(rr * columns + qq); };
    // Counter-clockwise seen from outside: (a, b, c) with (b − a) × (c − a) along ∂P/∂u × ∂P/∂t,
    // i.e. (r,q) → (r,q+1) → (r+1,q).
    for (std::size_t a = 0; a + 1 < r.size(); ++a)
        for (std::size_t b = 0; b + 1 < q.size(); ++b)
            out.insert(out.end(), {id(r[a], q[b]), id(r[a], q[b + 1]), id(r[a + 1], q[b]), id(r[a], q[b + 1]),
                                   id(r[a + 1], q[b + 1]), id(r[a + 1], q[b])});
    return out;
}

}  // namespace coif
