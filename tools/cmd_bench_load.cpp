// coif bench load — how long a hairstyle takes to become drawable: cooked live from the style and the database
// (the baseline) against read from a baked `.coif` asset, both uploaded to the same GL context in the same run.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "db/default_database.h"
#include "db/satf.h"
#include "models/core/error.h"
#include "models/core/statistics.h"
#include "online/gl_context.h"
#include "online/scene/cook.h"
#include "online/shell_renderer.h"
#include "online/shells/hair_asset.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct BenchLoadOptions {
    std::string style = "@default", db;
    int repeats = 5;
    bool json = false;
};

// One load's phases in milliseconds; compile is the GL programs compiled during it (counted inside upload).
struct Phases {
    double read = 0, cook = 0, upload = 0, compile = 0;
    double total() const { return read + cook + upload; }
    double total_without_compile() const { return total() - compile; }
};

// The shells' upload (ShellRenderer's constructor, waited for), with the programs compiled meanwhile.
void time_upload(coif::gl::Context& context, coif::CookedShells cooked, Phases& p) {
    const double compiled = coif::gl::program_compile_seconds();
    const auto t = Clock::now();
    coif::gl::ShellRenderer renderer(std::move(cooked));
    context.finish();
    p.upload = ms_since(t);
    p.compile = 1e3 * (coif::gl::program_compile_seconds() - compiled);
}

void add_bench_load(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchLoadOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "load",
        "Load time of a hairstyle: cooked live from the style and database against read from its baked .coif asset\n"
        "Bakes the style into a temporary asset (as `coif bake` does), then --repeats times in turn: opens the database\n"
        "and its SATF index, cooks the style and uploads it (the baseline), and maps, validates and uploads the asset.\n"
        "Both upload into the same headless GL context, waited for; the GL programs compiled meanwhile are reported\n"
        "beside (the first load compiles them, later ones find them compiled). Figures are medians, the files in the\n"
        "page cache (warm). The GL context's creation is timed once, apart: a host has its own.");
    cmd->add_option("--style", o->style, "Cluster hairstyle (JSON), or @default for the embedded one")->capture_default_str();
    cmd->add_option("--db", o->db, "HRIR database; default: the cached default database (built on first use)");
    cmd->add_option("--repeats", o->repeats, "Loads of each kind")->check(CLI::Range(1, 1000))->capture_default_str();
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif bench load\n  coif bench load --style my_style.json --repeats 9 --json");
    cmd->callback([o] {
        const coif::HairStyle style = coif::cli::load_style(o->style);
        // The asset, baked from the same style and database in a child process, so that this one's first load
        // finds its memory as a freshly started program does (the cook's freed pages would make it look faster).
        namespace fs = std::filesystem;
        const fs::path asset = fs::temp_directory_path() / ("coif-bench-load-" + std::to_string(::getpid()) + ".coif");
        struct Remove {
            fs::path p;
            ~Remove() {
                std::error_code ec;
                fs::remove(p, ec);
            }
        } remove{asset};
        std::fflush(nullptr);
        const pid_t child = ::fork();
        if (child < 0) throw coif::Error("coif bench load", "", "cannot start the process that bakes the asset");
        if (child == 0) {
            int rc = 0;
            try {
                const coif::HrirDatabase db = coif::open_database_or_default(o->db, nullptr);
                const coif::SatfIndex satf = coif::SatfIndex::open(db, coif::SatfOptions{});
                coif::write_hair_asset(asset, coif::cook_shells(style, satf, coif::style_orientation(style)));
            } catch (const std::exception& e) {
                std::fprintf(stderr, "coif: error: %s\n", e.what());
                rc = 1;
            }
            std::fflush(nullptr);
            ::_exit(rc);
        }
        int status = 0;
        if (::waitpid(child, &status, 0) != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
            throw coif::Error(o->style, "", "could not be baked into an asset to load");
        const std::uintmax_t asset_bytes = fs::file_size(asset);
        auto t = Clock::now();
        auto context = coif::gl::Context::headless();
        const double context_ms = ms_since(t);

        std::vector<Phases> live, baked;
        for (int i = 0; i < o->repeats; ++i) {
            Phases q;
            t = Clock::now();
            coif::CookedShells read = coif::read_hair_asset(asset);
            q.read = ms_since(t);
            time_upload(*context, std::move(read), q);
            baked.push_back(q);

            Phases p;
            t = Clock::now();
            const coif::HrirDatabase db = coif::open_database_or_default(o->db, nullptr);
            const coif::SatfIndex satf = coif::SatfIndex::open(db, coif::SatfOptions{});
            p.read = ms_since(t);
            t = Clock::now();
            coif::CookedShells cooked = coif::cook_shells(style, satf, coif::style_orientation(style));
            p.cook = ms_since(t);
            time_upload(*context, std::move(cooked), p);
            live.push_back(p);
        }
        // The first load of each kind, and the median of the later ones (none with --repeats 1).
        const auto phases_json = [](const Phases& p) {
            return nlohmann::ordered_json{{"read_ms", p.read},       {"cook_ms", p.cook},
                                          {"upload_ms", p.upload},   {"compile_ms", p.compile},
                                          {"total_ms", p.total()},   {"total_without_compile_ms", p.total_without_compile()}};
        };
        const auto later = [](const std::vector<Phases>& v) {
            std::vector<double> read, cook, upload, compile;
            for (std::size_t i = 1; i < v.size(); ++i) {
                read.push_back(v[i].read);
                cook.push_back(v[i].cook);
                upload.push_back(v[i].upload);
                compile.push_back(v[i].compile);
            }
            Phases m;
            if (read.empty()) return m;
            m.read = coif::median(read), m.cook = coif::median(cook), m.upload = coif::median(upload);
            m.compile = coif::median(compile);
            return m;
        };
        const Phases live_later = later(live), baked_later = later(baked);
        nlohmann::ordered_json j = {
            {"renderer", context->renderer()},
            {"style", o->style},
            {"asset_bytes", asset_bytes},
            {"repeats", o->repeats},
            {"context_ms", context_ms},
            {"asset_first", phases_json(baked.front())},
            {"style_and_database_first", phases_json(live.front())}};
        if (o->repeats > 1) {
            j["asset_later_median"] = phases_json(baked_later);
            j["style_and_database_later_median"] = phases_json(live_later);
            j["speedup_later"] = live_later.total() / baked_later.total();
        }
        if (o->json) {
            coif::cli::print_json(j);
            return;
        }
        std::printf("renderer  %s; style %s; asset %.1f MiB; %d load(s) of each kind in turn, the asset's first, files in\n"
                    "the page cache\n",
                    context->renderer().c_str(), o->style.c_str(), asset_bytes / 1048576.0, o->repeats);
        std::printf("GL context created once in %.1f ms (not counted: a host has its own)\n\n", context_ms);
        std::printf("%-34s %8s %8s %8s %9s %8s %12s\n", "load", "read", "cook", "upload", "(compile)", "total",
                    "w/o compile");
        std::printf("%-34s %8s %8s %8s %9s %8s %12s\n", "", "ms", "ms", "ms", "ms", "ms", "ms");
        const auto line = [](const char* name, const Phases& p) {
            std::printf("%-34s %8.1f %8.1f %8.1f %9.1f %8.1f %12.1f\n", name, p.read, p.cook, p.upload, p.compile, p.total(),
                        p.total_without_compile());
        };
        line("asset, first (a fresh process)", baked.front());
        if (o->repeats > 1) line("asset, later (median)", baked_later);
        line("style + database, first", live.front());
        if (o->repeats > 1) line("style + database, later (median)", live_later);
        std::printf("\nread: the asset mapped and validated, or the database and its SATF index opened; upload: the GPU\n"
                    "copies, waited for, with the GL programs compiled meanwhile (the first load compiles them)\n");
        if (o->repeats > 1) std::printf("later loads: the asset's %.1fx faster\n", live_later.total() / baked_later.total());
    });
}

COIF_REGISTER_COMMAND(94, add_bench_load);

}  // namespace
