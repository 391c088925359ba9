#pragma once
// `coif render --animate SPEC`: a head (or any bones) moved through keyframes, as a JSON file.
//
//   {"frames": 60,                          frames to render, 1 … kMaxAnimationFrames
//    "fps": 30,                             frames per second (> 0; the keys' times are frames, this labels the sheet)
//    "bones": ["frenchHornMonster_head_JNT", …],   the bones the keys move (names of the body's skeleton), together
//    "pivot": "frenchHornMonster_head_JNT", the bone whose pivot they turn about (default: the first of "bones")
//    "keys": [{"frame": 0, "rotate_deg": [0, -30, 0], "translate": [0, 0, 0]}, …],
//    "dynamics": {"wind": [300, 0, 0], "gust": 0.3, "gravity": [0, -981, 0], "damping": 0.02, "bend_stiffness": 0.6,
//                 "shape_stiffness": 0.1, "collision_margin": 0.3, "substeps": 4, "iterations": 8, "seed": 1}}
//                                           optional: simulate the hair
//
// With "dynamics" the clusters' axes are simulated (models/hair_dynamics.h), one step of 1/fps s per frame, each key
// optional (the defaults above; wind and gravity are accelerations in scene units per s²); without it they follow the
// skin rigidly.
//
// Each key gives the moved bones' rotation (Euler angles in degrees about x, then y, then z, in the renderer's y-up
// space) and translation (scene units) at a frame; between keys both are interpolated linearly (the rotation through
// its Euler angles), and before the first or after the last key they hold. Frames are 0 … frames − 1. Every other bone
// stays at rest (models/skinning.h: the data hold no hierarchy). Unknown keys, NaN or infinite numbers, zero frames, a
// non-positive fps, keys out of frame order or no key are refused with a coif::Error naming the file and the field.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "models/hair_dynamics.h"
#include "models/skinning.h"

namespace coif {

inline constexpr int kMaxAnimationFrames = 10'000;

struct AnimationKey {
    double frame = 0;
    glm::dvec3 rotate_deg{0.0}, translate{0.0};
};

struct AnimationSpec {
    int frames = 1;
    double fps = 30;
    std::vector<std::string> bones;
    std::string pivot;  // a bone's name
    std::vector<AnimationKey> keys;
    std::optional<DynamicsParams> dynamics;  // "dynamics", its dt 1 / fps
};

AnimationSpec read_animation_spec(const std::filesystem::path& path);
AnimationSpec parse_animation_spec(std::string_view text, const std::filesystem::path& name);

// The pose at `frame` over `skeleton` (whose rest pose is `rest`): the spec's bones turned about its pivot bone's pivot.
// Throws coif::Error::parameter (naming the bone) if a bone of the spec is not in the skeleton.
BonePose animation_pose(const AnimationSpec& spec, const std::vector<std::string>& skeleton, const BonePose& rest, int frame);

}  // namespace coif
