#pragma once
// What the shell renderer's tests share: a small database built once per test binary, its SATF index,
// a one-cluster style and two lights.
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "db/hrir_db.h"
#include "db/satf.h"
#include "models/character.h"
#include "models/hair_style.h"
#include "offline/srbf_lights.h"

namespace coif::test {

// A small database built once per test binary (40 sectors: ~3 s on 2 cores). The renderer's
// behaviour, not the look-up's quality, is under test here.
inline const HrirDatabase& test_db() {
    static const HrirDatabase db = [] {
        const auto path = std::filesystem::temp_directory_path() / ("coif-shell-test-" + std::to_string(::getpid()) + ".db");
        BuildOptions b;
        b.params.sectors = 40;
        b.threads = 2;
        build_database(b, path);
        HrirDatabase d = HrirDatabase::open(path);
        std::filesystem::remove(path);  // the mapping stays valid; nothing is left in the temp folder
        return d;
    }();
    return db;
}
inline const SatfIndex& test_index() {
    static const SatfIndex index(test_db(), SatfOptions{});
    return index;
}

// One straight cluster hanging along −y, 10 cm long, radius 1 cm, uniform density.
inline HairStyle one_cluster_style() {
    const char* text = R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 4, "s_t": 4, "s_u": 8, "grid": [8, 4], "mesh": [2, 2], "gaussian_width": 0.05},
      "clusters": [{"name": "c0", "trajectory": [[0, 0, 0], [0, -5, 0], [0, -10, 0]], "a": [1.0], "b": [1.0],
                    "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}}]})";
    return parse_style(text, "<test style>");
}

// The one-cluster style and an instance of it, turned 90° about y and moved 5 cm along x.
inline HairStyle prototype_and_instance() {
    const char* text = R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 4, "s_t": 4, "s_u": 8, "grid": [8, 4], "mesh": [2, 2], "gaussian_width": 0.05},
      "clusters": [{"name": "c0", "trajectory": [[0, 0, 0], [0, -5, 0], [0, -10, 0]], "a": [1.0], "b": [1.0],
                    "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}},
                   {"name": "c1", "instance_of": "c0",
                    "transform": {"scale": 1, "rotation": [0.70710678, 0, 0.70710678, 0], "translation": [5, 0, 0]}}]})";
    return parse_style(text, "<test style>");
}

// Two straight clusters hanging along −y from y = 0 to −10 at x = −3 ("left") and x = +3 ("right"); `skinned`: the left
// one on bone "a", the right one on bone "b" (models/skinning.h).
inline HairStyle two_cluster_style(bool skinned = false) {
    const std::string text = std::string(R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 4, "s_t": 4, "s_u": 8, "grid": [8, 4], "mesh": [2, 2], "gaussian_width": 0.05},
      "clusters": [{"name": "left", "trajectory": [[-3, 0, 0], [-3, -5, 0], [-3, -10, 0]], "a": [1.0], "b": [1.0],
                    "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}},
                   {"name": "right", "trajectory": [[3, 0, 0], [3, -5, 0], [3, -10, 0]], "a": [1.0], "b": [1.0],
                    "theta_deg": [0], "density": {"kind": "uniform", "value": 0.5}}])") +
                             (skinned ? R"(, "skinning": {"bones": ["a", "b"], "clusters": [[[0, 1.0]], [[1, 1.0]]]})" : "") + "}";
    return parse_style(text, "<two clusters>");
}

// A skinned "head" for two_cluster_style(true): two horizontal plates at y = 1 over the roots, x = −5 … −1 on bone "a"
// and x = 1 … 5 on bone "b".
inline BodyMesh skinned_head() {
    BodyMesh m;
    m.bones = {"a", "b"};
    for (float x : {-5.0f, -1.0f, 1.0f, 5.0f})
        for (float z : {-2.0f, 2.0f}) m.positions.push_back({x, 1.0f, z});
    m.normals.assign(m.positions.size(), glm::vec3(0, 1, 0));
    for (const glm::vec3& p : m.positions) {
        BoneInfluence b;
        b.weight = {1, 0, 0, 0};
        if (p.x > 0.0f) b.bone = {1, 0, 0, 0};
        m.influences.push_back(b);
    }
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 6, 5}, {5, 6, 7}};
    return m;
}

inline std::vector<SrbfLight> two_lights() {
    SrbfLight a, b;
    a.L = glm::vec3(2.0f, 1.8f, 1.5f);
    a.omega = glm::normalize(glm::vec3(0.2f, 0.8f, 0.6f));
    a.lambda = 0.3f;
    b.L = glm::vec3(0.3f, 0.4f, 0.6f);
    b.omega = glm::normalize(glm::vec3(-0.5f, 0.3f, -0.4f));
    b.lambda = 1.0f;
    return {a, b};
}

}  // namespace coif::test
