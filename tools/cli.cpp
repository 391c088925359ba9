#include "tools/cli.h"

#include <algorithm>
#include <iostream>
#include <vector>

#include "models/core/atomic_file.h"
#include "models/core/progress.h"

namespace coif::cli {
namespace {
std::vector<std::pair<int, RegisterFn>>& registry() {
    static std::vector<std::pair<int, RegisterFn>> r;
    return r;
}
}  // namespace

Registrar::Registrar(int order, RegisterFn fn) { registry().emplace_back(order, fn); }

void register_all(CLI::App& root) {
    auto r = registry();
    std::stable_sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [order, fn] : r) fn(root);
}

CLI::App* noun(CLI::App& root, const std::string& name, const std::string& description) {
    for (CLI::App* sub : root.get_subcommands({}))
        if (sub->get_name() == name) return sub;
    CLI::App* sub = root.add_subcommand(name, description);
    sub->require_subcommand(1);
    // CLI11 copies the parent's footer into subcommands; a noun points at its verbs' own help instead.
    sub->footer("\nRun `coif " + name + " <command> --help` for each command's options and examples.");
    return sub;
}

void examples(CLI::App* app, const std::string& lines) { app->footer("\nExamples:\n" + lines); }

void add_json_flag(CLI::App* app, bool& json) {
    app->add_flag("--json", json, "Print machine-readable JSON on stdout instead of a table")
        ->each([](const std::string&) { Progress::set_quiet(true); });
}

void print_json(const nlohmann::json& doc) { std::cout << doc.dump(2) << "\n"; }

void lock_output(const std::string& path) {
    static std::vector<OutputLock> held;  // released (lock files removed) when the process exits
    held.emplace_back(path);
}

}  // namespace coif::cli
