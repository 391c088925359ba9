#pragma once
// Hair dynamics on the clusters' axes (issue "Hair that moves on a character", simulated motion), GL-free.
//
// Each cluster's axis is a chain of kChainPoints points, sampled evenly in t from its trajectory (root first): the
// trajectory's shape at the resolution its B-spline control points give it. Position-based dynamics (Müller et al.
// 2007) moves them, at a fixed time step `dt` split into `substeps`:
//   - the first two points are pinned to where the character puts them (the skinned root frame): TressFX pins the
//     two root points of every guide strand (w = 0 in its .tfx), which holds the root's direction;
//   - the others fall under gravity and wind (an acceleration, gusting by a seeded, deterministic noise), damped, and
//     are pulled back by `shape_stiffness` towards where the skinned root frame puts their rest positions (TressFX's
//     global shape constraint: a styled mohawk keeps its spikes instead of falling flat);
//   - `iterations` sweeps project the bending constraints (points two apart keep their rest distance, with
//     `bend_stiffness`) and the body's collisions (a point closer than `collision_margin` to the body's surface, or on
//     its inner side, is pushed out along the nearest vertex's normal); then the lengths by "dynamic follow the leader"
//     (Müller et al. 2012: each point put back at its rest distance from its parent, root outward: exact lengths in one
//     sweep, with the velocity correction that keeps it from adding energy);
//   - velocities are the positions' change over the substep.
// It is deterministic: the same inputs, seed and steps give the same positions, bit for bit.
//
// The renderer's shells are rigid, similarity-placed meshes with SATF look-ups made for their rest density, so a
// simulated cluster is drawn by the rigid transform that best matches its chain to the rest chain about the root
// (shape matching: the rotation of Σᵢ (xᵢ − x₀)(x⁰ᵢ − x⁰₀)ᵀ, and the translation that keeps the root on x₀, which is
// pinned to the skin; cluster_transform). The bend within a cluster is what this leaves out.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace coif {

inline constexpr int kChainPoints = 8;

struct DynamicsParams {
    float dt = 1.0f / 30.0f;                       // s, fixed
    int substeps = 4;
    int iterations = 8;
    glm::vec3 gravity{0.0f, -981.0f, 0.0f};        // scene units (cm) / s²
    glm::vec3 wind{0.0f};                          // acceleration, cm / s²; 0: none
    float gust = 0.3f;                             // the wind's relative random variation (0: steady)
    float damping = 0.02f;                         // share of the velocity lost per substep
    float bend_stiffness = 0.6f;                   // 0 … 1 per iteration
    float shape_stiffness = 0.1f;                  // 0 … 1 per substep: the pull back to the skinned rest shape
    float collision_margin = 0.3f;                 // cm kept between a point and the body's surface
    std::uint32_t seed = 1;
};

// Throws coif::Error::parameter naming the field for a value out of its range (dt > 0, substeps and iterations 1..64,
// damping and the stiffnesses in [0, 1], finite vectors, margin ≥ 0).
void validate(const DynamicsParams& p);

// The collider's hash cell for a character's body, scene units (cm): the Ratboy's vertices lie ~1 cm apart.
inline constexpr float kBodyColliderCell = 2.0f;

// The body the chains collide with: its surface points and outward normals (a skinned body's vertices), hashed.
class BodyCollider {
public:
    BodyCollider() = default;
    // `cell`: the hash grid's cell edge (≥ the margin; scene units).
    void set(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals, float cell);
    // Pushes `p` out along the nearest vertex's normal if it lies within `margin` of that vertex's tangent plane on
    // the inner side (and within two cells of it); returns whether it moved.
    bool push_out(glm::vec3& p, float margin) const;
    // The signed distance of `p` from its nearest vertex's tangent plane (< 0 inside), or +inf without a vertex near.
    float signed_distance(glm::vec3 p) const;
    bool empty() const { return positions_.empty(); }

private:
    std::int64_t key(glm::ivec3 c) const;
    const glm::vec3* nearest(glm::vec3 p, std::size_t* index) const;
    std::vector<glm::vec3> positions_, normals_;
    std::vector<std::int64_t> keys_;     // sorted cell keys
    std::vector<std::uint32_t> order_;   // vertex indices in key order
    float cell_ = 1.0f;
};

class ClusterDynamics {
public:
    // `rest`: per cluster its chain at rest (kChainPoints points, root first), in the space the roots are posed in.
    explicit ClusterDynamics(std::vector<std::vector<glm::vec3>> rest, DynamicsParams params = {});

    // Places every chain where `root_frames` (per cluster: the rigid transform of its root from rest) puts its rest
    // chain, at rest (zero velocity): the start, and after a teleport.
    void reset(const std::vector<glm::mat4>& root_frames);
    // One time step: the pinned points follow `root_frames`, the others move (see the header).
    void step(const std::vector<glm::mat4>& root_frames, const BodyCollider& body);

    const std::vector<glm::vec3>& chain(std::size_t cluster) const { return x_[cluster]; }
    std::size_t clusters() const { return x_.size(); }
    // The rigid transform (rotation, translation) that best takes the rest chain to the current one.
    glm::mat4 cluster_transform(std::size_t cluster) const;
    // Σ ½ v² + the potential of gravity −g·x over the free points (unit mass each): with no wind, no driven roots
    // and damping it does not grow.
    double energy() const;
    // The largest relative change of a segment's length from rest, over every chain.
    double max_stretch() const;
    int steps() const { return steps_; }

private:
    DynamicsParams p_;
    std::vector<std::vector<glm::vec3>> rest_, x_, v_;
    std::vector<std::vector<float>> length_, bend_;  // rest distances: i to i+1, i to i+2
    int steps_ = 0;
};

}  // namespace coif
