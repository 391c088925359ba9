#include "models/animation.h"

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "models/core/atomic_file.h"
#include "models/core/error.h"
#include "models/core/json_field.h"
#include "models/core/units.h"

namespace coif {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

struct Reader {
    const fs::path& file;
    [[noreturn]] void fail(const std::string& where, const std::string& what) const { throw Error(file, "JSON " + where, what); }
    double number(const json& v, const std::string& where) const {
        if (!v.is_number()) fail(where, "expected a number, got " + std::string(v.type_name()));
        const double x = v.get<double>();
        if (!std::isfinite(x)) fail(where, "NaN or infinity; every number must be finite");
        return x;
    }
    glm::dvec3 vec3(const json& v, const std::string& where) const {
        if (!v.is_array() || v.size() != 3) fail(where, "expected an array of 3 numbers");
        return {number(v[0], where + "/0"), number(v[1], where + "/1"), number(v[2], where + "/2")};
    }
    std::string string(const json& v, const std::string& where) const {
        if (!v.is_string()) fail(where, "expected a string, got " + std::string(v.type_name()));
        return v.get<std::string>();
    }
    void only(const json& obj, const std::string& where, std::initializer_list<const char*> keys) const {
        for (const auto& [k, v] : obj.items()) {
            bool known = false;
            for (const char* key : keys) known = known || k == key;
            if (!known) {
                std::string list;
                for (const char* key : keys) list += std::string(list.empty() ? "" : ", ") + key;
                fail(where + "/" + k, "unknown key \"" + k + "\" (known: " + list + ")");
            }
        }
    }
};

}  // namespace

AnimationSpec parse_animation_spec(std::string_view text, const fs::path& file) {
    const Reader rd{file};
    const json doc = parse_json(text, file);
    if (!doc.is_object()) rd.fail("/", "an animation is a JSON object");
    rd.only(doc, "", {"frames", "fps", "bones", "pivot", "keys", "dynamics"});
    AnimationSpec s;
    if (!doc.contains("frames")) rd.fail("/frames", "missing field \"frames\"");
    const double frames = rd.number(doc["frames"], "/frames");
    if (frames != std::floor(frames) || frames < 1 || frames > kMaxAnimationFrames)
        rd.fail("/frames", "must be a whole number of frames, 1.." + std::to_string(kMaxAnimationFrames));
    s.frames = static_cast<int>(frames);
    if (doc.contains("fps")) {
        s.fps = rd.number(doc["fps"], "/fps");
        if (!(s.fps > 0)) rd.fail("/fps", "must be > 0");
    }
    if (!doc.contains("bones") || !doc["bones"].is_array() || doc["bones"].empty() || doc["bones"].size() > kMaxBones)
        rd.fail("/bones", "expected a non-empty array of bone names");
    for (std::size_t i = 0; i < doc["bones"].size(); ++i) s.bones.push_back(rd.string(doc["bones"][i], "/bones/" + std::to_string(i)));
    s.pivot = doc.contains("pivot") ? rd.string(doc["pivot"], "/pivot") : s.bones.front();
    if (!doc.contains("keys") || !doc["keys"].is_array() || doc["keys"].empty()) rd.fail("/keys", "expected a non-empty array of keys");
    if (doc["keys"].size() > static_cast<std::size_t>(kMaxAnimationFrames)) rd.fail("/keys", "more keys than frames allowed");
    for (std::size_t i = 0; i < doc["keys"].size(); ++i) {
        const std::string p = "/keys/" + std::to_string(i);
        const json& k = doc["keys"][i];
        if (!k.is_object()) rd.fail(p, "a key is an object");
        rd.only(k, p, {"frame", "rotate_deg", "translate"});
        AnimationKey key;
        if (!k.contains("frame")) rd.fail(p + "/frame", "missing field \"frame\"");
        key.frame = rd.number(k["frame"], p + "/frame");
        if (key.frame < 0) rd.fail(p + "/frame", "must be ≥ 0");
        if (!s.keys.empty() && !(key.frame > s.keys.back().frame)) rd.fail(p + "/frame", "keys must come in increasing frame order");
        if (k.contains("rotate_deg")) key.rotate_deg = rd.vec3(k["rotate_deg"], p + "/rotate_deg");
        if (k.contains("translate")) key.translate = rd.vec3(k["translate"], p + "/translate");
        s.keys.push_back(key);
    }
    if (doc.contains("dynamics")) {
        const json& d = doc["dynamics"];
        if (!d.is_object()) rd.fail("/dynamics", "expected an object");
        rd.only(d, "/dynamics", {"wind", "gust", "gravity", "damping", "bend_stiffness", "shape_stiffness", "collision_margin", "substeps", "iterations", "seed"});
        DynamicsParams p;
        p.dt = static_cast<float>(1.0 / s.fps);
        const auto count = [&](const char* key, double lo, double hi) {
            const double v = rd.number(d[key], std::string("/dynamics/") + key);
            if (v != std::floor(v) || v < lo || v > hi)
                rd.fail(std::string("/dynamics/") + key, "must be a whole number in " + number_text(lo) + ".." +
                                                             number_text(hi));
            return v;
        };
        if (d.contains("wind")) p.wind = glm::vec3(rd.vec3(d["wind"], "/dynamics/wind"));
        if (d.contains("gravity")) p.gravity = glm::vec3(rd.vec3(d["gravity"], "/dynamics/gravity"));
        if (d.contains("gust")) p.gust = static_cast<float>(rd.number(d["gust"], "/dynamics/gust"));
        if (d.contains("damping")) p.damping = static_cast<float>(rd.number(d["damping"], "/dynamics/damping"));
        if (d.contains("bend_stiffness")) p.bend_stiffness = static_cast<float>(rd.number(d["bend_stiffness"], "/dynamics/bend_stiffness"));
        if (d.contains("shape_stiffness")) p.shape_stiffness = static_cast<float>(rd.number(d["shape_stiffness"], "/dynamics/shape_stiffness"));
        if (d.contains("collision_margin")) p.collision_margin = static_cast<float>(rd.number(d["collision_margin"], "/dynamics/collision_margin"));
        if (d.contains("substeps")) p.substeps = static_cast<int>(count("substeps", 1, 64));
        if (d.contains("iterations")) p.iterations = static_cast<int>(count("iterations", 1, 64));
        if (d.contains("seed")) p.seed = static_cast<std::uint32_t>(count("seed", 0, 4294967295.0));
        try {
            validate(p);
        } catch (const Error& e) {
            rd.fail("/dynamics", e.problem() + " (" + e.place() + ")");
        }
        s.dynamics = p;
    }
    return s;
}

AnimationSpec read_animation_spec(const fs::path& path) {
    const std::vector<std::byte> b = read_file_bytes(path);
    return parse_animation_spec(std::string_view(reinterpret_cast<const char*>(b.data()), b.size()), path);
}

BonePose animation_pose(const AnimationSpec& spec, const std::vector<std::string>& skeleton, const BonePose& rest, int frame) {
    const auto pivot = find_bone(skeleton, spec.pivot);
    if (!pivot) throw Error::parameter("animation pivot", "no bone named \"" + spec.pivot + "\" in the body's skeleton");
    // The key pair around `frame`, and how far between them.
    const auto& k = spec.keys;
    AnimationKey at = k.front();
    if (frame >= k.back().frame) at = k.back();
    else
        for (std::size_t i = 0; i + 1 < k.size(); ++i)
            if (frame >= k[i].frame && frame < k[i + 1].frame) {
                const double f = (frame - k[i].frame) / (k[i + 1].frame - k[i].frame);
                at.rotate_deg = glm::mix(k[i].rotate_deg, k[i + 1].rotate_deg, f);
                at.translate = glm::mix(k[i].translate, k[i + 1].translate, f);
            }
    BonePose pose = rest;
    const glm::quat q(glm::vec3(glm::radians(at.rotate_deg)));  // x, then y, then z
    for (const std::string& name : spec.bones) {
        const auto b = find_bone(skeleton, name);
        if (!b) throw Error::parameter("animation bones", "no bone named \"" + name + "\" in the body's skeleton");
        const auto i = static_cast<std::size_t>(*b);
        pose.pivots[i] = rest.pivots[static_cast<std::size_t>(*pivot)];
        pose.transforms[i] = {q, glm::vec3(at.translate)};
    }
    return pose;
}

}  // namespace coif
