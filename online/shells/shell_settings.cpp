#include "online/shells/shell_settings.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <vector>

#include "models/core/error.h"

namespace coif::gl {

namespace {
constexpr float kDeg = 0.017453292519943295f;
}  // namespace

int supersampling(const ShellSettings& settings) {
    if (settings.compositing != Compositing::exact) return 1;
    return std::clamp(static_cast<int>(std::lround(std::sqrt(static_cast<double>(settings.samples)))), 1, 4);
}

const char* compositing_name(Compositing c) {
    switch (c) {
        case Compositing::sorted: return "sorted";
        case Compositing::unsorted: return "unsorted";
        case Compositing::exact: return "exact";
    }
    return "?";
}

Compositing parse_compositing(const std::string& text, const std::string& file, const std::string& place) {
    for (Compositing c : {Compositing::sorted, Compositing::unsorted, Compositing::exact})
        if (text == compositing_name(c)) return c;
    throw Error(file, place, "'" + text + "' is not sorted, unsorted or exact");
}

// ---- parameters file -------------------------------------------------------------------------------

ShellSettings read_shell_settings(const std::string& path, ShellSettings s) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "", "cannot open the parameters file");
    std::stringstream text;
    text << in.rdbuf();
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text.str());
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(path, "byte " + std::to_string(e.byte), "not valid JSON");
    }
    if (!j.is_object()) throw Error(path, "JSON /", "expected an object of parameters");
    static const std::vector<std::string> known = {
        "eta", "sigma_a", "alpha_R_deg", "beta_R_deg", "alpha_TT_deg", "alpha_TRT_deg", "beta_TT_deg", "beta_TRT_deg",
        "ecc_a", "w_c_deg", "delta_eta_p", "d_b", "kappa_shadow", "segments", "lobes", "multiple", "neighbours", "debug", "compositing",
        "shadows", "own_cluster_shadow", "kappa_between", "d_f", "lighting_per_fragment", "fourier_order"};
    for (const auto& [key, value] : j.items())
        if (std::find(known.begin(), known.end(), key) == known.end())
            throw Error(path, "JSON /" + key, "unknown parameter (known: eta, sigma_a, alpha_R_deg, beta_R_deg, …)");
    const auto number = [&](const char* key) -> std::optional<float> {
        if (!j.contains(key)) return std::nullopt;
        if (!j[key].is_number()) throw Error(path, std::string("JSON /") + key, "expected a number");
        const double v = j[key].get<double>();
        if (!std::isfinite(v)) throw Error(path, std::string("JSON /") + key, "not a finite number");
        return static_cast<float>(v);
    };
    shading::HairParams& h = s.hair;
    float eta = h.eta, alpha_R = h.alpha_R, beta_R = h.beta_R, ecc = h.ecc_a, w_c = h.w_c;
    glm::vec3 sigma = h.sigma_a;
    if (auto v = number("eta")) eta = *v;
    if (auto v = number("alpha_R_deg")) alpha_R = *v * kDeg;
    if (auto v = number("beta_R_deg")) beta_R = *v * kDeg;
    if (auto v = number("ecc_a")) ecc = *v;
    if (auto v = number("w_c_deg")) w_c = *v * kDeg;
    if (j.contains("sigma_a")) {
        const auto& a = j["sigma_a"];
        if (!a.is_array() || a.size() != 3) throw Error(path, "JSON /sigma_a", "expected [r, g, b]");
        for (int c = 0; c < 3; ++c) {
            if (!a[c].is_number()) throw Error(path, "JSON /sigma_a/" + std::to_string(c), "expected a number");
            sigma[c] = a[c].get<float>();
        }
    }
    const float delta_eta_p = h.delta_eta_p, d_b = h.d_b;
    if (j.contains("alpha_R_deg") || j.contains("beta_R_deg"))
        h = shading::linked_hair_params(eta, sigma, alpha_R, beta_R, ecc, w_c);
    else {
        h.eta = eta; h.sigma_a = sigma; h.ecc_a = ecc; h.w_c = w_c;
    }
    h.delta_eta_p = delta_eta_p;
    h.d_b = d_b;
    if (auto v = number("alpha_TT_deg")) h.alpha_TT = *v * kDeg;
    if (auto v = number("alpha_TRT_deg")) h.alpha_TRT = *v * kDeg;
    if (auto v = number("beta_TT_deg")) h.beta_TT = *v * kDeg;
    if (auto v = number("beta_TRT_deg")) h.beta_TRT = *v * kDeg;
    if (auto v = number("delta_eta_p")) h.delta_eta_p = *v;
    if (auto v = number("d_b")) h.d_b = *v;
    if (auto v = number("kappa_shadow")) {
        if (*v < 0) throw Error(path, "JSON /kappa_shadow", "must be >= 0");
        s.kappa_shadow = *v;
    }
    if (auto v = number("segments")) s.config.segments = static_cast<int>(*v);
    if (auto v = number("neighbours")) {
        if (*v < 1 || *v > kMaxShellNeighbours || *v != std::floor(*v))
            throw Error(path, "JSON /neighbours", "must be an integer 1.." + std::to_string(kMaxShellNeighbours));
        s.neighbours = static_cast<int>(*v);
    }
    if (auto v = number("kappa_between")) {
        if (*v < 0 || *v > 100) throw Error(path, "JSON /kappa_between", "must be in [0, 100]");
        s.kappa_between = *v;
    }
    if (auto v = number("d_f")) {
        if (*v < 0 || *v > 1) throw Error(path, "JSON /d_f", "must be in [0, 1]");
        s.d_f = *v;
    }
    if (auto v = number("debug")) {
        if (*v < 0 || *v > 4 || *v != std::floor(*v)) throw Error(path, "JSON /debug", "must be 0, 1, 2, 3 or 4");
        s.debug = static_cast<int>(*v);
    }
    if (j.contains("compositing")) {
        if (!j["compositing"].is_string()) throw Error(path, "JSON /compositing", "expected \"sorted\", \"unsorted\" or \"exact\"");
        s.compositing = parse_compositing(j["compositing"].get<std::string>(), path, "JSON /compositing");
    }
    if (j.contains("own_cluster_shadow")) {
        if (!j["own_cluster_shadow"].is_boolean()) throw Error(path, "JSON /own_cluster_shadow", "expected true or false");
        s.own_cluster_shadow = j["own_cluster_shadow"].get<bool>();
    }
    if (auto v = number("fourier_order")) {
        if (*v < 1 || *v > 4 || *v != std::floor(*v)) throw Error(path, "JSON /fourier_order", "must be 1, 2, 3 or 4");
        s.fourier_order = static_cast<int>(*v);
    }
    if (j.contains("lighting_per_fragment")) {
        if (!j["lighting_per_fragment"].is_boolean()) throw Error(path, "JSON /lighting_per_fragment", "expected true or false");
        s.lighting_per_fragment = j["lighting_per_fragment"].get<bool>();
    }
    if (j.contains("shadows")) {
        if (!j["shadows"].is_boolean()) throw Error(path, "JSON /shadows", "expected true or false");
        s.shadows = j["shadows"].get<bool>();
    }
    if (j.contains("multiple")) {
        if (!j["multiple"].is_boolean()) throw Error(path, "JSON /multiple", "expected true or false");
        s.multiple = j["multiple"].get<bool>();
    }
    if (j.contains("lobes")) {
        const auto& lo = j["lobes"];
        if (!lo.is_object()) throw Error(path, "JSON /lobes", "expected {\"R\": bool, \"TT\": bool, \"TRT\": bool}");
        const std::array<std::string, 3> names = {"R", "TT", "TRT"};
        for (const auto& [key, value] : lo.items()) {
            const auto it = std::find(names.begin(), names.end(), key);
            if (it == names.end() || !value.is_boolean())
                throw Error(path, "JSON /lobes/" + key, "expected R, TT or TRT with true or false");
            const int bit = 1 << static_cast<int>(it - names.begin());
            s.lobes = value.get<bool>() ? (s.lobes | bit) : (s.lobes & ~bit);
        }
    }
    shading::validate(s.hair, path);
    shading::validate(s.config, path);
    return s;
}

}  // namespace coif::gl
