#include "online/shells/shell_pick.h"

#include <cmath>
#include <limits>

namespace coif {
namespace {

// Möller–Trumbore: the ray parameter and barycentrics (u, v) of a hit, or false.
bool intersect(glm::vec3 o, glm::vec3 d, glm::vec3 a, glm::vec3 b, glm::vec3 c, float& s, float& u, float& v) {
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) return false;  // parallel; both faces count (the shells are seen from either side)
    const float inv = 1.0f / det;
    const glm::vec3 q = o - a;
    u = glm::dot(q, p) * inv;
    if (u < 0.0f || u > 1.0f) return false;
    const glm::vec3 r = glm::cross(q, e1);
    v = glm::dot(d, r) * inv;
    if (v < 0.0f || u + v > 1.0f) return false;
    s = glm::dot(e2, r) * inv;
    return s > 0.0f;
}

}  // namespace

std::optional<ShellHit> pick_shells(const PreparedShells& p, glm::vec3 origin, glm::vec3 direction) {
    if (glm::dot(direction, direction) <= 0.0f) return std::nullopt;
    const glm::vec3 dir = glm::normalize(direction);
    std::optional<ShellHit> best;
    float nearest = std::numeric_limits<float>::infinity();
    for (std::size_t c = 0; c < p.instances.size(); ++c) {
        // The ray in the prototype's space (the instance is a similarity: rotation, translation, uniform scale).
        const glm::mat4 inv = glm::inverse(p.instances[c].model);
        // o + s d is the prototype-space image of origin + s dir: s is the world distance along the unit dir.
        const glm::vec3 o = glm::vec3(inv * glm::vec4(origin, 1.0f)), d = glm::vec3(inv * glm::vec4(dir, 0.0f));
        const MeshRange& m = p.meshes[p.cluster_proto[c]].back();  // the outermost layer
        for (std::int32_t i = 0; i + 2 < m.count; i += 3) {
            const std::uint32_t* tri = p.indices.data() + m.first + i;
            const ShellVertex& a = p.vertices[static_cast<std::size_t>(m.base_vertex) + tri[0]];
            const ShellVertex& b = p.vertices[static_cast<std::size_t>(m.base_vertex) + tri[1]];
            const ShellVertex& e = p.vertices[static_cast<std::size_t>(m.base_vertex) + tri[2]];
            float s, u, v;
            if (!intersect(o, d, a.position, b.position, e.position, s, u, v)) continue;
            if (s >= nearest) continue;
            nearest = s;
            const float t = (1.0f - u - v) * a.texcoord.y + u * b.texcoord.y + v * e.texcoord.y;
            best = ShellHit{static_cast<int>(c), glm::clamp(t, 0.0f, 1.0f), s};
        }
    }
    return best;
}

}  // namespace coif
