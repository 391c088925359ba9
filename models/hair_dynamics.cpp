#include "models/hair_dynamics.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <numeric>

#include "models/core/error.h"
#include "models/skinning.h"

namespace coif {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A deterministic value in [−1, 1] from (seed, step): the wind's gust (splitmix64).
float noise(std::uint32_t seed, int step) {
    std::uint64_t z = (static_cast<std::uint64_t>(seed) << 32) + static_cast<std::uint64_t>(step) + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<float>(static_cast<double>(z >> 11) * 0x1.0p-53 * 2.0 - 1.0);
}

constexpr float kRootWeight = 4.0f;   // shape matching: the two pinned points count this much
constexpr float kFtlDamping = 0.9f;   // Müller et al. 2012's s_damping: how much of the next point's correction is undone

}  // namespace

void validate(const DynamicsParams& p) {
    if (!(p.dt > 0.0f) || !std::isfinite(p.dt)) throw Error::parameter("dynamics dt", "the time step must be finite and > 0");
    if (p.substeps < 1 || p.substeps > 64) throw Error::parameter("dynamics substeps", "must be 1..64");
    if (p.iterations < 1 || p.iterations > 64) throw Error::parameter("dynamics iterations", "must be 1..64");
    if (!finite(p.gravity) || !finite(p.wind)) throw Error::parameter("dynamics", "gravity and wind must be finite");
    if (!(p.gust >= 0.0f && p.gust <= 1.0f)) throw Error::parameter("dynamics gust", "must be in [0, 1]");
    if (!(p.damping >= 0.0f && p.damping <= 1.0f)) throw Error::parameter("dynamics damping", "must be in [0, 1]");
    if (!(p.bend_stiffness >= 0.0f && p.bend_stiffness <= 1.0f)) throw Error::parameter("dynamics bend_stiffness", "must be in [0, 1]");
    if (!(p.shape_stiffness >= 0.0f && p.shape_stiffness <= 1.0f)) throw Error::parameter("dynamics shape_stiffness", "must be in [0, 1]");
    if (!(p.collision_margin >= 0.0f) || !std::isfinite(p.collision_margin)) throw Error::parameter("dynamics collision_margin", "must be ≥ 0");
}

// ---- BodyCollider ----

std::int64_t BodyCollider::key(glm::ivec3 c) const {
    return (static_cast<std::int64_t>(c.x) & 0x1FFFFF) | ((static_cast<std::int64_t>(c.y) & 0x1FFFFF) << 21) |
           ((static_cast<std::int64_t>(c.z) & 0x1FFFFF) << 42);
}

void BodyCollider::set(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals, float cell) {
    if (!(cell > 0.0f)) throw Error::parameter("body collider", "the cell size must be > 0");
    positions_ = positions;
    normals_ = normals;
    cell_ = cell;
    std::vector<std::int64_t> k(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) k[i] = key(glm::ivec3(glm::floor(positions[i] / cell)));
    order_.resize(positions.size());
    std::iota(order_.begin(), order_.end(), 0u);
    std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) { return k[a] < k[b] || (k[a] == k[b] && a < b); });
    keys_.resize(order_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) keys_[i] = k[order_[i]];
}

const glm::vec3* BodyCollider::nearest(glm::vec3 p, std::size_t* index) const {
    const glm::ivec3 c = glm::ivec3(glm::floor(p / cell_));
    float best = INFINITY;
    const glm::vec3* out = nullptr;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const std::int64_t k = key(c + glm::ivec3(dx, dy, dz));
                auto it = std::lower_bound(keys_.begin(), keys_.end(), k);
                for (; it != keys_.end() && *it == k; ++it) {
                    const std::uint32_t v = order_[static_cast<std::size_t>(it - keys_.begin())];
                    const float d = glm::distance(p, positions_[v]);
                    if (d < best) best = d, out = &positions_[v], *index = v;
                }
            }
    return out;
}

float BodyCollider::signed_distance(glm::vec3 p) const {
    std::size_t i = 0;
    const glm::vec3* v = nearest(p, &i);
    return v ? glm::dot(p - *v, normals_[i]) : INFINITY;
}

bool BodyCollider::push_out(glm::vec3& p, float margin) const {
    std::size_t i = 0;
    const glm::vec3* v = nearest(p, &i);
    if (!v) return false;
    const float d = glm::dot(p - *v, normals_[i]);
    if (d >= margin) return false;
    p += (margin - d) * normals_[i];
    return true;
}

// ---- ClusterDynamics ----

ClusterDynamics::ClusterDynamics(std::vector<std::vector<glm::vec3>> rest, DynamicsParams params)
    : p_(params), rest_(std::move(rest)) {
    validate(p_);
    for (const auto& c : rest_) {
        if (c.size() != static_cast<std::size_t>(kChainPoints)) throw Error::parameter("dynamics", "every chain needs kChainPoints points");
        std::vector<float> l, b;
        for (std::size_t i = 0; i + 1 < c.size(); ++i) l.push_back(glm::distance(c[i], c[i + 1]));
        for (std::size_t i = 0; i + 2 < c.size(); ++i) b.push_back(glm::distance(c[i], c[i + 2]));
        length_.push_back(std::move(l));
        bend_.push_back(std::move(b));
    }
    x_ = rest_;
    v_.assign(rest_.size(), std::vector<glm::vec3>(kChainPoints, glm::vec3(0.0f)));
}

void ClusterDynamics::reset(const std::vector<glm::mat4>& frames) {
    for (std::size_t c = 0; c < rest_.size(); ++c)
        for (int i = 0; i < kChainPoints; ++i) {
            x_[c][static_cast<std::size_t>(i)] = glm::vec3(frames[c] * glm::vec4(rest_[c][static_cast<std::size_t>(i)], 1.0f));
            v_[c][static_cast<std::size_t>(i)] = glm::vec3(0.0f);
        }
}

void ClusterDynamics::step(const std::vector<glm::mat4>& frames, const BodyCollider& body) {
    if (frames.size() != rest_.size()) throw Error::parameter("dynamics", "one root frame per cluster");
    const float h = p_.dt / static_cast<float>(p_.substeps);
    for (int s = 0; s < p_.substeps; ++s) {
        const int tick = steps_ * p_.substeps + s;
        const glm::vec3 wind = p_.wind * (1.0f + p_.gust * noise(p_.seed, tick));
        const glm::vec3 a = p_.gravity + wind;
        for (std::size_t c = 0; c < rest_.size(); ++c) {
            std::vector<glm::vec3>& x = x_[c];
            std::vector<glm::vec3>& v = v_[c];
            glm::vec3 prev[kChainPoints];
            for (int i = 0; i < kChainPoints; ++i) prev[i] = x[static_cast<std::size_t>(i)];
            // The pinned points where the character puts them; the others predicted.
            for (int i = 0; i < 2; ++i) x[static_cast<std::size_t>(i)] = glm::vec3(frames[c] * glm::vec4(rest_[c][static_cast<std::size_t>(i)], 1.0f));
            for (std::size_t i = 2; i < x.size(); ++i) {
                x[i] += h * (v[i] + h * a);
                const glm::vec3 goal(frames[c] * glm::vec4(rest_[c][i], 1.0f));
                x[i] += p_.shape_stiffness * (goal - x[i]);
            }
            for (int it = 0; it < p_.iterations; ++it) {
                for (std::size_t i = 0; i + 2 < x.size(); ++i) {  // bending: points two apart
                    const glm::vec3 d = x[i + 2] - x[i];
                    const float len = glm::length(d);
                    if (!(len > 0.0f)) continue;
                    const glm::vec3 corr = p_.bend_stiffness * (len - bend_[c][i]) / len * d;
                    if (i < 2) x[i + 2] -= corr;  // x[0], x[1] pinned
                    else x[i] += 0.5f * corr, x[i + 2] -= 0.5f * corr;
                }
                if (!body.empty())
                    for (std::size_t i = 2; i < x.size(); ++i) body.push_out(x[i], p_.collision_margin);
            }
            // Lengths by "follow the leader" (Müller et al. 2012): each point put on the sphere of its rest distance about
            // its parent, root outward, which makes every length exact in one sweep; its velocity then takes back the
            // next point's correction (their "dynamic FTL", factor kFtlDamping), which FTL would otherwise turn into energy.
            glm::vec3 moved[kChainPoints] = {};
            for (std::size_t i = 1; i + 1 < x.size(); ++i) {
                const glm::vec3 d = x[i + 1] - x[i];
                const float len = glm::length(d);
                if (!(len > 0.0f)) continue;
                const glm::vec3 to = x[i] + d * (length_[c][i] / len);
                moved[i + 1] = to - x[i + 1];
                x[i + 1] = to;
            }
            for (std::size_t i = 2; i < x.size(); ++i) {
                glm::vec3 vi = (x[i] - prev[i]) / h;
                if (i + 1 < x.size()) vi -= kFtlDamping * moved[i + 1] / h;
                v[i] = (1.0f - p_.damping) * vi;
            }
            v[0] = (x[0] - prev[0]) / h;
            v[1] = (x[1] - prev[1]) / h;
        }
    }
    ++steps_;
}

glm::mat4 ClusterDynamics::cluster_transform(std::size_t c) const {
    const std::vector<glm::vec3>& x = x_[c];
    const std::vector<glm::vec3>& x0 = rest_[c];
    glm::mat3 A(0.0f);  // about the root, which the transform keeps where it is
    for (int i = 1; i < kChainPoints; ++i) {
        const float w = i < 2 ? kRootWeight : 1.0f;
        A += w * glm::outerProduct(x[static_cast<std::size_t>(i)] - x[0], x0[static_cast<std::size_t>(i)] - x0[0]);
    }
    const glm::mat3 R = extract_rotation(A, glm::mat3(1.0f), 50);
    glm::mat4 m(R);
    m[3] = glm::vec4(x[0] - R * x0[0], 1.0f);
    return m;
}

double ClusterDynamics::energy() const {
    double e = 0.0;
    for (std::size_t c = 0; c < x_.size(); ++c)
        for (std::size_t i = 2; i < x_[c].size(); ++i)
            e += 0.5 * glm::dot(v_[c][i], v_[c][i]) - glm::dot(p_.gravity, x_[c][i]);
    return e;
}

double ClusterDynamics::max_stretch() const {
    double m = 0.0;
    for (std::size_t c = 0; c < x_.size(); ++c)
        for (std::size_t i = 0; i + 1 < x_[c].size(); ++i)
            if (length_[c][i] > 0.0f)
                m = std::max(m, std::abs(static_cast<double>(glm::distance(x_[c][i], x_[c][i + 1])) / length_[c][i] - 1.0));
    return m;
}

}  // namespace coif
