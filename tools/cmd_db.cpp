// coif db build|merge|inspect|plot|eval|index|coverage — the HRIR database (004 §4–§5), built from the
// command line and shardable over any batch scheduler (docs/db.md).
#include <cstdio>

#include "db/coverage.h"
#include "db/eval.h"
#include "db/hrir_db.h"
#include "db/plot.h"
#include "db/satf.h"
#include "models/core/checksum.h"
#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {
namespace fs = std::filesystem;

void add_db(CLI::App& root) {
    CLI::App* db = coif::cli::noun(root, "db", "The HRIR database: random sectors ray-traced offline, looked up by density features");

    // ---- build ----
    struct BuildOpts {
        coif::BuildOptions b;
        std::string out, shard = "0/1";
        bool use_float = false, save_index = false;
    };
    auto bo = std::make_shared<BuildOpts>();
    CLI::App* build = db->add_subcommand(
        "build",
        "Generate N random generalized sectors (004 §5), ray-trace each in its plane (§5.1) on a grid of view and\n"
        "light azimuths, and write the HRIR database (format: db/hrir_db.h). Sector i depends only on (seed, i), so\n"
        "--shard k/n builds the contiguous range [N k/n, N (k+1)/n) and `coif db merge` of all n shards is\n"
        "byte-identical to the unsharded build. Finished chunks are kept in FILE.parts/ and --resume reuses them\n"
        "after a killed build. Prints records/second.");
    build->add_option("--sectors", bo->b.params.sectors, "Sectors in the whole build (default 1000)");
    build->add_option("--seed", bo->b.params.seed, "Global seed (default 1)");
    build->add_option("--threads", bo->b.threads, "Worker threads (default 0: every hardware thread; was 1 before v0.2)")
        ->check(CLI::Range(0, coif::kMaxThreads));
    build->add_option("--shard", bo->shard, "Build only shard k of n (0-based k), e.g. 3/8 (default 0/1: everything)");
    build->add_flag("--resume", bo->b.resume, "Reuse the valid finished chunks in FILE.parts/ (default: start afresh)");
    build->add_option("--chunk", bo->b.chunk, "Sectors per resumable chunk (default 64)");
    build->add_option("--views", bo->b.params.grids.views, "View azimuths over the full circle (default 32)");
    build->add_option("--hrir-length", bo->b.params.grids.hrir_length, "Samples along x per array (default 32)");
    build->add_option("--fourier-order", bo->b.params.grids.fourier_order, "Fourier order K of re in θl (default 4)");
    build->add_option("--light-samples", bo->b.params.grids.light_samples, "θl samples projected onto the Fourier basis (default 48)");
    build->add_option("--kappa", bo->b.params.tracer.kappa, "Opacity per unit density per λ of path (default 0.6)");
    build->add_option("--phong-exponent", bo->b.params.tracer.exponent, "Phong exponent of the in-plane reflectance (default 16)");
    build->add_option("--smoothing", bo->b.params.tracer.smoothing_ratio,
                      "Width of the Gaussian that smooths each array (004 §5.1), in strand Gaussian widths λ; 0 = none "
                      "(default 0; the paper's is 1.5: docs/quality.md \"Fibre detail\" measures both)")
        ->check(CLI::Range(0.0, 16.0));
    build->add_flag("--light-attenuation", bo->b.params.tracer.light_attenuation,
                    "Attenuate the light along its in-plane path to each sample (self-shadow in the sector; default off)");
    build->add_flag("--float", bo->use_float, "Store float32 records instead of half floats (default half)");
    build->add_flag("--save-index", bo->save_index, "Also save the FLANN index (rich+shape) beside the database");
    build->add_option("-o,--output", bo->out, "Database file to write")->required();
    coif::cli::examples(build, "  coif db build --sectors 4000 --threads 2 -o hrir.db\n"
                               "  coif db build --sectors 16000 --shard 3/8 -o hrir.part3.db   # then coif db merge\n"
                               "  coif db build --sectors 16000 --resume -o hrir.db            # after a killed build");
    build->callback([bo] {
        bo->b.shard = coif::parse_shard(bo->shard);
        bo->b.params.value_type = bo->use_float ? coif::ValueType::Float : coif::ValueType::Half;
        const coif::BuildReport r = coif::build_database(bo->b, bo->out);
        const int threads = coif::thread_count(bo->b.threads);
        std::fprintf(stderr, "wrote %s: sectors %llu..%llu (%llu reused), %.1f records/s on %d thread%s, %.2f MB\n", bo->out.c_str(),
                     static_cast<unsigned long long>(r.first), static_cast<unsigned long long>(r.first + r.count),
                     static_cast<unsigned long long>(r.reused), r.records_per_second(), threads, threads == 1 ? "" : "s",
                     static_cast<double>(fs::file_size(bo->out)) / 1e6);
        if (bo->save_index && bo->b.shard.count == 1) {
            const coif::HrirDatabase d = coif::HrirDatabase::open(bo->out);
            const coif::SatfIndex index(d, {});
            index.save(coif::SatfIndex::saved_path(d, coif::FeatureSet::RichShape));
        }
    });

    // ---- merge ----
    struct MergeOpts {
        std::vector<std::string> parts;
        std::string out;
    };
    auto mo = std::make_shared<MergeOpts>();
    CLI::App* merge = db->add_subcommand(
        "merge",
        "Merge the n shard files of one build (any order) into the finished database: byte-identical to the\n"
        "unsharded build with the same seed. Refuses gaps, overlaps and shards of different builds.");
    merge->add_option("parts", mo->parts, "Shard files written by coif db build --shard k/n")->required()->check(CLI::ExistingFile);
    merge->add_option("-o,--output", mo->out, "Database file to write")->required();
    coif::cli::examples(merge, "  coif db merge hrir.part*.db -o hrir.db");
    merge->callback([mo] {
        std::vector<fs::path> parts(mo->parts.begin(), mo->parts.end());
        coif::merge_databases(parts, mo->out);
        const coif::HrirDatabase d = coif::HrirDatabase::open(mo->out);
        std::fprintf(stderr, "wrote %s: %zu sectors, checksum %s\n", mo->out.c_str(), d.size(), coif::checksum_hex(d.checksum()).c_str());
    });

    // ---- inspect ----
    struct InspectOpts {
        std::string file;
        bool json = false;
    };
    auto io = std::make_shared<InspectOpts>();
    CLI::App* inspect = db->add_subcommand(
        "inspect", "Validate a database (magic, version, sizes, checksum) and print its parameters, angle grids, size per\n"
                   "1k sectors, and the range of every feature column and of the records.");
    inspect->add_option("file", io->file, "Database or shard file")->required()->check(CLI::ExistingFile);
    coif::cli::add_json_flag(inspect, io->json);
    coif::cli::examples(inspect, "  coif db inspect hrir.db\n  coif db inspect hrir.db --json");
    inspect->callback([io] {
        const coif::HrirDatabase d = coif::HrirDatabase::open(io->file);
        const nlohmann::json j = coif::inspect_json(d);
        if (io->json) {
            coif::cli::print_json(j);
            return;
        }
        const auto& g = d.params().grids;
        std::printf("%s  (%s, format %u, checksum %s)\n", io->file.c_str(), j["kind"].get<std::string>().c_str(), coif::kHrirFormatVersion,
                    coif::checksum_hex(d.checksum()).c_str());
        std::printf("  sectors          %zu (first %llu, build of %llu), seed %llu\n", d.size(),
                    static_cast<unsigned long long>(d.first_index()), static_cast<unsigned long long>(d.params().sectors),
                    static_cast<unsigned long long>(d.params().seed));
        std::printf("  size             %.2f MB, %.2f MB per 1k sectors\n", static_cast<double>(d.file_size()) / 1e6,
                    j["bytes_per_sector"].get<double>() * 1000 / 1e6);
        std::printf("  record           %d views × %d samples × (α + %d Fourier coefficients of re), %s\n", g.views, g.hrir_length,
                    g.coefficients(), d.params().value_type == coif::ValueType::Half ? "half" : "float");
        std::printf("  tracer           %s\n", coif::to_json(d.params().tracer).dump().c_str());
        std::printf("  generator        %s\n", coif::to_json(d.params().generator).dump().c_str());
        std::printf("  α mean %.3f max %.3f, re a0 max %.3f\n", j["alpha"]["mean"].get<double>(), j["alpha"]["max"].get<double>(),
                    j["re_a0_max"].get<double>());
        std::printf("  features (min / mean / max):\n");
        for (const auto& c : j["features"])
            std::printf("    %-22s %9.4f %9.4f %9.4f\n", c["name"].get<std::string>().c_str(), c["min"].get<double>(), c["mean"].get<double>(),
                        c["max"].get<double>());
    });

    // ---- plot ----
    struct PlotOpts {
        std::string file, out;
        std::size_t record = 0;
    };
    auto po = std::make_shared<PlotOpts>();
    CLI::App* plot = db->add_subcommand(
        "plot", "Draw one record: re and α against position x for θv = 0°, 45°, 135°, 180° (panels, top to bottom);\n"
                "white α, red re with the light behind the eye, green light at +90°, blue light along +r. y from 0 to 1.");
    plot->add_option("file", po->file, "Database file")->required()->check(CLI::ExistingFile);
    plot->add_option("--record", po->record, "Record (sector) index (default 0)");
    plot->add_option("-o,--output", po->out, "Image to write (.png or .exr)")->required();
    coif::cli::examples(plot, "  coif db plot hrir.db --record 17 -o record17.png");
    plot->callback([po] {
        coif::cli::lock_output(po->out);
        const coif::HrirDatabase d = coif::HrirDatabase::open(po->file);
        coif::write_image(po->out, coif::plot_record(d, po->record));
        std::fprintf(stderr, "wrote %s\n", po->out.c_str());
    });

    // ---- eval ----
    struct EvalOpts {
        std::string file;
        coif::EvalOptions e;
        std::vector<std::string> sets, blends;
        bool json = false, study = false;
    };
    auto eo = std::make_shared<EvalOpts>();
    CLI::App* eval = db->add_subcommand(
        "eval", "Generate M fresh sectors that are not in the database, ray-trace them at random (θv, θl), and print the\n"
                "relative L2 error of the SATF look-up against that truth (median, p95 over sectors) for re and α, for each\n"
                "feature set, k and blend; the 'oracle' row is the sector's own record (the storage floor). --study adds\n"
                "the error of each storage choice (Fourier order, view grid, HRIR length, half floats).");
    eval->add_option("file", eo->file, "Database file")->required()->check(CLI::ExistingFile);
    eval->add_option("--held-out", eo->e.held_out, "Held-out sectors M (default 200)");
    eval->add_option("--pairs", eo->e.angle_pairs, "Random (θv, θl) pairs per held-out sector (default 8)");
    eval->add_option("--k", eo->e.ks, "Neighbour counts to try (default 1 2 4 8 16)");
    eval->add_option("--features", eo->sets, "Feature sets to try: paper, paper+shape, rich, rich+shape (default all)");
    eval->add_option("--blend", eo->blends, "Blends to try: idw, gauss (default both)");
    eval->add_option("--threads", eo->e.threads, "Worker threads (default 0: every hardware thread; was 1 before v0.2)")
        ->check(CLI::Range(0, coif::kMaxThreads));
    eval->add_flag("--study", eo->study, "Also run the storage/resolution study");
    coif::cli::add_json_flag(eval, eo->json);
    coif::cli::examples(eval, "  coif db eval hrir.db --held-out 200 --threads 2\n  coif db eval hrir.db --held-out 50 --k 4 --features rich+shape --json");
    eval->callback([eo] {
        if (eo->json) coif::Progress::set_quiet(true);
        if (!eo->sets.empty()) {
            eo->e.sets.clear();
            for (const auto& s : eo->sets) eo->e.sets.push_back(coif::feature_set_from_name(s));
        }
        if (!eo->blends.empty()) {
            eo->e.blends.clear();
            for (const auto& b : eo->blends) eo->e.blends.push_back(coif::blend_from_name(b));
        }
        const coif::HrirDatabase d = coif::HrirDatabase::open(eo->file);
        const coif::EvalReport r = coif::evaluate_database(d, eo->e);
        std::vector<coif::StudyRow> study;
        if (eo->study) study = coif::resolution_study(d.params(), eo->e.held_out, eo->e.threads);
        if (eo->json) {
            nlohmann::json j = coif::to_json(r);
            if (eo->study) j["study"] = coif::to_json(study);
            coif::cli::print_json(j);
            return;
        }
        std::printf("SATF look-up error on %zu held-out sectors × %d angle pairs, database of %zu sectors (relative L2)\n", r.held_out,
                    r.angle_pairs, r.sectors);
        std::printf("  %-12s %3s %-6s  %9s %9s  %9s %9s\n", "features", "k", "blend", "re med", "re p95", "α med", "α p95");
        for (const auto& row : r.rows)
            std::printf("  %-12s %3d %-6s  %9.4f %9.4f  %9.4f %9.4f\n", row.set.c_str(), row.k, row.blend.c_str(), row.re.median, row.re.p95,
                        row.alpha.median, row.alpha.p95);
        if (eo->study) {
            std::printf("storage study (relative L2 against a direct trace)\n  %-14s %5s  %9s %9s  %9s %9s\n", "quantity", "value", "re med",
                        "re p95", "α med", "α p95");
            for (const auto& row : study)
                std::printf("  %-14s %5d  %9.4f %9.4f  %9.4f %9.4f\n", row.quantity.c_str(), row.value, row.re.median, row.re.p95,
                            row.alpha.median, row.alpha.p95);
        }
        std::printf("(%.1f s)\n", r.seconds);
    });

    // ---- coverage ----
    struct CoverageOpts {
        std::string file, set = "rich+shape";
        std::vector<std::string> styles;
        coif::CoverageOptions c;
        bool json = false;
    };
    auto co = std::make_shared<CoverageOpts>();
    CLI::App* coverage = db->add_subcommand(
        "coverage",
        "Does the database cover the sectors a real hairstyle asks for? Computes the features of every sector of each\n"
        "style (the renderer's densities, shape in the style's own λ) and prints, per feature column, the database's\n"
        "1st-99th percentile and range against the style's range, with the share of style sectors below p1 / above p99\n"
        "(≈ 1 % each if the generator's ranges fit); then the distance of each style sector to its nearest record in the\n"
        "look-up's normalised feature space, against held-out random sectors of the database's own generator (median,\n"
        "p95), and the share of style sectors farther than the held-out p95; and each non-empty sector's mean density over\n"
        "its nearest record's (the records are traced at their own density, so a ratio far from 1 draws the sector with\n"
        "another sector's coverage). Format: db/coverage.h.");
    coverage->add_option("file", co->file, "Database file")->required()->check(CLI::ExistingFile);
    coverage->add_option("styles", co->styles, "Style files (JSON, coif style import), or @default for the embedded style")->required();
    coverage->add_option("--features", co->set, "Feature set of the distances: paper, paper+shape, rich, rich+shape (default rich+shape)");
    coverage->add_option("--held-out", co->c.held_out, "Held-out random sectors for the reference distances (default 1000)");
    coif::cli::add_json_flag(coverage, co->json);
    coif::cli::examples(coverage, "  coif db coverage hrir.db @default\n"
                                  "  coif style import harolongo.data --clusters 64 -o h64.json && coif db coverage hrir.db h64.json --json");
    coverage->callback([co] {
        co->c.set = coif::feature_set_from_name(co->set);
        if (co->c.held_out < 1) throw coif::Error::parameter("--held-out", "must be at least 1");
        const coif::HrirDatabase d = coif::HrirDatabase::open(co->file);
        if (d.is_shard()) throw coif::Error(co->file, "", "a shard has no feature statistics: merge the shards first (coif db merge)");
        const std::vector<float> held = coif::held_out_sector_features(d.params(), co->c.held_out);
        nlohmann::json all = nlohmann::json::array();
        for (const std::string& name : co->styles) {
            const coif::HairStyle style = coif::cli::load_style(name);
            const std::vector<float> rows = coif::style_sector_features(style);
            coif::CoverageReport r = coif::database_coverage(d, rows, held, co->c);
            r.style = name;
            if (style.layout.grid_s != d.params().generator.feature_grid_s || style.layout.grid_r != d.params().generator.feature_grid_r)
                std::fprintf(stderr, "coif: note: %s: density grid %dx%d, the database's features use %dx%d\n", name.c_str(), style.layout.grid_s,
                             style.layout.grid_r, d.params().generator.feature_grid_s, d.params().generator.feature_grid_r);
            if (co->json) {
                all.push_back(coif::to_json(r));
                continue;
            }
            std::printf("%s against %s (%zu sectors): %zu sectors, λ = %g; empty sectors %.1f %% (database %.1f %%)\n", name.c_str(),
                        co->file.c_str(), r.db_sectors, r.style_sectors, style.layout.gaussian_width, 100 * r.style_empty, 100 * r.db_empty);
            std::printf("  %-22s %8s %8s %8s %8s | %8s %8s %8s %8s %8s | %6s %6s\n", "column", "db min", "db p1", "db p99", "db max", "st min",
                        "st p1", "st med", "st p99", "st max", "<p1 %", ">p99 %");
            for (const auto& c : r.columns)
                std::printf("  %-22s %8.3f %8.3f %8.3f %8.3f | %8.3f %8.3f %8.3f %8.3f %8.3f | %6.1f %6.1f\n", c.name.c_str(), c.db_min, c.db_p01,
                            c.db_p99, c.db_max, c.style_min, c.style_p01, c.style_median, c.style_p99, c.style_max, 100 * c.below, 100 * c.above);
            std::printf("  nearest-record distance (%s, normalised): style median %.3f p95 %.3f; held-out (%zu) median %.3f p95 %.3f\n",
                        r.set.c_str(), r.style_distance.median, r.style_distance.p95, r.held_out, r.held_out_distance.median,
                        r.held_out_distance.p95);
            std::printf("  style sectors beyond the held-out p95: %.1f %% (%.1f %% of the non-empty ones)\n", 100 * r.style_beyond_held_out_p95,
                        100 * r.style_beyond_held_out_p95_nonempty);
            const auto& dm = r.density_ratio;
            std::printf("  mean density, style sector over its nearest record (%zu non-empty sectors): p10 %.3g, median %.3g, p90 %.3g;"
                        " %.1f %% outside [1/2, 2]\n",
                        dm.sectors, dm.p10, dm.median, dm.p90, 100 * dm.outside_half_to_double);
        }
        if (co->json) coif::cli::print_json(all);
    });

    // ---- index ----
    struct IndexOpts {
        std::string file, set = "rich+shape";
    };
    auto xo = std::make_shared<IndexOpts>();
    CLI::App* index = db->add_subcommand(
        "index", "Build the FLANN k-d tree of a feature set and save it beside the database (FILE.<set>.flann), bound to the\n"
                 "database's checksum; look-ups load it instead of rebuilding, and refuse it for any other database.");
    index->add_option("file", xo->file, "Database file")->required()->check(CLI::ExistingFile);
    index->add_option("--features", xo->set, "Feature set (default rich+shape)");
    coif::cli::examples(index, "  coif db index hrir.db --features rich+shape");
    index->callback([xo] {
        const coif::HrirDatabase d = coif::HrirDatabase::open(xo->file);
        coif::SatfOptions o;
        o.set = coif::feature_set_from_name(xo->set);
        const coif::SatfIndex idx(d, o);
        const fs::path p = coif::SatfIndex::saved_path(d, o.set);
        idx.save(p);
        std::fprintf(stderr, "wrote %s\n", p.c_str());
    });
}

COIF_REGISTER_COMMAND(30, add_db);

}  // namespace
