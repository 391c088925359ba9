#include "shaders/hair_parameters.h"

#include <cmath>
#include <limits>

#include "models/core/error.h"

namespace coif::shading {

namespace {

// Degrees at the interface, radians in the struct. The file has always converted in float,
// radians = float(degrees) · kDeg, so that a file means the same radians as before (and as
// default_hair_params' -7.5f · deg); to_degrees inverts it exactly wherever a float does.
constexpr float kDeg = 0.017453292519943295f;
constexpr double kDegD = 0.017453292519943295;

float to_radians(double degrees) { return static_cast<float>(degrees) * kDeg; }

// The float degrees d nearest rad / kDeg with to_radians(d) == rad; where no float maps there exactly
// (about 9 % of radian floats: the product skips some), the nearest one (1 ulp of radians off).
double to_degrees(float radians) {
    const float d0 = static_cast<float>(static_cast<double>(radians) / kDegD);
    float up = d0, down = d0;
    for (int step = 0; step <= 4; ++step) {
        if (to_radians(up) == radians) return up;
        if (to_radians(down) == radians) return down;
        up = std::nextafter(up, std::numeric_limits<float>::infinity());
        down = std::nextafter(down, -std::numeric_limits<float>::infinity());
    }
    return d0;
}

using Table = ParamTable<HairParameters>;

template <class F>
Param<HairParameters> angle_param(std::string key, double min_rad, double max_rad, std::string help, F field) {
    Param<HairParameters> p =
        real_param<HairParameters>(std::move(key), "deg", min_rad / kDegD, max_rad / kDegD, std::move(help), field);
    p.get = [field](const HairParameters& h, int) { return to_degrees(field(h)); };
    p.set = [field](HairParameters& h, int, double v) { field(h) = to_radians(v); };
    return p;
}

// α_R and β_R restore 000's links of TT and TRT (the table applies the TT/TRT keys after them).
Param<HairParameters> linking(Param<HairParameters> p) {
    p.set = [set = p.set](HairParameters& h, int c, double v) {
        set(h, c, v);
        link_lobes_to_R(h.fibre);
    };
    return p;
}

// A TT/TRT angle is written only where it differs from its link.
template <class F>
Param<HairParameters> linked_angle(std::string key, double min_rad, double max_rad, std::string help, F field) {
    Param<HairParameters> p = angle_param(std::move(key), min_rad, max_rad, std::move(help), field);
    p.written = [field](const HairParameters& h) {
        HairParams linked = h.fibre;
        link_lobes_to_R(linked);
        HairParameters l = h;
        l.fibre = linked;
        return field(l) != field(h);
    };
    return p;
}

Table make_table() {
    constexpr double kPi = 3.14159265358979323846;
    std::vector<std::string> lobe_names;
    for (const Lobe& lobe : kLobes) lobe_names.emplace_back(lobe.name);
    Table t;
    Param<HairParameters> eta = real_param<HairParameters>("eta", "", kMinEta, kMaxEta, "index of refraction η",
                                                           [](auto& h) -> auto& { return h.fibre.eta; });
    eta.min_exclusive = true;
    t.push_back(eta);
    t.push_back(rgb_param<HairParameters>("sigma_a", "per unit fibre radius", 0.0, kMaxSigmaA, "absorption σa, R G B",
                                          [](auto& h) -> auto& { return h.fibre.sigma_a; }));
    t.push_back(linking(angle_param("alpha_R_deg", -kMaxAlpha, kMaxAlpha,
                                    "longitudinal shift α_R (links α_TT = -α_R/2, α_TRT = -3α_R/2)",
                                    [](auto& h) -> auto& { return h.fibre.alpha_R; })));
    t.push_back(linking(angle_param("beta_R_deg", kMinBeta, kMaxBeta,
                                    "longitudinal width β_R, 000's bandwidth (links β_TT = β_R/2, β_TRT = 2β_R)",
                                    [](auto& h) -> auto& { return h.fibre.beta_R; })));
    t.push_back(linked_angle("alpha_TT_deg", -kMaxAlpha, kMaxAlpha, "α_TT (overrides its link)",
                             [](auto& h) -> auto& { return h.fibre.alpha_TT; }));
    t.push_back(linked_angle("alpha_TRT_deg", -kMaxAlpha, kMaxAlpha, "α_TRT (overrides its link)",
                             [](auto& h) -> auto& { return h.fibre.alpha_TRT; }));
    t.push_back(linked_angle("beta_TT_deg", kMinBeta, kMaxBeta, "β_TT (overrides its link)",
                             [](auto& h) -> auto& { return h.fibre.beta_TT; }));
    t.push_back(linked_angle("beta_TRT_deg", kMinBeta, kMaxBeta, "β_TRT (overrides its link)",
                             [](auto& h) -> auto& { return h.fibre.beta_TRT; }));
    t.push_back(real_param<HairParameters>("ecc_a", "", kMinEcc, kMaxEcc, "eccentricity a of the cross-section (1 = round)",
                                           [](auto& h) -> auto& { return h.fibre.ecc_a; }));
    t.push_back(angle_param("w_c_deg", kMinLambda, kPi, "azimuthal width w_c of the TRT caustics",
                            [](auto& h) -> auto& { return h.fibre.w_c; }));
    t.push_back(real_param<HairParameters>("delta_eta_p", "", kMinDeltaEtaPrime, kMaxDeltaEtaPrime, "Δη', the range over which the caustics fade above η' = 2",
                                           [](auto& h) -> auto& { return h.fibre.delta_eta_p; }));
    t.push_back(real_param<HairParameters>("d_b", "", 0.0, 1.0, "backward-scattering density factor d_b of dual scattering",
                                           [](auto& h) -> auto& { return h.fibre.d_b; }));
    Param<HairParameters> longitudinal{"longitudinal", ParamKind::choice, "", 0, 0, false,
                                       "M_t: energy-conserving (normalised over the incident angle) or 000's literal Gaussian",
                                       {"normalised", "paper"}, {}, {}, {}};
    longitudinal.get = [](const HairParameters& h, int) { return h.fibre.longitudinal >= 0.5f ? 1.0 : 0.0; };
    longitudinal.set = [](HairParameters& h, int, double v) { h.fibre.longitudinal = v >= 0.5 ? 1.0f : 0.0f; };
    t.push_back(longitudinal);
    t.push_back(int_param<HairParameters>("segments", 2, glsl::LIGHTING_MAX_SEGMENTS, "segments m of the linear quadrature",
                                          [](auto& h) -> auto& { return h.config.segments; }));
    t.push_back(flags_param<HairParameters>("lobes", lobe_names, "single-scattering lobes drawn",
                                            [](auto& h) -> auto& { return h.lobes; }));
    t.push_back(bool_param<HairParameters>("multiple", "dual-scattering multiple scattering",
                                           [](auto& h) -> auto& { return h.multiple; }));
    t.push_back(real_param<HairParameters>("d_f", "", 0.0, 1.0, "forward-scattering density factor d_f of dual scattering",
                                           [](auto& h) -> auto& { return h.d_f; }));
    return t;
}

}  // namespace

void validate(const HairParameters& hair, const std::string& place) {
    validate(hair.fibre, place);
    validate(hair.config, place);
    if (hair.lobes < 0 || hair.lobes > kAllLobes) {
        std::string bits;
        for (const Lobe& lobe : kLobes) bits += (bits.empty() ? "" : ", ") + std::string(lobe.name) + " (" + std::to_string(lobe.bit) + ")";
        throw Error::parameter(place, "lobes must be a bit set of " + bits);
    }
    if (!(hair.d_f >= 0.0f && hair.d_f <= 1.0f)) throw Error::parameter(place, "d_f must be in [0, 1]");
}

glm::vec3 sigma_a_from_melanin(double eumelanin, double pheomelanin) {
    if (!(eumelanin >= 0.0 && eumelanin < 1e3) || !(pheomelanin >= 0.0 && pheomelanin < 1e3))
        throw Error::parameter("melanin", "concentrations must be finite and ≥ 0");
    const glm::dvec3 eu(0.419, 0.697, 1.37), pheo(0.187, 0.4, 1.05);
    return glm::vec3(eumelanin * eu + pheomelanin * pheo);
}

const ParamTable<HairParameters>& hair_parameter_table() {
    static const Table table = make_table();
    return table;
}

void set_hair_parameter(HairParameters& hair, const std::string& key, const nlohmann::json& value, const std::string& place) {
    for (const Param<HairParameters>& p : hair_parameter_table())
        if (p.key == key) return read_param(p, value, hair, {}, place);
    throw Error::parameter(place, "'" + key + "' is not a hair parameter");
}

bool same_hair_parameters(const HairParameters& a, const HairParameters& b) {
    for (const HairParamsField& f : kHairParamsFields)
        if (!std::visit([&](auto member) { return a.fibre.*member == b.fibre.*member; }, f.member)) return false;
    for (const LightingConfigField& f : kLightingConfigFields)
        if (!std::visit([&](auto member) { return a.config.*member == b.config.*member; }, f.member)) return false;
    return a.lobes == b.lobes && a.multiple == b.multiple && a.d_f == b.d_f;
}

}  // namespace coif::shading
