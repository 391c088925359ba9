#pragma once
// The hair's scattering parameters, written once: the struct every renderer and tool takes
// (HairParameters), the lobe table, the C++ mirror of the GLSL structs' fields, and the parameters
// file's hair keys (a models/core/param_table.h table). GL-free.
//
// The parameters file's hair keys are hair_parameter_table()'s (eta, sigma_a, alpha_R_deg, …: `coif render
// --help` lists them with their ranges); every key is optional, angles are in degrees at the interface and
// radians in the struct. α_R / β_R alone keep 000's links for TT and TRT (link_lobes_to_R); a TT/TRT key overrides its link.
// Degrees convert to radians in float, radians = float(degrees) · float(π/180), as the file always has (so an
// old file means the same radians, bit for bit). The writer inverts that exactly: write → read gives the same
// struct for every angle set from degrees (a file, a shorthand, a slider) and for the defaults; an angle set
// in radians that no float number of degrees reaches (about 9 % of floats) reads back 1 ulp away.
// The renderer's own keys are online/shells/shell_settings.h's; read_shell_settings reads one file through both.
#include <array>
#include <string>
#include <variant>

#include "models/core/param_table.h"
#include "models/core/units.h"
#include "shaders/lighting.h"

namespace coif::shading {

// The scattering lobes (000 §4.1), in the order of the shaders' LOBE_R, LOBE_TT, LOBE_TRT
// (shaders/lighting/marschner.glsl; a test checks that they agree). A set of lobes is a bit set of `bit`s.
struct Lobe {
    const char* name;  // as the parameters file's "lobes" object and the AOVs name it
    int bit;           // 1 << the lobe's index
};
inline constexpr std::array<Lobe, 3> kLobes = {{{"R", 1}, {"TT", 2}, {"TRT", 4}}};
inline constexpr int kLobeCount = static_cast<int>(kLobes.size());
inline constexpr int kAllLobes = (1 << kLobeCount) - 1;

struct HairParameters {
    HairParams fibre = default_hair_params();   // the GLSL struct (shaders/lighting/marschner.glsl): η, σa, α, β, a, w_c, Δη', d_b
    LightingConfig config = default_config(4);  // m (segments) and the paper switches
    int lobes = kAllLobes;                      // bits of kLobes
    bool multiple = true;                       // dual-scattering multiple scattering (shaders/lighting/srbf_shadowed.glsl)
    float d_f = 0.7f;                           // Zinke's forward-scattering density factor d_f (000 eq. 2)
};

// Every field equal (the fibre's and the config's through kHairParamsFields and kLightingConfigFields, below).
bool same_hair_parameters(const HairParameters& a, const HairParameters& b);

// Throws coif::Error (place as in shading::validate) for a bad fibre, config, lobe set or d_f.
void validate(const HairParameters& hair, const std::string& place = "hair parameters");

// The fields of the GLSL structs HairParams (shaders/lighting/marschner.glsl) and LightingConfig
// (shaders/lighting/srbf_single.glsl) in declaration order, for the code that must visit every field
// (online/lighting_uniforms.cpp's uniforms and table cache). The GLSL keeps its own declaration; a test
// (tests/shading/test_hair_parameters.cpp) checks these lists against its text.
// Each with the range validate() accepts (and NaN/Inf nowhere) and how its message names it.
struct HairParamsField {
    const char* name;
    std::variant<float HairParams::*, glm::vec3 HairParams::*> member;
    bool in_ms_tables;  // read by the dual-scattering tables (build_ms_tables); σa is not: they span every σa
    const char* label;  // in validate()'s message (a vec3's channels as label.r, .g, .b)
    float lo, hi;
    bool lo_exclusive;
    const char* unit;
};
inline constexpr std::array<HairParamsField, 13> kHairParamsFields = {{
    {"eta", &HairParams::eta, true, "eta (index of refraction)", kMinEta, kMaxEta, true, ""},
    {"sigma_a", &HairParams::sigma_a, false, "sigma_a", 0.0f, kMaxSigmaA, false, "per unit fibre radius"},
    {"alpha_R", &HairParams::alpha_R, true, "alpha_R", -kMaxAlpha, kMaxAlpha, false, "rad"},
    {"alpha_TT", &HairParams::alpha_TT, true, "alpha_TT", -kMaxAlpha, kMaxAlpha, false, "rad"},
    {"alpha_TRT", &HairParams::alpha_TRT, true, "alpha_TRT", -kMaxAlpha, kMaxAlpha, false, "rad"},
    {"beta_R", &HairParams::beta_R, true, "beta_R", kMinBeta, kMaxBeta, false, "rad"},
    {"beta_TT", &HairParams::beta_TT, true, "beta_TT", kMinBeta, kMaxBeta, false, "rad"},
    {"beta_TRT", &HairParams::beta_TRT, true, "beta_TRT", kMinBeta, kMaxBeta, false, "rad"},
    {"ecc_a", &HairParams::ecc_a, true, "eccentricity a", kMinEcc, kMaxEcc, false, "(eta* must stay above 1)"},
    {"w_c", &HairParams::w_c, true, "w_c", kMinLambda, kPiF, false, "rad"},
    {"delta_eta_p", &HairParams::delta_eta_p, true, "delta_eta_prime", kMinDeltaEtaPrime, kMaxDeltaEtaPrime, false, ""},
    {"d_b", &HairParams::d_b, true, "d_b", 0.0f, 1.0f, false, ""},
    {"longitudinal", &HairParams::longitudinal, true, "longitudinal (0 energy-conserving, 1 paper)", 0.0f, 1.0f, false, ""},
}};

struct LightingConfigField {
    const char* name;
    std::variant<int LightingConfig::*, bool LightingConfig::*> member;
};
inline constexpr std::array<LightingConfigField, 5> kLightingConfigFields = {{
    {"segments", &LightingConfig::segments},
    {"paper_schlick", &LightingConfig::paper_schlick},
    {"paper_norm", &LightingConfig::paper_norm},
    {"paper_theta_gauss", &LightingConfig::paper_theta_gauss},
    {"paper_tt", &LightingConfig::paper_tt},
}};

// The hair keys of a parameters file (see the header comment), in the order they are applied.
const ParamTable<HairParameters>& hair_parameter_table();

// σa of a fibre with these melanin concentrations (Chiang et al. 2016 §4.2, as pbrt-v4's SigmaAFromConcentration):
// ce · (0.419, 0.697, 1.37) + cp · (0.187, 0.4, 1.05). Their σa is per unit fibre radius (a path through the fibre's
// centre is 2 radii long), as coif's is, so no conversion is needed. Natural hair spans roughly ce 0 … 8 (blond 0.3,
// brown 1.3, black 8) and cp 0 … 3 (red hair's). Throws coif::Error::parameter for a negative or non-finite value.
glm::vec3 sigma_a_from_melanin(double eumelanin, double pheomelanin);

// A shorthand option (`coif reference --alpha-r 5`) or any single key: `value` read as the file's `key`
// would be, with the same links; coif::Error(place) if the key is not a hair key or the value is bad.
void set_hair_parameter(HairParameters& hair, const std::string& key, const nlohmann::json& value, const std::string& place);

}  // namespace coif::shading
