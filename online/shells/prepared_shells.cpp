#include "online/shells/prepared_shells.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <string>

#include "models/core/error.h"
#include "models/strands.h"

namespace coif {
namespace {

glm::mat4 to_mat4(const glm::mat3& orientation, const Similarity& s) {
    const glm::mat3 r = glm::mat3_cast(glm::quat(s.rotation));
    glm::mat4 m(orientation * r * static_cast<float>(s.scale));
    m[3] = glm::vec4(orientation * glm::vec3(s.translation), 1.0f);
    return m;
}

}  // namespace

std::vector<PrototypeBox> prototype_boxes(const PreparedShells& p) {
    std::vector<PrototypeBox> proto(p.meshes.size());  // per prototype: its outer mesh's box
    for (std::size_t q = 0; q < p.meshes.size(); ++q) {
        const MeshRange& outer = p.meshes[q].back();
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (std::int32_t v = 0; v < outer.vertex_count; ++v) {
            const glm::vec3 x = p.vertices[static_cast<std::size_t>(outer.base_vertex + v)].position;
            lo = glm::min(lo, x);
            hi = glm::max(hi, x);
        }
        proto[q] = {lo, hi};
    }
    return proto;
}

std::vector<ClusterBox> cluster_boxes(const PreparedShells& p, std::span<const PrototypeBox> proto) {
    std::vector<ClusterBox> out(p.instances.size());
    for (std::size_t c = 0; c < p.instances.size(); ++c) {
        const auto [lo, hi] = proto[p.cluster_proto[c]];
        for (int k = 0; k < 8; ++k) {
            const glm::vec3 corner(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
            out[c][static_cast<std::size_t>(k)] = glm::vec3(p.instances[c].model * glm::vec4(corner, 1.0f));
        }
    }
    return out;
}

bool box_in_view(const glm::mat4& vp, const ClusterBox& box) {
    const glm::vec4 row0(vp[0][0], vp[1][0], vp[2][0], vp[3][0]), row1(vp[0][1], vp[1][1], vp[2][1], vp[3][1]);
    const glm::vec4 row2(vp[0][2], vp[1][2], vp[2][2], vp[3][2]), row3(vp[0][3], vp[1][3], vp[2][3], vp[3][3]);
    const glm::vec4 planes[6] = {row3 + row0, row3 - row0, row3 + row1, row3 - row1, row3 + row2, row3 - row2};
    for (const glm::vec4& plane : planes) {
        bool all_outside = true;
        for (const glm::vec3& x : box)
            if (glm::dot(plane, glm::vec4(x, 1.0f)) >= 0.0f) {
                all_outside = false;
                break;
            }
        if (all_outside) return false;
    }
    return true;
}

glm::mat3 style_orientation(const HairStyle& style) {
    if (style_axes_stated(style)) return glm::mat3(1.0f);
    glm::dvec3 sum(0.0);
    for (const Cluster& c : style.clusters) {
        if (!c.shape) continue;
        sum += c.placement.apply(c.shape->position(1.0)) - c.placement.apply(c.shape->position(0.0));
    }
    StrandStats st;
    st.mean_root_to_tip = glm::length(sum) > 0 ? glm::normalize(sum) : glm::dvec3(0, -1, 0);
    return hang_axis_rotation(st);
}

glm::mat3 body_orientation(const HairStyle& style) { return style_orientation(style) * style_source_rotation(style); }

std::vector<glm::vec3> cluster_roots(const HairStyle& style, const glm::mat3& orientation) {
    std::vector<glm::vec3> roots;
    roots.reserve(style.clusters.size());
    for (const Cluster& c : style.clusters) {
        if (!c.shape) throw Error::parameter("style", "a cluster has no shape");
        roots.push_back(orientation * glm::vec3(c.placement.apply(c.shape->position(0.0))));
    }
    return roots;
}

DiskLayout PreparedShells::layout_of_slot(std::size_t slot) const {
    DiskLayout l = layout;
    l.layers = static_cast<int>(meshes.at(slot).size());
    return l;
}

std::vector<std::size_t> PreparedShells::sector_bases() const {
    std::vector<std::size_t> base(meshes.size() + 1, 0);
    for (std::size_t p = 0; p < meshes.size(); ++p) base[p + 1] = base[p] + layout_of_slot(p).sector_count();
    return base;
}

void place_clusters(PreparedShells& m, const HairStyle& style, const glm::mat3& orientation, int lighting_rows_per_hsv) {
    if (lighting_rows_per_hsv < 0 || lighting_rows_per_hsv > kMaxMeshSubdivision)
        throw Error::parameter("lighting rows per HSV", "must be 0.." + std::to_string(kMaxMeshSubdivision));
    const DiskLayout& L = m.layout;
    const std::vector<std::size_t> base = m.sector_bases();
    m.lighting_rows = L.s_t * (lighting_rows_per_hsv > 0 ? lighting_rows_per_hsv : L.mesh_t) + 1;
    m.instances.clear();
    m.samples.clear();
    m.cluster_ids.clear();
    m.cluster_centre.clear();
    m.bounds_min = glm::vec3(std::numeric_limits<float>::max());
    m.bounds_max = glm::vec3(std::numeric_limits<float>::lowest());
    for (std::size_t c = 0; c < style.clusters.size(); ++c) {
        const Cluster& cl = style.clusters[c];
        const std::size_t p = m.cluster_proto.at(c);
        const glm::mat4 model = to_mat4(orientation, cl.placement);
        const glm::mat3 rot(model);
        m.instances.push_back({model, glm::uvec4(static_cast<std::uint32_t>(base[p]), static_cast<std::uint32_t>(c), 0, 0)});
        m.cluster_ids.push_back(static_cast<std::uint32_t>(c));
        const GeneralizedCylinder& shape = *cl.shape;
        m.cluster_centre.push_back(glm::vec3(model * glm::vec4(glm::vec3(shape.position(0.5)), 1.0f)));
        for (int r = 0; r < m.lighting_rows; ++r) {
            const double t = static_cast<double>(r) / (m.lighting_rows - 1);
            const Frame f = shape.frame(t);
            glm::vec4 position = model * glm::vec4(glm::vec3(shape.position(t)), 1.0f);
            position.w = static_cast<float>(cl.placement.scale * shape.a(t));
            const float b = static_cast<float>(cl.placement.scale * shape.b(t));
            m.samples.push_back({position, glm::vec4(glm::normalize(rot * glm::vec3(f.tangent)), b),
                                 glm::vec4(glm::normalize(rot * glm::vec3(f.normal)), static_cast<float>(shape.theta(t)))});
        }
        const MeshRange& outer = m.meshes[p].back();
        for (std::int32_t v = 0; v < outer.vertex_count; ++v) {
            const glm::vec3 w = glm::vec3(model * glm::vec4(m.vertices[static_cast<std::size_t>(outer.base_vertex + v)].position, 1.0f));
            m.bounds_min = glm::min(m.bounds_min, w);
            m.bounds_max = glm::max(m.bounds_max, w);
        }
    }
}

namespace {
// A lighting sample's frame: the unit tangent and two unit normals (r0, T × r0); tilts are summed in it.
struct TiltFrame {
    glm::vec3 T, r, s;
};
TiltFrame tilt_frame(const LightingSample& q) {
    const glm::vec3 T = glm::normalize(glm::vec3(q.tangent));
    const glm::vec3 n = glm::vec3(q.normal);
    const glm::vec3 r = glm::normalize(n - glm::dot(n, T) * T);
    return {T, r, glm::cross(T, r)};
}
std::size_t placed_rows(const PreparedShells& shells) {
    const auto rows = static_cast<std::size_t>(shells.lighting_rows);
    if (rows == 0 || shells.samples.size() != rows * shells.clusters())
        throw Error::parameter("fibre tilts", "the shells' lighting samples are not placed");
    return rows;
}
// Adds the segments of strand `s` (of cluster `c`, whose samples' frames are `frames`) to `sums`.
void add_strand_tilts(FibreTiltSums& sums, const PreparedShells& shells, std::size_t c, std::span<const TiltFrame> frames,
                      const Strands& strands, std::size_t s, const glm::mat3& orientation) {
    const std::size_t rows = sums.rows.size();
    for (std::uint32_t k = strands.offsets[s]; k + 1 < strands.offsets[s + 1]; ++k) {
        const glm::vec3 d = orientation * (strands.points[k + 1] - strands.points[k]);
        const float len = glm::length(d);
        if (!(len > 0) || !std::isfinite(len)) continue;
        const glm::vec3 mid = orientation * (0.5f * (strands.points[k] + strands.points[k + 1]));
        // The nearest sample along the own axis (a curve of few rows, so a scan is cheap).
        std::size_t best = 0;
        float best_d2 = std::numeric_limits<float>::infinity();
        for (std::size_t i = 0; i < rows; ++i) {
            const glm::vec3 e = glm::vec3(shells.samples[c * rows + i].position) - mid;
            const float d2 = glm::dot(e, e);
            if (d2 < best_d2) best_d2 = d2, best = i;
        }
        const TiltFrame& f = frames[best];
        const glm::vec3 t = d / len;
        const double angle = std::acos(std::clamp(double(glm::dot(t, f.T)), -1.0, 1.0));
        const glm::dvec2 across(glm::dot(t, f.r), glm::dot(t, f.s));
        const double across_len = glm::length(across);
        const glm::dvec2 v = across_len > 1e-12 ? angle * across / across_len : glm::dvec2(0.0);
        FibreTiltSums::Moments& m = sums.rows[best];
        m.w += len;
        m.sum += double(len) * v;
        m.sum2 += double(len) * glm::dvec3(v.x * v.x, v.y * v.y, v.x * v.y);
        sums.angle2 += len * angle * angle;
        sums.weight += len;
    }
}
std::vector<TiltFrame> cluster_frames(const PreparedShells& shells, std::size_t c, std::size_t rows) {
    std::vector<TiltFrame> frames(rows);
    for (std::size_t i = 0; i < rows; ++i) frames[i] = tilt_frame(shells.samples[c * rows + i]);
    return frames;
}
}  // namespace

FibreTiltSums cluster_fibre_tilt_sums(const PreparedShells& shells, std::size_t cluster, const Strands& strands,
                                      const glm::mat3& orientation) {
    const std::size_t rows = placed_rows(shells);
    if (cluster >= shells.clusters()) throw Error::parameter("fibre tilts", "a strand's cluster is out of range");
    FibreTiltSums sums;
    sums.rows.resize(rows);
    const std::vector<TiltFrame> frames = cluster_frames(shells, cluster, rows);
    for (std::size_t s = 0; s < strands.strand_count(); ++s) add_strand_tilts(sums, shells, cluster, frames, strands, s, orientation);
    return sums;
}

float set_fibre_tilts(PreparedShells& shells, std::span<const FibreTiltSums> clusters) {
    const std::size_t rows = placed_rows(shells);
    if (clusters.size() != shells.clusters()) throw Error::parameter("fibre tilts", "one set of sums per cluster is needed");
    double angle2 = 0, weight = 0;
    for (std::size_t c = 0; c < clusters.size(); ++c) {
        if (clusters[c].rows.size() != rows) throw Error::parameter("fibre tilts", "the sums are of another lighting layout");
        angle2 += clusters[c].angle2;
        weight += clusters[c].weight;
        for (std::size_t r = 0; r < rows; ++r) {
            const FibreTiltSums::Moments& m = clusters[c].rows[r];
            LightingSample& q = shells.samples[c * rows + r];
            q.tilt_mean = q.tilt_a = q.tilt_b = glm::vec4(0.0f);
            if (!(m.w > 0)) continue;
            // The mean tilt and the covariance about it, and its eigen-decomposition (2 × 2, symmetric).
            const glm::dvec2 mean = m.sum / m.w;
            const double xx = m.sum2.x / m.w - mean.x * mean.x, yy = m.sum2.y / m.w - mean.y * mean.y,
                         xy = m.sum2.z / m.w - mean.x * mean.y;
            const double half_trace = 0.5 * (xx + yy), det = xx * yy - xy * xy;
            const double disc = std::sqrt(std::max(0.0, half_trace * half_trace - det));
            const double l1 = std::max(0.0, half_trace + disc), l2 = std::max(0.0, half_trace - disc);
            const glm::dvec2 e1 = std::abs(xy) > 1e-12 ? glm::normalize(glm::dvec2(l1 - yy, xy))
                                                       : (xx >= yy ? glm::dvec2(1.0, 0.0) : glm::dvec2(0.0, 1.0));
            const glm::dvec2 e2(-e1.y, e1.x);
            const TiltFrame f = tilt_frame(q);
            const auto world = [&f](glm::dvec2 v) { return glm::vec4(float(v.x) * f.r + float(v.y) * f.s, 0.0f); };
            // ±a, ±b with a = √(2 λ1) e1, b = √(2 λ2) e2: their second moment about the mean is λ1 e1e1ᵀ + λ2 e2e2ᵀ.
            q.tilt_mean = world(mean);
            q.tilt_a = world(std::sqrt(2.0 * l1) * e1);
            q.tilt_b = world(std::sqrt(2.0 * l2) * e2);
        }
    }
    return weight > 0 ? static_cast<float>(std::sqrt(angle2 / weight)) : 0.0f;
}

float measure_fibre_tilts(PreparedShells& shells, const Strands& strands, std::span<const std::uint32_t> strand_cluster,
                          const glm::mat3& orientation) {
    if (strand_cluster.size() != strands.strand_count())
        throw Error::parameter("fibre tilts", "one cluster per strand is needed");
    const std::size_t rows = placed_rows(shells);
    std::vector<FibreTiltSums> sums(shells.clusters());
    std::vector<std::vector<TiltFrame>> frames(shells.clusters());
    for (std::size_t c = 0; c < sums.size(); ++c) sums[c].rows.resize(rows);
    for (std::size_t s = 0; s < strands.strand_count(); ++s) {
        const std::size_t c = strand_cluster[s];
        if (c >= shells.clusters()) throw Error::parameter("fibre tilts", "a strand's cluster is out of range");
        if (frames[c].empty()) frames[c] = cluster_frames(shells, c, rows);
        add_strand_tilts(sums[c], shells, c, frames[c], strands, s, orientation);
    }
    return set_fibre_tilts(shells, sums);
}

int lighting_step_within(const PreparedShells& shells, int wanted, float max_angle, std::vector<float>* worst) {
    const int rows = shells.lighting_rows;
    if (rows < 2 || shells.samples.empty()) return 1;
    const std::size_t clusters = shells.samples.size() / static_cast<std::size_t>(rows);
    const auto axis = [&](std::size_t c, int r) {
        return glm::normalize(glm::vec3(shells.samples[c * static_cast<std::size_t>(rows) + static_cast<std::size_t>(r)].tangent));
    };
    int best = 1;
    for (int k = 2; k <= std::min(wanted, rows - 1); ++k) {
        if ((rows - 1) % k != 0) continue;
        std::vector<float> angles;
        for (std::size_t c = 0; c < clusters; ++c)
            for (int r = 0; r < rows; ++r) {
                if (r % k == 0) continue;
                const int r0 = r / k * k;
                const float f = static_cast<float>(r - r0) / static_cast<float>(k);
                const glm::vec3 between = glm::normalize(glm::mix(axis(c, r0), axis(c, r0 + k), f));
                angles.push_back(std::acos(std::clamp(glm::dot(axis(c, r), between), -1.0f, 1.0f)));
            }
        const auto p90 = angles.begin() + static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(angles.size() - 1));
        std::nth_element(angles.begin(), p90, angles.end());
        if (worst) worst->push_back(*p90);
        if (*p90 > max_angle) break;
        best = k;
    }
    return best;
}

}  // namespace coif
