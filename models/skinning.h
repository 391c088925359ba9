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
// --skinning`), made rigid by taking the rotation part of A's linear part as its rotation (extract_rotation; A's own
// rotation when the bones' rotations agree) and the translation that puts the cluster's root where A puts it
// (cluster_transform): roots stay where linear blend skinning puts the skin under them.
//   The functions that pose take the bones as matrices, M_b per bone (an engine's skinning matrices: each bone's
// rest-to-posed transform, in the body's frame): BonePose::matrices() makes them from a pose about pivots.
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
    std::vector<glm::mat4> matrices() const;  // every bone's
};

// The centroid of the vertices whose largest weight is on each bone of `mesh` (mesh.bones order); a bone that is no
// vertex's largest gets the weighted centroid of the vertices it weighs, or the mesh's centroid if it weighs none.
std::vector<glm::vec3> bone_pivots(const BodyMesh& mesh);
// The rest pose of `mesh`'s skeleton: its pivots, every bone at rest.
BonePose rest_pose(const BodyMesh& mesh);

// The body's positions and normals under the bones' matrices `bones` (over mesh.bones; linear blend skinning). Throws
// coif::Error::parameter if the mesh is not skinned or the bone count differs.
void skin_body(const BodyMesh& rest, std::span<const glm::mat4> bones, std::vector<glm::vec3>& positions,
               std::vector<glm::vec3>& normals);
void skin_body(const BodyMesh& rest, const BonePose& pose, std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);

// Matrices over the bones `to` from matrices over the bones `from`, matched by name (bone_map); a bone of `to` that
// `from` lacks stays at rest (identity).
std::vector<glm::mat4> map_bone_matrices(std::span<const glm::mat4> from_matrices, const std::vector<std::string>& from,
                                         const std::vector<std::string>& to);

// A cluster's rigid transform (see the header) under the bones' matrices `bones`, indexed as the influence's bones are;
// `root` the cluster's root. Throws coif::Error::parameter for an influence's bone outside `bones`.
glm::mat4 cluster_transform(const BoneInfluence& influence, std::span<const glm::mat4> bones, glm::vec3 root);

// The rotation part of a 3×3 matrix A (Müller et al. 2016, "A robust method to extract the rotational part of
// deformations"), iterated from `guess` (a rotation): the rotation closest to A, whatever the order of its columns.
glm::mat3 extract_rotation(const glm::mat3& A, const glm::mat3& guess, int iterations = 20);

}  // namespace coif
