#include "offline/srbf_lights.h"

#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "models/core/atomic_file.h"
#include "models/core/checksum.h"
#include "models/core/error.h"
#include "models/core/json_field.h"
#include "shaders/envmap.h"

namespace coif {
namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

constexpr const char* kFormat = "coif-srbf-lights";
constexpr int kVersion = 1;
// A stored centre may be off unit length by rounding of the printed digits; more means a broken file.
constexpr double kUnitTolerance = 1e-3;

constexpr const char* kConvention =
    "L(w) = sum_j L_j exp(2(w.w_j - 1)/lambda_j^2) (Xu et al. 2011 eq. 1, Table 1); w, w_j world "
    "directions, right-handed, y up; map orientation of shaders/envmap.glsl (row 0 = +y, centre column = +x, "
    "quarter column = -z); L_j linear RGB radiance in the source map's units";

ojson vec_json(const glm::dvec3& v) { return ojson::array({v.x, v.y, v.z}); }

class Reader {
public:
    Reader(const fs::path& source) : source_(source) {}

    [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
        throw Error(source_, "JSON " + (pointer.empty() ? std::string("/") : pointer), what);
    }
    const ojson& member(const ojson& object, const std::string& pointer, const char* key) const {
        if (!object.is_object()) fail(pointer, "expected an object");
        auto it = object.find(key);
        if (it == object.end()) fail(pointer + "/" + key, "missing");
        return *it;
    }
    double number(const ojson& j, const std::string& pointer) const {
        if (!j.is_number()) fail(pointer, "expected a number");
        const double v = j.get<double>();
        if (!std::isfinite(v)) fail(pointer, "not a finite number");
        return v;
    }
    std::int64_t integer(const ojson& j, const std::string& pointer) const {
        if (!j.is_number_integer()) fail(pointer, "expected an integer");
        return j.get<std::int64_t>();
    }
    std::string string(const ojson& j, const std::string& pointer) const {
        if (!j.is_string()) fail(pointer, "expected a string");
        return j.get<std::string>();
    }
    glm::dvec3 vec3(const ojson& j, const std::string& pointer) const {
        if (!j.is_array() || j.size() != 3) fail(pointer, "expected an array of 3 numbers");
        return {number(j[0], pointer + "/0"), number(j[1], pointer + "/1"), number(j[2], pointer + "/2")};
    }

private:
    fs::path source_;
};

}  // namespace

glm::vec3 evaluate_srbf_lights(std::span<const SrbfLight> lights, const glm::vec3& omega) {
    glm::vec3 sum(0.0f);
    for (const SrbfLight& light : lights) sum += light.L * glsl::srbf_G(omega, light.omega, light.lambda);
    return sum;
}

glm::dvec3 srbf_lights_energy(std::span<const SrbfLight> lights) {
    glm::dvec3 sum(0.0);
    for (const SrbfLight& light : lights) sum += glm::dvec3(light.L) * double(glsl::srbf_integral(light.lambda));
    return sum;
}

std::vector<SrbfLight> rotate_srbf_lights(std::span<const SrbfLight> lights, const glm::mat3& rotation) {
    std::vector<SrbfLight> out(lights.begin(), lights.end());
    for (SrbfLight& light : out) light.omega = glm::normalize(rotation * light.omega);
    return out;
}

std::vector<SrbfLight> rotate_srbf_lights_y(std::span<const SrbfLight> lights, float angle) {
    const glm::mat3 rotation(glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0.0f, 1.0f, 0.0f)));
    return rotate_srbf_lights(lights, rotation);
}

float srbf_rotation_radians(double degrees, const std::string& place) {
    if (!std::isfinite(degrees)) throw Error::parameter(place, "must be a finite number of degrees");
    return static_cast<float>(glm::radians(std::fmod(degrees, 360.0)));
}

nlohmann::ordered_json srbf_fit_record_json(const SrbfFitRecord& f) {
    return {{"lights", f.lights},
            {"seed", f.seed},
            {"fit_width", f.fit_width},
            {"supersampling", f.supersampling},
            {"lambda_min", f.lambda_min},
            {"lambda_max", f.lambda_max},
            {"max_iterations", f.max_iterations},
            {"iterations", f.iterations},
            {"termination", f.termination},
            {"seconds", f.seconds},
            {"relative_l2_error", f.relative_l2_error},
            {"relative_l2_error_fit_grid", f.relative_l2_error_fit_grid},
            {"energy_error", f.energy_error},
            {"energy_error_rgb", vec_json(f.energy_error_rgb)}};
}

std::string srbf_lights_to_json(const SrbfLightSet& set) {
    ojson j;
    j["format"] = kFormat;
    j["version"] = kVersion;
    j["convention"] = kConvention;
    if (set.source) {
        j["source"] = {{"file", set.source->file},
                       {"checksum", checksum_hex(set.source->checksum)},
                       {"width", set.source->width},
                       {"height", set.source->height}};
        if (set.source->rotation_y_deg != 0) j["source"]["rotation_y_deg"] = set.source->rotation_y_deg;
    }
    if (set.fit) j["fit"] = srbf_fit_record_json(*set.fit);
    ojson lights = ojson::array();
    for (const SrbfLight& light : set.lights)
        lights.push_back({{"L", vec_json(light.L)}, {"omega", vec_json(light.omega)}, {"lambda", light.lambda}});
    j["lights"] = std::move(lights);
    return j.dump(2) + "\n";
}

SrbfLightSet srbf_lights_from_json(std::string_view text, const fs::path& source) {
    const ojson j = parse_json<ojson>(text, source);
    Reader r(source);
    if (!j.is_object()) r.fail("", "expected a JSON object (a coif SRBF lights file)");
    if (r.string(r.member(j, "", "format"), "/format") != kFormat)
        r.fail("/format", std::string("expected \"") + kFormat + "\"");
    if (r.integer(r.member(j, "", "version"), "/version") != kVersion)
        r.fail("/version", "unsupported version (this coif reads version " + std::to_string(kVersion) + ")");

    SrbfLightSet set;
    if (j.contains("source")) {
        const ojson& s = j["source"];
        SrbfSource src;
        src.file = r.string(r.member(s, "/source", "file"), "/source/file");
        const std::string hex = r.string(r.member(s, "/source", "checksum"), "/source/checksum");
        if (hex.size() != 16 || hex.find_first_not_of("0123456789abcdef") != std::string::npos)
            r.fail("/source/checksum", "expected 16 lower-case hex digits");
        src.checksum = std::stoull(hex, nullptr, 16);
        src.width = int(r.integer(r.member(s, "/source", "width"), "/source/width"));
        src.height = int(r.integer(r.member(s, "/source", "height"), "/source/height"));
        if (src.width <= 0 || src.height <= 0) r.fail("/source/width", "map size must be positive");
        if (s.contains("rotation_y_deg")) src.rotation_y_deg = r.number(s["rotation_y_deg"], "/source/rotation_y_deg");
        set.source = src;
    }
    if (j.contains("fit")) {
        const ojson& f = j["fit"];
        const std::string p = "/fit";
        SrbfFitRecord rec;
        rec.lights = int(r.integer(r.member(f, p, "lights"), p + "/lights"));
        rec.seed = std::uint64_t(r.integer(r.member(f, p, "seed"), p + "/seed"));
        rec.fit_width = int(r.integer(r.member(f, p, "fit_width"), p + "/fit_width"));
        rec.supersampling = int(r.integer(r.member(f, p, "supersampling"), p + "/supersampling"));
        rec.lambda_min = r.number(r.member(f, p, "lambda_min"), p + "/lambda_min");
        rec.lambda_max = r.number(r.member(f, p, "lambda_max"), p + "/lambda_max");
        rec.max_iterations = int(r.integer(r.member(f, p, "max_iterations"), p + "/max_iterations"));
        rec.iterations = int(r.integer(r.member(f, p, "iterations"), p + "/iterations"));
        rec.termination = r.string(r.member(f, p, "termination"), p + "/termination");
        rec.seconds = r.number(r.member(f, p, "seconds"), p + "/seconds");
        rec.relative_l2_error = r.number(r.member(f, p, "relative_l2_error"), p + "/relative_l2_error");
        rec.relative_l2_error_fit_grid =
            r.number(r.member(f, p, "relative_l2_error_fit_grid"), p + "/relative_l2_error_fit_grid");
        rec.energy_error = r.number(r.member(f, p, "energy_error"), p + "/energy_error");
        rec.energy_error_rgb = r.vec3(r.member(f, p, "energy_error_rgb"), p + "/energy_error_rgb");
        set.fit = rec;
    }

    const ojson& lights = r.member(j, "", "lights");
    if (!lights.is_array()) r.fail("/lights", "expected an array");
    if (lights.empty() || lights.size() > size_t(kMaxSrbfLights))
        r.fail("/lights", std::to_string(lights.size()) + " lights; expected 1.." + std::to_string(kMaxSrbfLights));
    for (size_t i = 0; i < lights.size(); ++i) {
        const std::string p = "/lights/" + std::to_string(i);
        const ojson& l = lights[i];
        SrbfLight light;
        const glm::dvec3 L = r.vec3(r.member(l, p, "L"), p + "/L");
        if (L.x < 0 || L.y < 0 || L.z < 0) r.fail(p + "/L", "negative radiance");
        const glm::dvec3 omega = r.vec3(r.member(l, p, "omega"), p + "/omega");
        if (std::abs(glm::length(omega) - 1.0) > kUnitTolerance) r.fail(p + "/omega", "not a unit vector");
        const double lambda = r.number(r.member(l, p, "lambda"), p + "/lambda");
        if (!(lambda >= kSrbfLambdaMinAllowed && lambda <= kSrbfLambdaMaxAllowed))
            r.fail(p + "/lambda", "bandwidth " + std::to_string(lambda) + " outside [" +
                                      std::to_string(kSrbfLambdaMinAllowed) + ", " +
                                      std::to_string(kSrbfLambdaMaxAllowed) + "]");
        light.L = glm::vec3(L);
        light.omega = glm::vec3(glm::normalize(omega));
        light.lambda = float(lambda);
        set.lights.push_back(light);
    }
    if (set.fit && set.fit->lights != int(set.lights.size()))
        r.fail("/fit/lights", "says " + std::to_string(set.fit->lights) + " lights but /lights has " +
                                  std::to_string(set.lights.size()));
    return set;
}

void write_srbf_lights(const fs::path& path, const SrbfLightSet& set) {
    write_file_atomic(path, srbf_lights_to_json(set));
}

SrbfLightSet read_srbf_lights(const fs::path& path) {
    const std::vector<std::byte> bytes = read_file_bytes(path);
    if (bytes.empty()) throw Error(path, "", "empty file");
    return srbf_lights_from_json(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

}  // namespace coif
