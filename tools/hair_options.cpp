#include "tools/hair_options.h"

#include "models/core/error.h"

namespace coif::cli {
namespace {

// Each shorthand flag and the parameters file key it stands for.
struct Shorthand {
    const char* flag;
    const char* key;
    std::optional<double> HairCliOptions::*value;
};
constexpr Shorthand kShorthands[] = {
    {"--eta", "eta", &HairCliOptions::eta},         {"--alpha-r", "alpha_R_deg", &HairCliOptions::alpha_r},
    {"--beta-r", "beta_R_deg", &HairCliOptions::beta_r}, {"--ecc", "ecc_a", &HairCliOptions::ecc},
    {"--wc", "w_c_deg", &HairCliOptions::wc},
};
constexpr const char* kSigmaFlag = "--sigma-a";
constexpr const char* kSigmaKey = "sigma_a";

const Param<shading::HairParameters>& hair_key(const char* key) {
    for (const auto& p : shading::hair_parameter_table())
        if (p.key == key) return p;
    throw Error::parameter("hair options", std::string("no hair key ") + key);
}

// "<the key's help> in <unit and range> (the parameters file's key <key>; default <value>)".
std::string shorthand_help(const char* key, const shading::HairParameters& defaults) {
    const Param<shading::HairParameters>& p = hair_key(key);
    std::string value;
    for (int c = 0; c < p.components(); ++c) value += (c ? " " : "") + number_text(param_detail::shortest_float(p.get(defaults, c)));
    return p.help + ": " + accepted_text(p) + " (the --params key " + p.key + "; default " + value + ")";
}

}  // namespace

void HairCliOptions::add_to(CLI::App* app, const shading::HairParameters& defaults) {
    app->add_option("--params", params,
                    "Parameters file, as `coif render --params` reads it (see `coif render --help`); the fibre's keys "
                    "apply, the flags below override them");
    for (const Shorthand& s : kShorthands) app->add_option(s.flag, this->*s.value, shorthand_help(s.key, defaults));
    app->add_option(kSigmaFlag, sigma_a, shorthand_help(kSigmaKey, defaults))->expected(3);
}

gl::ShellSettings HairCliOptions::settings(gl::ShellSettings base) const {
    gl::ShellSettings s = params.empty() ? base : gl::read_shell_settings(params, base);
    for (const Shorthand& sh : kShorthands)
        if (const std::optional<double>& v = this->*sh.value)
            shading::set_hair_parameter(s.hair, sh.key, *v, std::string("option ") + sh.flag);
    if (!sigma_a.empty()) shading::set_hair_parameter(s.hair, kSigmaKey, sigma_a, std::string("option ") + kSigmaFlag);
    std::string flags;
    for (const Shorthand& sh : kShorthands) flags += std::string(sh.flag) + ", ";
    shading::validate(s.hair, "hair parameters (" + (params.empty() ? std::string() : params + ", ") + flags + kSigmaFlag + ")");
    return s;
}

}  // namespace coif::cli
