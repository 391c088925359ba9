#include "online/scene/hair_motion.h"

#include <chrono>

#include "models/core/error.h"
#include "online/shells/prepared_shells.h"

namespace coif::gl {
namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }
}  // namespace

HairMotion::HairMotion(const HairStyle& style, const BodyMesh& body, const glm::mat3& hair_orientation,
                       const glm::mat3& body_orientation) {
    if (!style.skinning) throw Error::parameter("style", "it has no bone weights (coif style import --skinning FILE.tfxbone)");
    if (body.bones.empty() || body.influences.size() != body.positions.size())
        throw Error::parameter("body", "it has no bone weights to pose it with (a .tfxmesh has them, an .obj has none)");
    body_ = body.turned(body_orientation);
    posed_ = body_;
    rest_ = rest_pose(body_);
    bool any = false;
    for (int b : bone_map(style.skinning->bones, body_.bones)) any = any || b >= 0;
    if (!any) throw Error::parameter("skinning", "none of the style's bones is in the body's skeleton (matched by name)");
    influences_ = style.skinning->clusters;
    style_bones_ = style.skinning->bones;
    rest_roots_ = cluster_roots(style, hair_orientation);
    for (const Cluster& c : style.clusters) {
        std::vector<glm::vec3> chain;  // the axis, sampled evenly in t, for the dynamics
        for (int i = 0; i < kChainPoints; ++i)
            chain.push_back(hair_orientation * glm::vec3(c.placement.apply(c.shape->position(static_cast<double>(i) / (kChainPoints - 1)))));
        chains_.push_back(std::move(chain));
    }
    roots_ = rest_roots_;
    transforms_.assign(style.clusters.size(), glm::mat4(1.0f));
}

void HairMotion::simulate(const DynamicsParams& params) {
    validate(params);
    dynamics_.emplace(chains_, params);
    dynamics_started_ = false;
}

void HairMotion::pose(ShellRenderer& renderer, const BonePose& pose) {
    auto t0 = Clock::now();
    if (pose.transforms.size() != body_.bones.size() || pose.pivots.size() != body_.bones.size())
        throw Error::parameter("pose", "it has " + std::to_string(pose.transforms.size()) + " bones, the body " +
                                           std::to_string(body_.bones.size()));
    const std::vector<glm::mat4> body_bones = pose.matrices();
    skin_body(body_, body_bones, posed_.positions, posed_.normals);
    const std::vector<glm::mat4> bones = map_bone_matrices(body_bones, body_.bones, style_bones_);
    for (std::size_t c = 0; c < influences_.size(); ++c) transforms_[c] = cluster_transform(influences_[c], bones, rest_roots_[c]);
    if (dynamics_) {  // the skinned transforms drive the roots; the simulated axes give the clusters' transforms
        if (!dynamics_started_) {
            dynamics_->reset(transforms_);
            dynamics_started_ = true;
        } else {
            collider_.set(posed_.positions, posed_.normals, kBodyColliderCell);
            dynamics_->step(transforms_, collider_);
        }
        for (std::size_t c = 0; c < transforms_.size(); ++c) transforms_[c] = dynamics_->cluster_transform(c);
    }
    for (std::size_t c = 0; c < influences_.size(); ++c) roots_[c] = glm::vec3(transforms_[c] * glm::vec4(rest_roots_[c], 1.0f));
    timings_.skinning_ms = ms_since(t0);
    t0 = Clock::now();
    renderer.set_body(&posed_, glm::mat3(1.0f), false);  // voxelized into the grid that set_cluster_transforms makes
    const double body_ms = ms_since(t0);
    renderer.set_cluster_transforms(transforms_);
    timings_.deformation_ms = renderer.move_timings().placement_ms;
    timings_.shadow_grid_ms = body_ms + renderer.move_timings().shadow_grid_ms;
}

}  // namespace coif::gl
