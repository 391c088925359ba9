#pragma once
// A skinned hairstyle on its character, posed frame by frame (issue "Hair that moves on a character"): the character's
// bones are posed (models/skinning.h: a rigid transform per bone about its pivot), and each frame
//   skinning     the body's vertices by linear blend skinning, each cluster's rigid transform from its bone weights;
//   deformation  the clusters' instances and lighting samples moved (ShellRenderer::set_cluster_transforms);
//   shadow grid  the grid's strands, moved with their clusters, voxelized again with the posed body (the same call,
//                after ShellRenderer::set_body);
// then the renderer's shadow and lighting passes follow on its next draw. The SATF look-ups stay: a cluster moved rigidly
// keeps its density. That holds while clusters move as rigid bodies; strands that bend within a cluster (simulation, a
// cluster spanning a joint) would change the sectors' densities, which this does not follow.
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "models/character.h"
#include "models/hair_dynamics.h"
#include "models/hair_style.h"
#include "models/skinning.h"
#include "online/shell_renderer.h"

namespace coif::gl {

struct MotionTimings {  // of the last pose(), wall-clock milliseconds
    double skinning_ms = 0;    // the body's vertices and the clusters' transforms, with the simulation when on
    double deformation_ms = 0, shadow_grid_ms = 0;
};

class HairMotion {
public:
    // `style` must carry skinning (coif style import --skinning) and `body` bone weights; bones are matched by name.
    // `hair_orientation` turns the style into the renderer's space (style_orientation), `body_orientation` the body
    // (style_orientation · style_source_rotation). Throws coif::Error::parameter if either is not skinned or no bone of
    // the style is in the body's skeleton.
    HairMotion(const HairStyle& style, const BodyMesh& body, const glm::mat3& hair_orientation, const glm::mat3& body_orientation);

    // The rest pose, over the body's bones, with pivots in the renderer's space.
    const BonePose& rest() const { return rest_; }
    const std::vector<std::string>& bones() const { return body_.bones; }
    // Poses the hair and the body in `renderer` (made from the same style, with this body set or not).
    void pose(ShellRenderer& renderer, const BonePose& pose);
    // From the next pose on, the clusters' axes are simulated (models/hair_dynamics.h) with their roots on the skinned
    // ones, colliding with the posed body, one time step of `params.dt` per pose; each cluster is drawn by the rigid
    // transform that matches its simulated axis (shape matching). The first pose after this starts the simulation at
    // rest there (as after a teleport: reset_dynamics). Throws coif::Error::parameter for bad parameters.
    void simulate(const DynamicsParams& params);
    void reset_dynamics() { dynamics_started_ = false; }
    const ClusterDynamics* dynamics() const { return dynamics_ ? &*dynamics_ : nullptr; }
    const MotionTimings& timings() const { return timings_; }
    // The posed body of the last pose() (the rest body before), in the renderer's space.
    const BodyMesh& posed_body() const { return posed_; }
    // The clusters' roots as posed by the last pose() (cooked before), and their transforms.
    const std::vector<glm::vec3>& roots() const { return roots_; }
    const std::vector<glm::mat4>& cluster_transforms() const { return transforms_; }

private:
    BodyMesh body_, posed_;                 // in the renderer's space
    std::vector<std::string> style_bones_;
    std::vector<BoneInfluence> influences_;  // per cluster, over the style's bones
    std::vector<glm::vec3> rest_roots_, roots_;
    std::vector<std::vector<glm::vec3>> chains_;  // each cluster's axis at rest (kChainPoints points)
    std::vector<glm::mat4> transforms_;
    BonePose rest_;
    MotionTimings timings_;
    std::optional<ClusterDynamics> dynamics_;
    bool dynamics_started_ = false;
    BodyCollider collider_;
};

}  // namespace coif::gl
