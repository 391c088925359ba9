// The one home of the hair parameters (shaders/hair_parameters.h): the lobe table and the C++ field lists
// against the GLSL's own declarations, and the hair keys' table (models/core/param_table.h): round trip,
// links, refusals with the JSON path named.
// GCC 12 reports a false -Wmaybe-uninitialized inside <regex>'s automaton (a std::function moved from a
// temporary) when it inlines it under the sanitizer build's flags: the standard library's, not this file's. The
// warning is judged where the headers' text stands, so it is off for the whole file.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "models/core/error.h"
#include "shaders/hair_parameters.h"

namespace coif::shading {
namespace {

std::string source_text(const std::string& relative) {
    std::ifstream in(std::string(COIF_SOURCE_DIR) + "/" + relative);
    EXPECT_TRUE(in) << relative;
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// (type, name) of each field of `struct <name> { ... };` in GLSL text, comments removed.
std::vector<std::pair<std::string, std::string>> glsl_struct_fields(const std::string& text, const std::string& name) {
    const std::string code = std::regex_replace(text, std::regex("//[^\n]*"), "");
    std::smatch body;
    EXPECT_TRUE(std::regex_search(code, body, std::regex("struct\\s+" + name + "\\s*\\{([^}]*)\\}"))) << name;
    std::vector<std::pair<std::string, std::string>> fields;
    const std::string inside = body[1];
    const std::regex field("(\\w+)\\s+(\\w+)\\s*;");
    for (auto it = std::sregex_iterator(inside.begin(), inside.end(), field); it != std::sregex_iterator(); ++it)
        fields.emplace_back((*it)[1], (*it)[2]);
    return fields;
}

bool same_fibre(const HairParams& a, const HairParams& b) {
    for (const HairParamsField& f : kHairParamsFields)
        if (!std::visit([&](auto member) { return a.*member == b.*member; }, f.member)) return false;
    return true;
}

bool same(const HairParameters& a, const HairParameters& b) {
    bool config = true;
    for (const LightingConfigField& f : kLightingConfigFields)
        config = config && std::visit([&](auto member) { return a.config.*member == b.config.*member; }, f.member);
    return same_fibre(a.fibre, b.fibre) && config && a.lobes == b.lobes && a.multiple == b.multiple && a.d_f == b.d_f;
}

HairParameters read(const std::string& json, HairParameters base = {}) {
    read_params(nlohmann::json::parse(json), base, hair_parameter_table(), "hair.json");
    return base;
}

// The error's place ("JSON /beta_R_deg") for a file that must be refused.
std::string refused_at(const std::string& json) {
    try {
        read(json);
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "hair.json");
        return e.place();
    }
    ADD_FAILURE() << json << " accepted";
    return "";
}

TEST(HairParameters, LobeTableAgreesWithTheShaders) {
    EXPECT_STREQ(kLobes[glsl::LOBE_R].name, "R");
    EXPECT_STREQ(kLobes[glsl::LOBE_TT].name, "TT");
    EXPECT_STREQ(kLobes[glsl::LOBE_TRT].name, "TRT");
    for (int i = 0; i < kLobeCount; ++i) EXPECT_EQ(kLobes[i].bit, 1 << i) << kLobes[i].name;
    EXPECT_EQ(kAllLobes, 7);
    const std::string marschner = source_text("shaders/lighting/marschner.glsl");
    for (int i = 0; i < kLobeCount; ++i)
        EXPECT_NE(marschner.find("const int LOBE_" + std::string(kLobes[i].name) + " = " + std::to_string(i) + ";"), std::string::npos)
            << kLobes[i].name;
}

TEST(HairParameters, FieldListsMatchTheGlslStructs) {
    const auto hair = glsl_struct_fields(source_text("shaders/lighting/marschner.glsl"), "HairParams");
    ASSERT_EQ(hair.size(), kHairParamsFields.size());
    for (size_t i = 0; i < hair.size(); ++i) {
        EXPECT_EQ(hair[i].second, kHairParamsFields[i].name);
        EXPECT_EQ(hair[i].first, kHairParamsFields[i].member.index() == 0 ? "float" : "vec3") << hair[i].second;
    }
    const auto config = glsl_struct_fields(source_text("shaders/lighting/srbf_single.glsl"), "LightingConfig");
    ASSERT_EQ(config.size(), kLightingConfigFields.size());
    for (size_t i = 0; i < config.size(); ++i) {
        EXPECT_EQ(config[i].second, kLightingConfigFields[i].name);
        EXPECT_EQ(config[i].first, kLightingConfigFields[i].member.index() == 0 ? "int" : "bool") << config[i].second;
    }
    // Every field is in the list once: together the members cover the C++ struct's size.
    EXPECT_EQ(sizeof(HairParams), 15 * sizeof(float));
}

TEST(HairParameters, WriteThenReadGivesTheSameStruct) {
    const ParamTable<HairParameters>& table = hair_parameter_table();
    HairParameters a;
    EXPECT_TRUE(same(read(write_params(a, table).dump()), a));
    // Unlinked TT/TRT, odd angles, every key away from its default.
    HairParameters b;
    b.fibre = linked_hair_params(1.61f, glm::vec3(0.1f, 0.77f, 2.5f), -0.09f, 0.2f, 0.93f, 0.31f);
    b.fibre.alpha_TRT = 0.05f;
    b.fibre.beta_TT = 0.03f;
    b.fibre.delta_eta_p = 0.45f;
    b.fibre.d_b = 0.55f;
    b.fibre.longitudinal = 1.0f;
    b.config.segments = 7;
    b.lobes = 5;
    b.multiple = false;
    b.d_f = 0.25f;
    const nlohmann::ordered_json jb = write_params(b, table);
    EXPECT_TRUE(jb.contains("alpha_TRT_deg") && jb.contains("beta_TT_deg"));
    EXPECT_FALSE(jb.contains("alpha_TT_deg") || jb.contains("beta_TRT_deg")) << jb.dump();  // still linked
    EXPECT_TRUE(same(read(jb.dump()), b)) << jb.dump();
    EXPECT_EQ(jb["longitudinal"], "paper");
    EXPECT_EQ(write_params(a, table)["longitudinal"], "normalised");  // energy-conserving by default
    EXPECT_THROW(set_hair_parameter(a, "longitudinal", "literal", "test"), Error);
    // Angles set from degrees, as a file or a slider sets them, come back exactly.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> deg(-40.0, 40.0);
    for (int i = 0; i < 2000; ++i) {
        HairParameters c;
        set_hair_parameter(c, "alpha_R_deg", deg(rng), "test");
        set_hair_parameter(c, "w_c_deg", 5.0 + std::abs(deg(rng)), "test");
        ASSERT_TRUE(same(read(write_params(c, table).dump()), c)) << write_params(c, table).dump();
    }
}

TEST(HairParameters, DegreesMeanWhatTheyAlwaysMeant) {
    // The file converts in float (float(deg) · 0.017453292519943295f) as before: a file's -7.5° is the
    // default's α_R bit for bit, so old parameters files render the same.
    const HairParameters h = read(R"({"alpha_R_deg": -7.5, "beta_R_deg": 7.5, "w_c_deg": 20})");
    EXPECT_EQ(h.fibre.alpha_R, default_hair_params().alpha_R);
    EXPECT_EQ(h.fibre.beta_R, default_hair_params().beta_R);
    EXPECT_EQ(h.fibre.w_c, 20.0f * 0.017453292519943295f);
}

TEST(HairParameters, AlphaAndBetaRKeepTheLinksAndTtTrtKeysOverrideThem) {
    HairParameters base;
    base.fibre.alpha_TT = 0.2f;  // an unlinked base
    base.fibre.beta_TRT = 0.5f;
    const HairParameters untouched = read(R"({"eta": 1.6})", base);
    EXPECT_EQ(untouched.fibre.alpha_TT, 0.2f);  // no α_R/β_R key: TT/TRT stay the base's
    const HairParameters linked = read(R"({"beta_R_deg": 10})", base);
    HairParams want = linked.fibre;
    link_lobes_to_R(want);
    EXPECT_TRUE(same_fibre(linked.fibre, want));  // α_R or β_R alone relinks all four
    EXPECT_EQ(linked.fibre.beta_TRT, 2.0f * (10.0f * 0.017453292519943295f));
    const HairParameters overridden = read(R"({"beta_TRT_deg": 3, "beta_R_deg": 10})", base);  // key order is irrelevant
    EXPECT_EQ(overridden.fibre.beta_TRT, 3.0f * 0.017453292519943295f);
    EXPECT_EQ(overridden.fibre.beta_TT, linked.fibre.beta_TT);
}

TEST(HairParameters, RefusesUnknownKeysWrongTypesAndOutOfRangeValuesNamingTheJsonPath) {
    EXPECT_EQ(refused_at(R"({"nonsense": 1})"), "JSON /nonsense");
    EXPECT_EQ(refused_at(R"({"neighbours": 2})"), "JSON /neighbours");  // a renderer key is not a hair key
    EXPECT_EQ(refused_at(R"({"eta": 1.0})"), "JSON /eta");             // η must exceed 1
    EXPECT_EQ(refused_at(R"({"eta": "1.5"})"), "JSON /eta");
    EXPECT_EQ(refused_at(R"({"alpha_R_deg": 50})"), "JSON /alpha_R_deg");
    EXPECT_EQ(refused_at(R"({"beta_R_deg": 0})"), "JSON /beta_R_deg");
    EXPECT_EQ(refused_at(R"({"sigma_a": [1, 2]})"), "JSON /sigma_a");
    EXPECT_EQ(refused_at(R"({"sigma_a": [1, -2, 3]})"), "JSON /sigma_a/1");
    EXPECT_EQ(refused_at(R"({"segments": 1})"), "JSON /segments");
    EXPECT_EQ(refused_at(R"({"segments": 4.5})"), "JSON /segments");
    EXPECT_EQ(refused_at(R"({"lobes": {"TX": true}})"), "JSON /lobes/TX");
    EXPECT_EQ(refused_at(R"({"lobes": {"TT": 1}})"), "JSON /lobes/TT");
    EXPECT_EQ(refused_at(R"({"multiple": 1})"), "JSON /multiple");
    EXPECT_EQ(refused_at(R"({"d_f": 1.5})"), "JSON /d_f");
    EXPECT_EQ(refused_at(R"([1, 2])"), "JSON /");
    try {
        read(R"({"d_b": 2})");
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("[0, 1]"), std::string::npos) << e.what();  // says what it accepts
    }
}

TEST(HairParameters, TableIsIterableForHelpAndSliders) {
    const ParamTable<HairParameters>& table = hair_parameter_table();
    const HairParameters defaults;
    for (const Param<HairParameters>& p : table) {
        EXPECT_FALSE(p.help.empty()) << p.key;
        if (p.kind == ParamKind::real || p.kind == ParamKind::integer || p.kind == ParamKind::rgb)
            for (int c = 0; c < p.components(); ++c) {
                const double v = p.get(defaults, c);  // the default lies in the range a slider offers
                EXPECT_TRUE((p.min_exclusive ? v > p.min : v >= p.min) && v <= p.max) << p.key << " = " << v;
            }
        if (p.key.ends_with("_deg")) {
            EXPECT_EQ(p.unit, "deg") << p.key;
        }
    }
    const std::string help = params_help(table);
    for (const Param<HairParameters>& p : table) EXPECT_NE(help.find(p.key), std::string::npos) << p.key;
}

TEST(HairParameters, ValidateRefusesABadLobeSetOrDf) {
    HairParameters h;
    EXPECT_NO_THROW(validate(h));
    h.lobes = 8;
    EXPECT_THROW(validate(h), Error);
    h = {};
    h.d_f = -0.1f;
    EXPECT_THROW(validate(h), Error);
}

TEST(HairParameters, MelaninGivesChiangsAbsorption) {
    // pbrt-v4's brown (ce 1.3) and a red mix; the sum is linear in both concentrations.
    const glm::vec3 brown = sigma_a_from_melanin(1.3, 0.0);
    EXPECT_NEAR(brown.r, 0.5447, 1e-4);
    EXPECT_NEAR(brown.g, 0.9061, 1e-4);
    EXPECT_NEAR(brown.b, 1.781, 1e-4);
    const glm::vec3 red = sigma_a_from_melanin(0.0, 2.0);
    EXPECT_NEAR(red.r, 0.374, 1e-6);
    EXPECT_NEAR(red.b, 2.1, 1e-6);
    const glm::vec3 both = sigma_a_from_melanin(1.3, 2.0);
    EXPECT_NEAR(both.g, brown.g + red.g, 1e-6);
    EXPECT_EQ(sigma_a_from_melanin(0.0, 0.0), glm::vec3(0.0f));
    EXPECT_THROW((void)sigma_a_from_melanin(-0.1, 0.0), Error);
    EXPECT_THROW((void)sigma_a_from_melanin(0.0, std::nan("")), Error);
}

}  // namespace
}  // namespace coif::shading
