#pragma once
// The plumbing of the `coif` command. Each noun (`coif hair`, `coif env`, ...) lives in its own file
// tools/cmd_<noun>.cpp and registers itself, so adding a command edits no shared file:
//
//   namespace {
//   void add_env(CLI::App& root) {
//       CLI::App* env = coif::cli::noun(root, "env", "Environment maps as SRBF lights");
//       CLI::App* fit = env->add_subcommand("fit", "Fit N SRBF lights to an HDR map");
//       ...
//       fit->callback([opts] { ... throw coif::Error(...) on failure ... });
//   }
//   COIF_REGISTER_COMMAND(40, add_env);   // order of appearance in `coif --help`
//   }
//
// Conventions (every command): a description that teaches, each option with its default and unit,
// an example in the footer (coif::cli::examples), `--json` on inspect/check commands
// (coif::cli::add_json_flag). Failures throw coif::Error; main prints `coif: error: …` on stderr
// and exits 1. Usage errors (CLI11 parse errors) exit 2. Long work shows coif::Progress.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "models/core/units.h"  // radians(): degrees at the interface, radians in the code

namespace coif::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

using RegisterFn = void (*)(CLI::App& root);

struct Registrar {
    Registrar(int order, RegisterFn fn);
};
void register_all(CLI::App& root);

#define COIF_CLI_CONCAT2(a, b) a##b
#define COIF_CLI_CONCAT(a, b) COIF_CLI_CONCAT2(a, b)
#define COIF_REGISTER_COMMAND(order, fn) \
    static const ::coif::cli::Registrar COIF_CLI_CONCAT(coif_registrar_, __LINE__) { order, fn }

// The subcommand `name` of root, created with `description` if it does not exist yet (several files
// may add verbs to one noun, e.g. `coif bench lighting` and `coif bench render`).
CLI::App* noun(CLI::App& root, const std::string& name, const std::string& description);

// Appends "Examples:\n  <lines>" to the subcommand's help.
void examples(CLI::App* app, const std::string& lines);

// Adds `--json` (machine-readable output on stdout; progress and notes go to stderr, quiet).
void add_json_flag(CLI::App* app, bool& json);

// Prints a JSON document on stdout (2-space indent).
void print_json(const nlohmann::json& doc);

// Locks a file the command writes (coif::OutputLock) until the process exits: a second coif writing the
// same file stops at once with a clear error, and temporaries that a killed run left for it are removed.
// Every command with an output calls it before its work, after the cheap checks of its options.
void lock_output(const std::string& path);

}  // namespace coif::cli
