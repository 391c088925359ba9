// coif lighting check|plot — the SRBF circular-Gaussian Marschner lighting (000 §4-5, issue 6)
// against its brute-force reference: error tables, and plots of exact vs approximate terms (000 Fig. 3).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "models/core/atomic_file.h"
#include "models/core/error.h"
#include "models/core/image.h"
#include "models/core/progress.h"
#include "shaders/lighting_check.h"
#include "shaders/lighting_plot.h"
#include "tools/cli.h"
#include "tools/hair_options.h"

namespace {

namespace fs = std::filesystem;
using namespace coif::shading;

nlohmann::json stats_json(const check::Stats& s) {
    return {{"median", s.median},
            {"p95", s.p95},
            {"max", s.max},
            {"median_unweighted", s.median_unweighted},
            {"p95_unweighted", s.p95_unweighted},
            {"count", s.count}};
}

struct CheckOptions {
    int configs = 1000;
    int ms_sets = 6;
    int ms_configs = 30;
    std::uint64_t seed = 1;
    bool json = false;
};

void run_check(const CheckOptions& o) {
    coif::Progress::set_quiet(o.json);
    const auto t0 = std::chrono::steady_clock::now();
    const LightingTables& tables = global_lighting_tables();
    const auto configs = check::random_configs(o.configs, o.seed);
    std::vector<check::SingleRow> single;
    {
        coif::Progress bar("single scattering vs brute force", std::uint64_t(o.configs));
        single = check::check_single(configs, {2, 4, 6, 200}, [&] { bar.advance(); });
        bar.finish();
    }
    std::vector<check::ApproxRow> approx;
    {
        coif::Progress bar("approximations on grids", 9);
        approx = check::check_approximations([&] { bar.advance(); });
        bar.finish();
    }
    std::vector<check::MultipleRow> multiple;
    {
        coif::Progress bar("multiple scattering vs brute force", std::uint64_t(o.ms_sets));
        multiple = check::check_multiple(o.ms_sets, o.ms_configs, o.seed + 100, [&] { bar.advance(); });
        bar.finish();
    }
    const auto cost = check::count_fetches(4);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    if (o.json) {
        nlohmann::json doc;
        doc["tables_build_seconds"] = tables.build_seconds;
        doc["configs"] = o.configs;
        doc["seed"] = o.seed;
        for (const auto& r : single)
            doc["single_scattering"].push_back({{"variant", r.variant}, {"m", r.segments}, {"stats", stats_json(r.stats)}});
        for (const auto& r : approx)
            doc["approximations"].push_back({{"name", r.name}, {"metric", r.metric}, {"max", r.max}, {"rms", r.rms}, {"samples", r.samples}});
        for (const auto& r : multiple) doc["multiple_scattering"].push_back({{"term", r.term}, {"stats", stats_json(r.stats)}});
        for (const auto& r : cost) doc["texture_fetches"].push_back({{"what", r.what}, {"per_light", r.fetches_per_light}});
        doc["seconds"] = seconds;
        coif::cli::print_json(doc);
        return;
    }
    std::printf("SRBF lighting vs brute force (issue 6). Tables built in %.3f s at start-up.\n\n", tables.build_seconds);
    std::printf("Single scattering of one SRBF light, %d random configurations (seed %llu).\n", o.configs,
                static_cast<unsigned long long>(o.seed));
    std::printf("Relative error of the RGB sum; median/p95 weighted by energy (response per unit light energy);\n");
    std::printf("'improved' = our default, 'paper' = 000 as written. Issue bound at m = 4: median <= 2 %%, p95 <= 5 %%.\n");
    std::printf("  %-9s %4s  %8s %8s %8s   %12s %10s\n", "variant", "m", "median", "p95", "max", "unw. median", "unw. p95");
    for (const auto& r : single)
        std::printf("  %-9s %4d  %7.2f%% %7.2f%% %7.1f%%   %11.2f%% %9.2f%%\n", r.variant.c_str(), r.segments,
                    100 * r.stats.median, 100 * r.stats.p95, 100 * r.stats.max, 100 * r.stats.median_unweighted,
                    100 * r.stats.p95_unweighted);
    std::printf("\nEach approximation on its own, on a grid:\n");
    std::printf("  %-50s %10s %10s  %s\n", "approximation", "max", "rms", "metric");
    for (const auto& r : approx)
        std::printf("  %-50s %10.3e %10.3e  %s\n", r.name.c_str(), r.max, r.rms, r.metric.c_str());
    std::printf("\nMultiple scattering vs brute-force dual scattering (%d parameter sets x %d configurations, m = 4):\n",
                o.ms_sets, o.ms_configs);
    for (const auto& r : multiple)
        std::printf("  %-16s median %6.2f%%  p95 %6.2f%%  max %6.1f%%\n", r.term.c_str(), 100 * r.stats.median,
                    100 * r.stats.p95, 100 * r.stats.max);
    std::printf("\nTexture look-ups (counted through the CPU back end, m = 4):\n");
    for (const auto& r : cost) std::printf("  %-45s %6.2f\n", r.what.c_str(), r.fetches_per_light);
    std::printf("\n(%.1f s)\n", seconds);
}

void add_lighting(CLI::App& root) {
    CLI::App* lighting = coif::cli::noun(
        root, "lighting", "The SRBF circular-Gaussian Marschner lighting: its approximations against brute force");

    auto co = std::make_shared<CheckOptions>();
    CLI::App* check_cmd = lighting->add_subcommand(
        "check",
        "Measure every approximation of the SRBF lighting (000 §4-5) against the exact Marschner model\n"
        "integrated by brute force: per-light single scattering over random configurations (light direction,\n"
        "bandwidth lambda in [0.05, 2], view, eta in [1.4, 1.8], sigma_a in [0, 3], alpha_R in [-10, 0] deg,\n"
        "beta_R in [2, 15] deg, eccentricity in [0.85, 1.15], w_c in [0.05, 0.3]) for m = 2, 4, 6, 200 segments\n"
        "of the linear quadrature, the paper's variant beside ours; each table and fit on a grid; multiple\n"
        "scattering against brute-force dual scattering; and texture look-ups per light. Takes minutes.");
    check_cmd->add_option("--configs", co->configs, "Random single-scattering configurations (default 1000)")
        ->check(CLI::Range(1, 1000000));
    check_cmd->add_option("--ms-sets", co->ms_sets, "Random parameter sets for multiple scattering (default 6)")
        ->check(CLI::Range(1, 10000));
    check_cmd->add_option("--ms-configs", co->ms_configs, "Light/view configurations per parameter set (default 30)")
        ->check(CLI::Range(1, 100000));
    check_cmd->add_option("--seed", co->seed, "Seed of the random configurations (default 1)");
    coif::cli::add_json_flag(check_cmd, co->json);
    coif::cli::examples(check_cmd, "  coif lighting check\n  coif lighting check --configs 200 --ms-sets 2 --json");
    check_cmd->callback([co] { run_check(*co); });

    struct PlotOptions {
        std::string out;
        coif::cli::HairCliOptions hair;
        coif::gl::ShellSettings base;  // 000's brown hair, but grey σa = 0.2 (000 Fig. 3)
    };
    auto po = std::make_shared<PlotOptions>();
    po->base.hair.fibre.sigma_a = glm::vec3(0.2f);
    CLI::App* plot = lighting->add_subcommand(
        "plot",
        "Write PNG plots of exact vs approximate terms, as 000 Fig. 3: N_TT (one circular Gaussian) and N_TRT\n"
        "(three or one) at theta_d = 0, pi/6, pi/3; the attenuation T(h) with its Taylor expansion and our\n"
        "interpolation for sigma_a = 0.2, 0.6, 1.0; and the integrand of the linear quadrature\n"
        "N_t cos^2(theta_i)/cos^2(theta_d) for lambda' = 0.5. Exact curves solid, approximations dashed; each PNG\n"
        "has a CSV of its data and README.txt lists colours and axes. Bad parameter values are refused (exit 1).");
    plot->add_option("-o,--out", po->out, "Output folder (created if missing)")->required();
    po->hair.add_to(plot, po->base.hair);
    coif::cli::examples(plot, "  coif lighting plot -o lighting_plots/\n  coif lighting plot -o dark/ --sigma-a 1.2 1.6 2.4 --eta 1.6");
    plot->callback([po] {
        const HairParams params = po->hair.settings(po->base).hair.fibre;  // validated
        const fs::path dir(po->out);
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) throw coif::Error(dir, "", "cannot create the folder: " + ec.message());
        std::string readme = "coif lighting plot: exact (solid) vs approximate (dashed) terms of the SRBF lighting (000 Fig. 3).\n"
                             "PNG tone map: linear 8-bit, white background. Axes: x from left to right, y from bottom to top;\n"
                             "ranges below. Colours per series as listed.\n\n";
        for (const auto& [name, p] : fig3_plots(params)) {
            coif::write_image(dir / (name + ".png"), render_plot(p, 900, 560));
            coif::write_file_atomic(dir / (name + ".csv"), plot_csv(p));
            readme += plot_description(name, p) + "\n";
            std::printf("wrote %s\n", (dir / (name + ".png")).string().c_str());
        }
        coif::write_file_atomic(dir / "README.txt", readme);
    });
}

COIF_REGISTER_COMMAND(55, add_lighting);

}  // namespace
