#pragma once
// Skinning a hairstyle and its character's body to the character's bones (linear blend skinning), GL-free.
//
// The TressFX data hold bone names and weights but no bind poses and no hierarchy (PROVENANCE.md). So a pose is a rigid
// transform per bone about that bone's pivot, the other bones at rest (identity):
//   pivot(b)  the centroid of the body's vertices whose largest weight is on bone b (bone_pivots);
//   M_b(x)    = pivot + R_b (x − pivot) + t_b, in the body's (and the hair's) frame (BonePose).
// A body vertex moves by the linear blend Σ_k w_k M_{b_k} of its four bones (skin_body). A cluster of the hair moves as
// one rigid body (its shells are similarity-placed meshes): the blend A = Σ_k w_k M_{b_k} of its four bones, the weights
// the mean of its strands' .tfxbone weights (cluster_influences, written into the style by `coif style import
// --skinning`), made rigid by taking the Gram–Schmidt frame of A's linear part as its rotation (A's own rotation when the
// bones' rotations agree) and the translation that puts the cluster's root where A puts it (cluster_transform): roots
// stay where linear blend skinning puts the skin under them.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <span>
#include <string>
#include <vector>

#include "models/character.h"

namespace coif {

// A cluster hairstyle's skinning: the skeleton's bone names and each cluster's four influences (indices into bones).
struct StyleSkinning {
    std::vector<std::string> bones;
    std::vector<BoneInfluence> clusters;  // one per cluster of the style, in its order
};

// Each cluster's weights: the mean of the weights of its strands (strand_cluster[i]: strand i's cluster, −1 none), the four
// largest kept and renormalised. Throws coif::Error::parameter for a cluster with no strand (every fitted cluster has
// some) or strand counts that differ.
StyleSkinning cluster_influences(const StrandSkinning& strands, std::span<const int> strand_cluster, std::size_t clusters);

// One rigid transform per bone, about its pivot; rest: identity rotation, zero translation.
struct BoneTransform {
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 translation{0.0f};
};
struct BonePose {
    std::vector<glm::vec3> pivots;          // per bone (bone_pivots)
    std::vector<BoneTransform> transforms;  // per bone
    // M_b as a matrix: x ↦ pivot + R (x − pivot) + t.
    glm::mat4 matrix(std::size_t bone) const;
};

// The centroid of the vertices whose largest weight is on each bone of `mesh` (mesh.bones order); a bone that is no
// vertex's largest gets the weighted centroid of the vertices it weighs, or the mesh's centroid if it weighs none.
std::vector<glm::vec3> bone_pivots(const BodyMesh& mesh);
// The rest pose of `mesh`'s skeleton: its pivots, every bone at rest.
BonePose rest_pose(const BodyMesh& mesh);

// The body's positions and normals under `pose` (linear blend skinning); `pose` is over mesh.bones. Throws
// coif::Error::parameter if the mesh is not skinned or the pose's bone count differs.
void skin_body(const BodyMesh& rest, const BonePose& pose, std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);

// A cluster's rigid transform under `pose` (see the header): `bone_of[k]` maps the influence's bones into the pose's
// (bone_map of the style's bone names to the mesh's; −1: not in the mesh, at rest); `root` the cluster's root.
glm::mat4 cluster_transform(const BoneInfluence& influence, std::span<const int> bone_of, const BonePose& pose, glm::vec3 root);

}  // namespace coif
