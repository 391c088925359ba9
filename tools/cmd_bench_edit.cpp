// coif bench edit — the CPU work of one cluster edit in coif view (a dragged control point): the edited style cooked
// again keeping what the edit did not change (CookCache, online/scene/cook.h) and handed to the renderer it is drawn
// with (ShellRenderer::set_hair), against the baseline in the same run: a cook from nothing and a new renderer, which
// is what `coif render` does on every load and what an edit cost before.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "db/default_database.h"
#include "db/satf.h"
#include "models/core/error.h"
#include "models/core/statistics.h"
#include "models/style_edit.h"
#include "online/gl_context.h"
#include "online/scene/cook.h"
#include "online/shell_renderer.h"
#include "online/shells/hair_asset.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct BenchEditOptions {
    std::string style = "@default", db;
    int edits = 8, repeats = 3;
    long cluster = -1, point = -1;
    double step = 0.5;
    bool json = false;
};

void add_bench_edit(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchEditOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "edit",
        "CPU work of one cluster edit in `coif view`: a control point dragged, the style cooked again and drawn\n"
        "Cooks the style once from nothing and makes a renderer of it, --repeats times (the baseline: what `coif render`\n"
        "does on every load, and what an edit cost before edits kept what they did not change). Then moves one\n"
        "cluster's control point --edits times by --step % of the hair's longest side, alternately along x and z, as a\n"
        "drag does; after each, cooks the edited style keeping what the edit did not change (the prototypes, clusters'\n"
        "strands and tilts, the shadow grid's sums and the atlas's tiles of the last cook) and hands it to the same\n"
        "renderer (its upload waited for). Prints the medians, their parts and the ratio to the baseline, and checks\n"
        "that the last edit's cook is the same, byte for byte, as a cook of the edited style from nothing.");
    cmd->add_option("--style", o->style, "Cluster hairstyle (JSON), or @default for the embedded one")->capture_default_str();
    cmd->add_option("--db", o->db, "HRIR database; default: the cached default database (built on first use)");
    cmd->add_option("--edits", o->edits, "Edits timed")->check(CLI::Range(1, 1000))->capture_default_str();
    cmd->add_option("--repeats", o->repeats, "Baseline cooks timed")->check(CLI::Range(1, 100))->capture_default_str();
    cmd->add_option("--cluster", o->cluster, "The cluster edited (its index; default: the middle one)")->check(CLI::NonNegativeNumber);
    cmd->add_option("--point", o->point, "Its control point moved (default: the middle one)")->check(CLI::NonNegativeNumber);
    cmd->add_option("--step", o->step, "How far each edit moves it, in % of the hair's longest side")
        ->check(CLI::Range(0.0, 100.0))
        ->capture_default_str();
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif bench edit\n  coif bench edit --cluster 3 --point 2 --step 2 --json");
    cmd->callback([o] {
        coif::HairStyle style = coif::cli::load_style(o->style);
        if (style.clusters.empty()) throw coif::Error(o->style, "clusters", "the style has no clusters");
        const std::size_t cluster = o->cluster < 0 ? style.clusters.size() / 2 : static_cast<std::size_t>(o->cluster);
        if (cluster >= style.clusters.size())
            throw coif::Error::parameter("cluster", "the style has " + std::to_string(style.clusters.size()) + " clusters");
        const std::size_t points = style.clusters[style.clusters[cluster].prototype].shape->trajectory().size();
        const std::size_t point = o->point < 0 ? points / 2 : static_cast<std::size_t>(o->point);
        if (point >= points)
            throw coif::Error::parameter("point", "the cluster has " + std::to_string(points) + " control points");
        const coif::HrirDatabase db = coif::open_database_or_default(o->db, nullptr);
        const coif::SatfIndex satf = coif::SatfIndex::open(db, coif::SatfOptions{});
        auto context = coif::gl::Context::headless();
        const glm::mat3 orientation = coif::style_orientation(style);

        // The baseline: a cook from nothing and a new renderer (its upload and programs), waited for.
        std::vector<double> full_cook, full_renderer;
        float longest = 0;
        for (int i = 0; i < o->repeats; ++i) {
            auto t = Clock::now();
            coif::CookedShells cooked = coif::cook_shells(style, satf, orientation);
            full_cook.push_back(ms_since(t));
            const glm::vec3 size = cooked.grid.strands_max - cooked.grid.strands_min;
            longest = std::max({size.x, size.y, size.z});
            t = Clock::now();
            coif::gl::ShellRenderer renderer(std::move(cooked));
            context->finish();
            full_renderer.push_back(ms_since(t));
        }
        // The edits, with a cache filled by a first cook, into one renderer.
        coif::CookCache cache;
        coif::gl::ShellRenderer renderer(coif::cook_shells(style, satf, orientation, 0, nullptr, &cache));
        context->finish();
        std::vector<double> cook, set_hair, total, prototypes, atlas, strands, tilts, grid, rest;
        int rebuilt = 0;
        const double step = o->step / 100.0 * longest;
        coif::CookedShells last;
        for (int i = 0; i < o->edits; ++i) {
            // Back and forth along x, then along z: a drag that stays near where it started.
            const double sign = (i / 2) % 2 == 0 ? 1.0 : -1.0;
            coif::move_control_point(style, cluster, point, i % 2 == 0 ? glm::dvec3(sign * step, 0, 0) : glm::dvec3(0, 0, sign * step));
            const auto t = Clock::now();
            coif::CookedShells cooked = coif::cook_shells(style, satf, orientation, 0, nullptr, &cache);
            cook.push_back(ms_since(t));
            if (i + 1 == o->edits) last = cooked;
            const auto u = Clock::now();
            renderer.set_hair(std::move(cooked));
            context->finish();
            set_hair.push_back(ms_since(u));
            total.push_back(ms_since(t));
            const coif::CookCache::Timings& ct = cache.timings();
            prototypes.push_back(ct.prototypes_ms);
            atlas.push_back(ct.atlas_ms);
            strands.push_back(ct.strands_ms);
            tilts.push_back(ct.tilts_ms);
            grid.push_back(ct.grid_ms);
            rest.push_back(ct.rest_ms);
            rebuilt += ct.grid_rebuilt;
        }
        const bool same = coif::hair_asset_bytes(last) == coif::hair_asset_bytes(coif::cook_shells(style, satf, orientation));
        const coif::CookCache::Timings& ct = cache.timings();
        const double baseline = coif::median(full_cook) + coif::median(full_renderer);
        const double edit = coif::median(total);
        const nlohmann::ordered_json j = {
            {"renderer", context->renderer()},
            {"style", o->style},
            {"cluster", cluster},
            {"point", point},
            {"step_percent", o->step},
            {"edits", o->edits},
            {"baseline_cook_ms", coif::median(full_cook)},
            {"baseline_renderer_ms", coif::median(full_renderer)},
            {"edit_ms", edit},
            {"edit_cook_ms", coif::median(cook)},
            {"edit_set_hair_ms", coif::median(set_hair)},
            {"edit_cook_parts_ms",
             {{"prototypes", coif::median(prototypes)}, {"atlas", coif::median(atlas)}, {"strands", coif::median(strands)},
              {"tilts", coif::median(tilts)}, {"grid", coif::median(grid)}, {"rest", coif::median(rest)}}},
            {"prototypes_made", ct.prototypes_made},
            {"prototypes", ct.prototypes},
            {"clusters_sampled", ct.clusters_sampled},
            {"clusters", ct.clusters},
            {"grid_voxelized_again", rebuilt},
            {"ratio", edit / baseline},
            {"same_as_cook_from_nothing", same}};
        if (o->json) coif::cli::print_json(j);
        else {
            std::printf("renderer %s; style %s: cluster %zu's control point %zu moved %d times by %.2g %% of %.1f\n\n",
                        context->renderer().c_str(), o->style.c_str(), cluster, point, o->edits, o->step, longest);
            std::printf("baseline (median of %d)      %8.1f ms  cook from nothing %.1f + new renderer %.1f\n", o->repeats,
                        baseline, coif::median(full_cook), coif::median(full_renderer));
            std::printf("one edit (median of %d)      %8.1f ms  cook %.1f + set_hair %.1f\n", o->edits, edit,
                        coif::median(cook), coif::median(set_hair));
            std::printf("  its cook's parts           prototypes %.1f, atlas %.1f, strands %.1f, tilts %.1f, grid %.1f, rest %.1f\n",
                        coif::median(prototypes), coif::median(atlas), coif::median(strands), coif::median(tilts),
                        coif::median(grid), coif::median(rest));
            std::printf("  made anew                  %zu of %zu prototypes, %zu of %zu clusters' strands; the grid voxelized "
                        "again in %d of %d edits\n",
                        ct.prototypes_made, ct.prototypes, ct.clusters_sampled, ct.clusters, rebuilt, o->edits);
            std::printf("ratio edit / baseline        %8.3f\n", edit / baseline);
            std::printf("the last edit's cook is %s a cook from nothing\n", same ? "the same, byte for byte, as" : "NOT the same as");
        }
        if (!same) throw coif::Error(o->style, "", "an edit's cook differs from a cook of the edited style from nothing");
    });
}

}  // namespace

COIF_REGISTER_COMMAND(97, add_bench_edit);
