#pragma once
// The hair options every command that takes scattering parameters shares (`coif reference`, `coif bench
// quality`, `coif lighting plot`): --params FILE, the parameters file of `coif render --params`
// (online/shells/shell_settings.h), and shorthand flags for its commonest hair keys, each read exactly as
// its key would be (same unit, range and links): --eta, --sigma-a, --alpha-r, --beta-r, --ecc, --wc.
// The shorthands override the file's values.
#include <optional>
#include <string>
#include <vector>

#include "online/shells/shell_settings.h"
#include "tools/cli.h"

namespace coif::cli {

struct HairCliOptions {
    std::string params;                                   // --params FILE (empty: none)
    std::optional<double> eta, alpha_r, beta_r, ecc, wc;  // the shorthands, in their keys' units (degrees)
    std::vector<double> sigma_a;                          // R G B

    void add_to(CLI::App* app, const shading::HairParameters& defaults = {});  // defaults: for the help text
    // `base`, then the file's keys, then the shorthands; validated (coif::Error naming the file and key or
    // the option).
    gl::ShellSettings settings(gl::ShellSettings base = {}) const;
};

}  // namespace coif::cli
