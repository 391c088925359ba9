#include "models/skinning.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "models/core/error.h"

namespace coif {

StyleSkinning cluster_influences(const StrandSkinning& strands, std::span<const int> strand_cluster, std::size_t clusters) {
    if (strand_cluster.size() != strands.strands.size())
        throw Error::parameter("skinning", std::to_string(strands.strands.size()) + " skinned strands for " +
                                               std::to_string(strand_cluster.size()) + " strands of the hair");
    std::vector<std::vector<float>> sum(clusters, std::vector<float>(strands.bones.size(), 0.0f));
    std::vector<std::size_t> count(clusters, 0);
    for (std::size_t i = 0; i < strand_cluster.size(); ++i) {
        const int c = strand_cluster[i];
        if (c < 0 || static_cast<std::size_t>(c) >= clusters) continue;
        const BoneInfluence& b = strands.strands[i];
        for (int k = 0; k < 4; ++k) sum[static_cast<std::size_t>(c)][static_cast<std::size_t>(b.bone[k])] += b.weight[k];
        ++count[static_cast<std::size_t>(c)];
    }
    StyleSkinning out;
    out.bones = strands.bones;
    out.clusters.resize(clusters);
    for (std::size_t c = 0; c < clusters; ++c) {
        if (count[c] == 0) throw Error::parameter("skinning", "cluster " + std::to_string(c) + " has no strand to take weights from");
        std::vector<int> order(strands.bones.size());
        std::iota(order.begin(), order.end(), 0);
        std::partial_sort(order.begin(), order.begin() + std::min<std::size_t>(4, order.size()), order.end(),
                          [&](int a, int b) { return sum[c][static_cast<std::size_t>(a)] > sum[c][static_cast<std::size_t>(b)]; });
        BoneInfluence& b = out.clusters[c];
        float total = 0.0f;
        for (int k = 0; k < 4 && static_cast<std::size_t>(k) < order.size(); ++k) {
            b.bone[k] = order[static_cast<std::size_t>(k)];
            b.weight[k] = sum[c][static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
            total += b.weight[k];
        }
        b.weight /= total;
        for (int k = 0; k < 4; ++k)
            if (b.weight[k] == 0.0f) b.bone[k] = 0;
    }
    return out;
}

glm::mat4 BonePose::matrix(std::size_t bone) const {
    const BoneTransform& t = transforms[bone];
    const glm::mat3 R = glm::mat3_cast(t.rotation);
    glm::mat4 m(R);
    m[3] = glm::vec4(pivots[bone] - R * pivots[bone] + t.translation, 1.0f);
    return m;
}

std::vector<glm::mat4> BonePose::matrices() const {
    std::vector<glm::mat4> m(transforms.size());
    for (std::size_t b = 0; b < m.size(); ++b) m[b] = matrix(b);
    return m;
}

std::vector<glm::vec3> bone_pivots(const BodyMesh& mesh) {
    const std::size_t B = mesh.bones.size();
    std::vector<glm::dvec3> main_sum(B, glm::dvec3(0.0)), weighted(B, glm::dvec3(0.0));
    std::vector<double> main_count(B, 0.0), weight(B, 0.0);
    glm::dvec3 centroid(0.0);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        centroid += glm::dvec3(mesh.positions[i]);
        if (mesh.influences.empty()) continue;
        const BoneInfluence& b = mesh.influences[i];
        int best = 0;
        for (int k = 1; k < 4; ++k)
            if (b.weight[k] > b.weight[best]) best = k;
        main_sum[static_cast<std::size_t>(b.bone[best])] += glm::dvec3(mesh.positions[i]);
        main_count[static_cast<std::size_t>(b.bone[best])] += 1.0;
        for (int k = 0; k < 4; ++k) {
            weighted[static_cast<std::size_t>(b.bone[k])] += static_cast<double>(b.weight[k]) * glm::dvec3(mesh.positions[i]);
            weight[static_cast<std::size_t>(b.bone[k])] += b.weight[k];
        }
    }
    centroid /= std::max<double>(1.0, static_cast<double>(mesh.positions.size()));
    std::vector<glm::vec3> out(B);
    for (std::size_t b = 0; b < B; ++b)
        out[b] = glm::vec3(main_count[b] > 0 ? main_sum[b] / main_count[b] : weight[b] > 0 ? weighted[b] / weight[b] : centroid);
    return out;
}

BonePose rest_pose(const BodyMesh& mesh) {
    BonePose p;
    p.pivots = bone_pivots(mesh);
    p.transforms.assign(mesh.bones.size(), BoneTransform{});
    return p;
}

void skin_body(const BodyMesh& rest, std::span<const glm::mat4> m, std::vector<glm::vec3>& positions,
               std::vector<glm::vec3>& normals) {
    if (rest.influences.size() != rest.positions.size() || rest.bones.empty())
        throw Error::parameter("body", "the mesh has no bone weights to skin it with");
    if (m.size() != rest.bones.size())
        throw Error::parameter("pose", "it has " + std::to_string(m.size()) + " bones, the body " + std::to_string(rest.bones.size()));
    positions.resize(rest.positions.size());
    normals.resize(rest.normals.size());
    for (std::size_t i = 0; i < rest.positions.size(); ++i) {
        const BoneInfluence& b = rest.influences[i];
        glm::mat4 a(0.0f);
        for (int k = 0; k < 4; ++k) a += b.weight[k] * m[static_cast<std::size_t>(b.bone[k])];
        positions[i] = glm::vec3(a * glm::vec4(rest.positions[i], 1.0f));
        const glm::vec3 n = glm::transpose(glm::inverse(glm::mat3(a))) * rest.normals[i];
        normals[i] = glm::dot(n, n) > 0.0f ? glm::normalize(n) : rest.normals[i];
    }
}

void skin_body(const BodyMesh& rest, const BonePose& pose, std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
    if (pose.transforms.size() != rest.bones.size() || pose.pivots.size() != rest.bones.size())
        throw Error::parameter("pose", "it has " + std::to_string(pose.transforms.size()) + " bones, the body " +
                                           std::to_string(rest.bones.size()));
    skin_body(rest, pose.matrices(), positions, normals);
}

std::vector<glm::mat4> map_bone_matrices(std::span<const glm::mat4> from_matrices, const std::vector<std::string>& from,
                                         const std::vector<std::string>& to) {
    if (from_matrices.size() != from.size())
        throw Error::parameter("bones", std::to_string(from_matrices.size()) + " matrices for " + std::to_string(from.size()) + " bones");
    const std::vector<int> of = bone_map(to, from);
    std::vector<glm::mat4> out(to.size(), glm::mat4(1.0f));
    for (std::size_t b = 0; b < to.size(); ++b)
        if (of[b] >= 0) out[b] = from_matrices[static_cast<std::size_t>(of[b])];
    return out;
}

glm::mat4 cluster_transform(const BoneInfluence& influence, std::span<const glm::mat4> bones, glm::vec3 root) {
    glm::mat4 a(0.0f);
    for (int k = 0; k < 4; ++k) {
        const int b = influence.bone[k];
        if (b < 0 || static_cast<std::size_t>(b) >= bones.size())
            throw Error::parameter("skinning", "bone " + std::to_string(b) + " of " + std::to_string(bones.size()));
        a += influence.weight[k] * bones[static_cast<std::size_t>(b)];
    }
    // The rotation of A's linear part, from the identity: A's own when the bones' rotations agree.
    const glm::mat3 R = extract_rotation(glm::mat3(a), glm::mat3(1.0f), 50);
    glm::mat4 out(R);
    out[3] = glm::vec4(glm::vec3(a * glm::vec4(root, 1.0f)) - R * root, 1.0f);
    return out;
}

glm::mat3 extract_rotation(const glm::mat3& A, const glm::mat3& guess, int iterations) {
    glm::quat q = glm::quat_cast(guess);
    for (int k = 0; k < iterations; ++k) {
        const glm::mat3 R = glm::mat3_cast(q);
        const glm::vec3 num = glm::cross(R[0], A[0]) + glm::cross(R[1], A[1]) + glm::cross(R[2], A[2]);
        const float den = std::abs(glm::dot(R[0], A[0]) + glm::dot(R[1], A[1]) + glm::dot(R[2], A[2])) + 1e-9f;
        const glm::vec3 omega = num / den;
        const float w = glm::length(omega);
        if (w < 1e-9f) break;
        q = glm::normalize(glm::angleAxis(w, omega / w) * q);
    }
    return glm::mat3_cast(q);
}

}  // namespace coif
