// coif bake — cook a hairstyle against the HRIR database once and write what drawing it needs as one `.coif`
// asset (online/shells/hair_asset.h), which coif render and the runtime library load without the database.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "db/default_database.h"
#include "db/satf.h"
#include "models/core/error.h"
#include "online/scene/cook.h"
#include "online/shells/hair_asset.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct BakeOptions {
    std::string style, db, params, output;
    int lighting_rows = 0;
    bool json = false;
};

void add_bake(CLI::App& root) {
    auto o = std::make_shared<BakeOptions>();
    CLI::App* cmd = root.add_subcommand(
        "bake",
        "Cook a hairstyle into a .coif asset that a game or tool loads without the database\n"
        "Runs the look-ups of every sector in the HRIR database's FLANN index, packs only the records they use into the\n"
        "GPU's record atlas (with the whole database's quantisation ranges, so the asset draws bit-identically to the\n"
        "style), voxelizes the style's strands for the shadow grid, and writes all of it with the parameters to start\n"
        "from (--params) as one versioned, checksummed file. `coif render --style hair.coif` draws it; the runtime\n"
        "library (coif::runtime, coif/coif.h) loads it without the database (docs/renderer.md has the load times). The file\n"
        "format and its compatibility rule are in online/shells/hair_asset.h.");
    cmd->add_option("style", o->style, "Cluster hairstyle (JSON), or @default for the embedded one")->required();
    cmd->add_option("--db", o->db, "HRIR database; default: the cached default database (built on first use)");
    cmd->add_option("--params", o->params, "Parameters JSON the asset starts from (see coif render --help); default: the library's");
    cmd->add_option("--lighting-rows", o->lighting_rows, "Lighting samples per HSV along the axis (0: one per mesh row)")
        ->check(CLI::Range(0, 64))
        ->capture_default_str();
    cmd->add_option("-o,--output", o->output, "The .coif file to write (atomically: nothing is left on failure)")->required();
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif bake @default -o hair.coif\n  coif bake style.json --params look.json -o hair.coif\n"
                             "  coif render --style hair.coif -o hair.png");
    cmd->callback([o] {
        const coif::gl::ShellSettings defaults = o->params.empty() ? coif::gl::ShellSettings{}
                                                                   : coif::gl::read_shell_settings(o->params);
        const coif::HairStyle style = coif::cli::load_style(o->style);
        coif::cli::lock_output(o->output);
        const auto start = std::chrono::steady_clock::now();
        const coif::HrirDatabase db = coif::open_database_or_default(o->db, o->json ? nullptr : &std::cerr);
        const coif::SatfIndex satf = coif::SatfIndex::open(db, coif::SatfOptions{});
        coif::CookedShells cooked = coif::cook_shells(style, satf, coif::style_orientation(style), o->lighting_rows);
        cooked.defaults = defaults;
        coif::write_hair_asset(o->output, cooked);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const auto bytes = std::filesystem::file_size(o->output);
        if (o->json)
            coif::cli::print_json({{"output", o->output},
                                   {"style", o->style},
                                   {"database", db.path().string()},
                                   {"clusters", cooked.shells.clusters()},
                                   {"prototypes", cooked.shells.prototypes.size()},
                                   {"records", cooked.atlas.mean_alpha.size()},
                                   {"database_records", db.size()},
                                   {"atlas", {cooked.atlas.width, cooked.atlas.height}},
                                   {"bytes", bytes},
                                   {"seconds", seconds}});
        else
            std::fprintf(stderr,
                         "baked %s (%zu clusters, %zu prototypes; %zu of the database's %zu records, atlas %dx%d) in %.2f s "
                         "-> %s (%.1f MiB)\n",
                         o->style.c_str(), cooked.shells.clusters(), cooked.shells.prototypes.size(),
                         cooked.atlas.mean_alpha.size(), db.size(), cooked.atlas.width, cooked.atlas.height, seconds,
                         o->output.c_str(), double(bytes) / (1024.0 * 1024.0));
    });
}

COIF_REGISTER_COMMAND(62, add_bake);

}  // namespace
