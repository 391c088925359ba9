// Skinning (models/skinning.h) and the animation spec (models/animation.h): a pose on one bone is that bone's rigid
// transform, clusters take their strands' mean weights, styles keep their skinning through a file, and bad specs are
// refused with the field named.
#include <cmath>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/animation.h"
#include "models/character.h"
#include "models/core/error.h"
#include "models/hair_style.h"
#include "models/skinning.h"

namespace coif {
namespace {
using ::testing::HasSubstr;

// A skinned strip of 6 vertices along x, bones "a" (x < 1) and "b" (x ≥ 1), blended at x = 1.
BodyMesh strip() {
    BodyMesh m;
    m.bones = {"a", "b"};
    for (int i = 0; i < 6; ++i) {
        m.positions.push_back({0.5f * i, 0.0f, 0.0f});
        m.positions.push_back({0.5f * i, 1.0f, 0.0f});
    }
    m.normals.assign(m.positions.size(), glm::vec3(0, 0, 1));
    for (const glm::vec3& p : m.positions) {
        BoneInfluence b;
        if (p.x < 0.9f) b.bone = {0, 0, 0, 0}, b.weight = {1, 0, 0, 0};
        else if (p.x < 1.1f) b.bone = {0, 1, 0, 0}, b.weight = {0.5f, 0.5f, 0, 0};
        else b.bone = {1, 0, 0, 0}, b.weight = {1, 0, 0, 0};
        m.influences.push_back(b);
    }
    for (std::uint32_t i = 0; i + 1 < 6; ++i) {
        m.triangles.push_back({2 * i, 2 * i + 2, 2 * i + 1});
        m.triangles.push_back({2 * i + 1, 2 * i + 2, 2 * i + 3});
    }
    return m;
}

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

TEST(Skinning, AllWeightOnOneBoneIsThatBonesRigidTransform) {
    const BodyMesh body = strip();
    BonePose pose = rest_pose(body);
    pose.transforms[1] = {glm::angleAxis(0.7f, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f))), glm::vec3(0.1f, -0.4f, 2.0f)};
    const glm::mat4 M = pose.matrix(1);
    // The pivot is where the bone's own vertices are centred (x = 1.5 … 2.5: at x = 1 the tie goes to the first bone),
    // and it moves only by the translation.
    EXPECT_NEAR(glm::distance(pose.pivots[1], glm::vec3(2.0f, 0.5f, 0.0f)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(apply(M, pose.pivots[1]), pose.pivots[1] + pose.transforms[1].translation), 0.0f, 1e-5f);
    std::vector<glm::vec3> p, n;
    skin_body(body, pose, p, n);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::vec3 x = body.positions[i];
        if (x.x > 1.1f) EXPECT_NEAR(glm::distance(p[i], apply(M, x)), 0.0f, 1e-5f) << i;        // bone b alone
        else if (x.x < 0.9f) EXPECT_NEAR(glm::distance(p[i], x), 0.0f, 1e-6f) << i;               // bone a, at rest
        else EXPECT_NEAR(glm::distance(p[i], 0.5f * (x + apply(M, x))), 0.0f, 1e-5f) << i;         // the blend
    }
    // A cluster weighted wholly on b moves as b does, about any root; and its transform is rigid.
    BoneInfluence on_b;
    on_b.bone = {1, 0, 0, 0};
    on_b.weight = {1, 0, 0, 0};
    const std::vector<glm::mat4> bones = pose.matrices();
    const glm::mat4 T = cluster_transform(on_b, bones, glm::vec3(3.0f, 2.0f, 1.0f));
    for (const glm::vec3 q : {glm::vec3(0.0f), glm::vec3(3, 2, 1), glm::vec3(-1, 5, 2)})
        EXPECT_NEAR(glm::distance(apply(T, q), apply(M, q)), 0.0f, 1e-4f);
    // Half on each: the root goes where the blend puts it, and the frame stays orthonormal.
    BoneInfluence half;
    half.bone = {0, 1, 0, 0};
    half.weight = {0.5f, 0.5f, 0, 0};
    const glm::vec3 root(1.0f, 0.5f, 0.0f);
    const glm::mat4 H = cluster_transform(half, bones, root);
    EXPECT_NEAR(glm::distance(apply(H, root), 0.5f * (root + apply(M, root))), 0.0f, 1e-5f);
    const glm::mat3 R(H);
    EXPECT_NEAR(glm::length(glm::transpose(R) * R[0] - glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::determinant(R), 1.0f, 1e-5f);
    // A bone of the style that the body lacks stays at rest; a bone outside the matrices is refused.
    const std::vector<glm::mat4> mapped = map_bone_matrices(bones, {"a", "b"}, {"a", "c"});
    EXPECT_EQ(mapped[0], bones[0]);
    EXPECT_EQ(mapped[1], glm::mat4(1.0f));
    EXPECT_EQ(cluster_transform(on_b, mapped, root), glm::mat4(1.0f));
    EXPECT_THROW(cluster_transform(on_b, std::span<const glm::mat4>(bones).first(1), root), Error);
}

TEST(Skinning, ClustersTakeTheMeanOfTheirStrandsWeights) {
    StrandSkinning s;
    s.bones = {"a", "b", "c"};
    BoneInfluence on_a, on_b, ab;
    on_a.weight = {1, 0, 0, 0};
    on_b.bone = {1, 0, 0, 0};
    on_b.weight = {1, 0, 0, 0};
    ab.bone = {0, 2, 0, 0};
    ab.weight = {0.5f, 0.5f, 0, 0};
    s.strands = {on_a, on_b, ab, on_a};
    const std::vector<int> cluster = {0, 0, 1, -1};
    const StyleSkinning out = cluster_influences(s, cluster, 2);
    ASSERT_EQ(out.clusters.size(), 2u);
    // Cluster 0: a and b, half each; cluster 1: a and c, half each (the unassigned strand counts nowhere).
    for (int k = 0; k < 2; ++k) EXPECT_FLOAT_EQ(out.clusters[0].weight[k], 0.5f);
    EXPECT_EQ(glm::ivec2(std::min(out.clusters[0].bone.x, out.clusters[0].bone.y), std::max(out.clusters[0].bone.x, out.clusters[0].bone.y)),
              glm::ivec2(0, 1));
    EXPECT_THROW(cluster_influences(s, std::vector<int>{0, 0, 0, 0}, 2), Error);  // cluster 1 has no strand
    EXPECT_THROW(cluster_influences(s, std::vector<int>{0, 1}, 2), Error);        // counts differ
}

TEST(Skinning, StyleFilesKeepTheirSkinningAndRefuseBadWeights) {
    const std::string head = R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 4, "s_t": 4, "s_u": 8, "grid": [8, 4], "mesh": [2, 2], "gaussian_width": 0.05},
      "clusters": [{"name": "c0", "trajectory": [[0, 0, 0], [0, -5, 0], [0, -10, 0]], "a": [1.0], "b": [1.0],
                    "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}}])";
    const HairStyle s = parse_style(head + R"(, "skinning": {"bones": ["neck", "head"], "clusters": [[[1, 0.6], [0, 0.2]]]}})", "s.json");
    ASSERT_TRUE(s.skinning);
    EXPECT_EQ(s.skinning->bones[1], "head");
    EXPECT_FLOAT_EQ(s.skinning->clusters[0].weight.x, 0.75f);  // renormalised
    const HairStyle again = parse_style(style_text(s), "again.json");
    ASSERT_TRUE(again.skinning);
    EXPECT_EQ(again.skinning->clusters[0].bone, s.skinning->clusters[0].bone);
    EXPECT_FLOAT_EQ(again.skinning->clusters[0].weight.y, s.skinning->clusters[0].weight.y);
    const auto refused = [&](const std::string& skinning, const std::string& what) {
        try {
            parse_style(head + ", \"skinning\": " + skinning + "}", "bad.json");
            ADD_FAILURE() << skinning << " was accepted";
        } catch (const Error& e) {
            EXPECT_THAT(std::string(e.what()), HasSubstr(what)) << skinning;
        }
    };
    refused(R"({"bones": ["a"], "clusters": [[[1, 1.0]]]})", "/skinning/clusters/0/0/0");     // bone out of range
    refused(R"({"bones": ["a"], "clusters": [[[0, 0.1]]]})", "below 0.5");
    refused(R"({"bones": ["a"], "clusters": [[[0, -1.0]]]})", "negative");
    refused(R"({"bones": ["a"], "clusters": []})", "/skinning/clusters");                      // one per cluster
    refused(R"({"bones": ["a"], "clusters": [[[0, NaN]]]})", "");
}

TEST(Animation, KeysAreInterpolatedAndTheOtherBonesRest) {
    const AnimationSpec s = parse_animation_spec(
        R"({"frames": 5, "fps": 24, "bones": ["b"], "keys": [{"frame": 1, "rotate_deg": [0, 40, 0]}, {"frame": 3, "rotate_deg": [0, 0, 0], "translate": [0, 2, 0]}]})",
        "turn.json");
    EXPECT_EQ(s.frames, 5);
    EXPECT_EQ(s.pivot, "b");
    const BodyMesh body = strip();
    const BonePose rest = rest_pose(body);
    const auto yaw = [&](int f) { return glm::degrees(glm::eulerAngles(animation_pose(s, body.bones, rest, f).transforms[1].rotation).y); };
    EXPECT_NEAR(yaw(0), 40.0f, 1e-3f);  // before the first key: held
    EXPECT_NEAR(yaw(2), 20.0f, 1e-3f);  // half way
    EXPECT_NEAR(yaw(4), 0.0f, 1e-3f);
    EXPECT_NEAR(animation_pose(s, body.bones, rest, 2).transforms[1].translation.y, 1.0f, 1e-6f);
    EXPECT_EQ(animation_pose(s, body.bones, rest, 2).transforms[0].rotation, glm::quat(1, 0, 0, 0));  // a rests
    EXPECT_FALSE(s.dynamics);
    const AnimationSpec windy = parse_animation_spec(
        R"({"frames": 2, "fps": 60, "bones": ["b"], "keys": [{"frame": 0}], "dynamics": {"wind": [300, 0, 0], "seed": 4}})", "w.json");
    ASSERT_TRUE(windy.dynamics);
    EXPECT_FLOAT_EQ(windy.dynamics->dt, 1.0f / 60.0f);
    EXPECT_EQ(windy.dynamics->wind, glm::vec3(300, 0, 0));
    EXPECT_EQ(windy.dynamics->seed, 4u);
    const AnimationSpec other = parse_animation_spec(R"({"frames": 1, "bones": ["nose"], "keys": [{"frame": 0}]})", "x.json");
    EXPECT_THROW(animation_pose(other, body.bones, rest, 0), Error);  // no such bone
}

TEST(Animation, BadSpecsAreRefusedNamingTheField) {
    const auto refused = [](const std::string& text, const std::string& what) {
        try {
            parse_animation_spec(text, "bad.json");
            ADD_FAILURE() << text << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), "bad.json");
            EXPECT_THAT(std::string(e.what()), HasSubstr(what)) << text;
        }
    };
    const std::string keys = R"("keys": [{"frame": 0}])";
    refused(R"({"frames": 0, "bones": ["b"], )" + keys + "}", "/frames");
    refused(R"({"frames": 2.5, "bones": ["b"], )" + keys + "}", "/frames");
    refused(R"({"frames": 2, "fps": 0, "bones": ["b"], )" + keys + "}", "/fps: must be > 0");
    refused(R"({"frames": 2, "bones": ["b"], "wind": [1, 0, 0], )" + keys + "}", "unknown key \"wind\"");
    refused(R"({"frames": 2, "bones": ["b"], "keys": [{"frame": 0, "rotate_deg": [0, NaN, 0]}]})", "not valid JSON");
    refused(R"({"frames": 2, "bones": ["b"], "keys": [{"frame": 0, "rotate_deg": [0, 1e999, 0]}]})", "not valid JSON");
    refused(R"({"frames": 2, "bones": ["b"], "keys": [{"frame": 1}, {"frame": 1}]})", "increasing frame order");
    refused(R"({"frames": 2, "bones": ["b"], "keys": [{"frame": 0, "spin": 3}]})", "unknown key \"spin\"");
    refused(R"({"frames": 2, "bones": [], )" + keys + "}", "/bones");
    refused(R"({"frames": 2, "bones": ["b"], "keys": []})", "/keys");
    refused(R"([1, 2])", "a JSON object");
    refused(R"({"frames": 2, "bones": ["b"], "dynamics": {"damping": 2}, )" + keys + "}", "/dynamics: must be in [0, 1]");
    refused(R"({"frames": 2, "bones": ["b"], "dynamics": {"substeps": 0}, )" + keys + "}", "/dynamics/substeps");
    refused(R"({"frames": 2, "bones": ["b"], "dynamics": {"wind": [1, 2]}, )" + keys + "}", "/dynamics/wind");
    refused(R"({"frames": 2, "bones": ["b"], "dynamics": {"stiff": 1}, )" + keys + "}", "unknown key \"stiff\"");
}

}  // namespace
}  // namespace coif
