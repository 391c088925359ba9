// coif env fit|inspect — environment maps as SRBF lights (000 eq. 1).
#include <cmath>
#include <cstdio>
#include <memory>

#include "models/core/atomic_file.h"
#include "models/core/units.h"
#include "models/core/checksum.h"
#include "models/core/error.h"
#include "models/core/image.h"
#include "models/core/progress.h"
#include "offline/envmap.h"
#include "offline/srbf_fit.h"
#include "offline/srbf_lights.h"
#include "shaders/envmap.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {
namespace fs = std::filesystem;

// Width of each half of the preview image (original | reconstruction), or the map's width if smaller.
constexpr int kPreviewWidth = 512;

nlohmann::json vec_json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json record_json(const coif::SrbfFitRecord& f) { return nlohmann::json(coif::srbf_fit_record_json(f)); }

void check_output_folder(const fs::path& path, const char* option) {
    const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(parent)) throw coif::Error(path, std::string("option ") + option, "folder does not exist");
}

// Direction → (elevation above the horizon, azimuth from +x toward +z), degrees.
glm::dvec2 elevation_azimuth_degrees(const glm::vec3& w) {
    const double elevation = coif::degrees(std::asin(std::clamp(double(w.y), -1.0, 1.0)));
    const double azimuth = coif::degrees(std::atan2(double(w.z), double(w.x)));
    return {elevation, azimuth};
}

void print_record(const coif::SrbfFitRecord& f) {
    std::printf("  fit                 N = %d, seed %llu, fit grid %dx%d (x%d supersampled), lambda in [%.4g, %.4g]\n",
                f.lights, static_cast<unsigned long long>(f.seed), f.fit_width, f.fit_width / 2, f.supersampling,
                f.lambda_min, f.lambda_max);
    std::printf("  solver              %d Levenberg-Marquardt iterations (limit %d), %s, %.2f s\n", f.iterations,
                f.max_iterations, f.termination.c_str(), f.seconds);
    std::printf("  relative L2 error   %.4f  full-resolution map (solid-angle weighted, RGB)\n", f.relative_l2_error);
    std::printf("                      %.4f  on the %dx%d fit grid\n", f.relative_l2_error_fit_grid, f.fit_width,
                f.fit_width / 2);
    std::printf("  energy error        %+.3f %%  (R %+.3f %%, G %+.3f %%, B %+.3f %%)  of the integral of L over the sphere\n",
                100 * f.energy_error, 100 * f.energy_error_rgb.r, 100 * f.energy_error_rgb.g,
                100 * f.energy_error_rgb.b);
}

struct FitOptions {
    std::string map;
    std::string output;
    std::string preview;
    coif::SrbfFitSettings settings;
    float exposure = NAN;
    double rotate_deg = 0;
    bool json = false;
};

void fit_command(const FitOptions& o) {
    // Check everything the user gave before the (long) fit, so that a bad option costs nothing and
    // leaves nothing behind.
    check_output_folder(o.output, "-o");
    if (!o.preview.empty()) {
        check_output_folder(o.preview, "--preview");
        const std::string ext = fs::path(o.preview).extension().string();
        if (ext != ".png" && ext != ".exr" && ext != ".hdr")
            throw coif::Error(o.preview, "option --preview", "use a .png, .exr or .hdr file");
    }
    coif::cli::lock_output(o.output);
    if (!o.preview.empty()) coif::cli::lock_output(o.preview);
    if (o.settings.lights < 1 || o.settings.lights > coif::kMaxSrbfLights)
        throw coif::Error::parameter("option --lights", std::to_string(o.settings.lights) + ": expected 1.." +
                                                            std::to_string(coif::kMaxSrbfLights));

    const float turn = coif::cli::lights_rotation(o.rotate_deg);
    coif::EnvMapLoadInfo info;
    const coif::EnvMap map = coif::rotate_envmap_y(coif::load_envmap(o.map, &info), turn);
    for (const std::string& w : info.warnings) std::fprintf(stderr, "coif: warning: %s\n", w.c_str());

    coif::SrbfFitSettings settings = o.settings;
    settings.fit_width = std::min(settings.fit_width, map.width);
    std::unique_ptr<coif::Progress> bar;
    const coif::SrbfFitResult result = coif::fit_srbf_lights(map, settings, [&](int iteration, int max_iterations) {
        if (!bar) bar = std::make_unique<coif::Progress>("fitting " + std::to_string(settings.lights) + " SRBF lights",
                                                         std::uint64_t(max_iterations));
        (void)iteration;
        bar->advance(1);
    });
    if (bar) bar->finish();

    coif::SrbfLightSet set;
    set.lights = result.lights;
    set.source = coif::SrbfSource{fs::path(o.map).filename().string(), info.checksum, map.width, map.height, std::fmod(o.rotate_deg, 360.0)};
    set.fit = result.record;
    coif::write_srbf_lights(o.output, set);

    float exposure = o.exposure;
    if (!o.preview.empty()) {
        const int width = std::min(kPreviewWidth, map.width - map.width % 2);
        const coif::EnvMap original = coif::downsample_envmap(map, width);
        const coif::EnvMap fitted = coif::render_srbf_lights(result.lights, width);
        if (std::isnan(exposure)) exposure = coif::envmap_preview_exposure(original);
        coif::Image side(2 * width, width / 2, 3);
        for (int row = 0; row < width / 2; ++row)
            for (int col = 0; col < width; ++col) {
                const glm::vec3& a = original.at(col, row);
                const glm::vec3& b = fitted.at(col, row);
                float* pa = side.at(col, row);
                float* pb = side.at(width + col, row);
                pa[0] = a.r, pa[1] = a.g, pa[2] = a.b;
                pb[0] = b.r, pb[1] = b.g, pb[2] = b.b;
            }
        coif::WriteOptions wo;
        wo.exposure = exposure;
        wo.description = "left: " + fs::path(o.map).filename().string() + "; right: " +
                         std::to_string(result.lights.size()) + " SRBF lights (coif env fit); exposure " +
                         std::to_string(exposure) + " stops on both";
        coif::write_image(o.preview, side, wo);
    }

    const coif::SrbfFitRecord& f = result.record;
    if (o.json) {
        nlohmann::json doc = {{"map", o.map},
                              {"checksum", coif::checksum_hex(info.checksum)},
                              {"width", map.width},
                              {"height", map.height},
                              {"warnings", info.warnings},
                              {"fit", record_json(f)},
                              {"lights_file", o.output}};
        if (!o.preview.empty()) doc["preview"] = {{"file", o.preview}, {"exposure", exposure}};
        coif::cli::print_json(doc);
        return;
    }
    std::printf("%s  (%dx%d, checksum %s)\n", o.map.c_str(), map.width, map.height,
                coif::checksum_hex(info.checksum).c_str());
    print_record(f);
    std::printf("wrote %s\n", o.output.c_str());
    if (!o.preview.empty())
        std::printf("wrote %s  (left: the map, right: the %d lights; tone-mapped at %+.2f stops, the same for both)\n",
                    o.preview.c_str(), f.lights, exposure);
}

void inspect_command(const std::string& file, const std::string& map_path, bool json) {
    const coif::SrbfLightSet set = coif::read_srbf_lights(file);
    std::optional<bool> checksum_matches;
    if (!map_path.empty()) {
        if (!set.source) throw coif::Error(file, "JSON /source", "the lights file records no source map to compare with");
        checksum_matches = coif::checksum(coif::read_file_bytes(map_path)) == set.source->checksum;
    }
    const glm::dvec3 energy = coif::srbf_lights_energy(set.lights);
    const double total_y = coif::luminance(energy);

    if (json) {
        nlohmann::json lights = nlohmann::json::array();
        for (const coif::SrbfLight& l : set.lights) {
            const glm::dvec2 ea = elevation_azimuth_degrees(l.omega);
            const glm::vec2 uv = coif::glsl::envmap_uv(l.omega);
            const double e = coif::luminance(glm::dvec3(l.L)) * coif::glsl::srbf_integral(l.lambda);
            lights.push_back({{"L", vec_json(l.L)},
                              {"omega", vec_json(l.omega)},
                              {"lambda", l.lambda},
                              {"elevation_degrees", ea.x},
                              {"azimuth_degrees", ea.y},
                              {"map_uv", {uv.x, uv.y}},
                              {"energy_share", total_y > 0 ? e / total_y : 0.0}});
        }
        nlohmann::json doc = {{"file", file}, {"lights", set.lights.size()}, {"energy", vec_json(energy)}};
        if (set.source)
            doc["source"] = {{"file", set.source->file},
                             {"checksum", coif::checksum_hex(set.source->checksum)},
                             {"width", set.source->width},
                             {"height", set.source->height},
                             {"rotation_y_deg", set.source->rotation_y_deg}};
        if (checksum_matches) doc["source_matches"] = *checksum_matches;
        if (set.fit) doc["fit"] = record_json(*set.fit);
        doc["light_list"] = lights;
        coif::cli::print_json(doc);
        return;
    }
    std::printf("%s  (%zu SRBF lights)\n", file.c_str(), set.lights.size());
    if (set.source) {
        std::printf("  source              %s  (%dx%d, checksum %s)%s\n", set.source->file.c_str(), set.source->width,
                    set.source->height, coif::checksum_hex(set.source->checksum).c_str(),
                    !checksum_matches ? "" : *checksum_matches ? "  matches the given map" : "  DIFFERS from the given map");
        if (set.source->rotation_y_deg != 0) std::printf("  turned about +y    %g deg before the fit\n", set.source->rotation_y_deg);
    }

    if (set.fit) print_record(*set.fit);
    std::printf("  total energy        (%.4g, %.4g, %.4g)  radiance x sr\n", energy.r, energy.g, energy.b);
    std::printf("\n    #   L (R, G, B)                        elev.   azim.   lambda  (deg)   energy\n");
    for (size_t i = 0; i < set.lights.size(); ++i) {
        const coif::SrbfLight& l = set.lights[i];
        const glm::dvec2 ea = elevation_azimuth_degrees(l.omega);
        const double e = coif::luminance(glm::dvec3(l.L)) * coif::glsl::srbf_integral(l.lambda);
        std::printf("  %3zu   %10.4g %10.4g %10.4g   %6.1f  %6.1f   %6.4f  (%5.1f)  %5.1f %%\n", i, l.L.r, l.L.g, l.L.b,
                    ea.x, ea.y, l.lambda, coif::degrees(double(l.lambda)), total_y > 0 ? 100.0 * e / total_y : 0.0);
    }
    std::printf("\n  elev. = degrees above the horizon (y up); azim. = degrees from +x toward +z (map column u = 0.5 + azim/360);\n"
                "  lambda = bandwidth of G = exp(2(w.w_j - 1)/lambda^2), in radians and (degrees); energy = share of the\n"
                "  lights' total luminous energy.\n");
    if (checksum_matches && !*checksum_matches)
        throw coif::Error(map_path, "checksum", "the map is not the one these lights were fitted to (checksum " +
                                                    coif::checksum_hex(set.source->checksum) + " in " + file + ")");
}


// coif bench env: the issue-7 table (fit error, energy error and time for several N, every map given).
struct BenchOptions {
    std::vector<std::string> maps;
    std::vector<int> lights{10, 20, 40, 80};
    std::vector<int> fit_widths{coif::kDefaultSrbfFitWidth};
    coif::SrbfFitSettings settings;
    bool json = false;
};

void bench_command(const BenchOptions& o) {
    nlohmann::json rows = nlohmann::json::array();
    if (!o.json)
        std::printf("%-36s %5s %9s %12s %12s %10s %7s %6s\n", "map", "N", "fit grid", "L2 err full", "L2 err grid",
                    "energy err", "iters", "s");
    for (const std::string& path : o.maps) {
        coif::EnvMapLoadInfo info;
        const coif::EnvMap map = coif::load_envmap(path, &info);
        for (int width : o.fit_widths)
            for (int n : o.lights) {
                coif::SrbfFitSettings s = o.settings;
                s.lights = n;
                s.fit_width = std::min(width, map.width);
                const coif::SrbfFitRecord f = coif::fit_srbf_lights(map, s).record;
                if (o.json) {
                    nlohmann::json row = record_json(f);
                    row["map"] = path;
                    rows.push_back(row);
                    continue;
                }
                char grid[32];
                std::snprintf(grid, sizeof grid, "%dx%d", f.fit_width, f.fit_width / 2);
                std::printf("%-36s %5d %9s %12.4f %12.4f %+9.2f%% %7d %6.2f\n",
                            fs::path(path).filename().string().c_str(), n, grid, f.relative_l2_error,
                            f.relative_l2_error_fit_grid, 100 * f.energy_error, f.iterations, f.seconds);
                std::fflush(stdout);
            }
    }
    if (o.json) coif::cli::print_json(rows);
    else
        std::printf("\nL2 err = solid-angle-weighted relative L2 error of the RGB radiance (full = against the full-resolution\n"
                    "map at its pixel centres; grid = against the box-filtered fit grid the solver saw); energy err = relative\n"
                    "error of the luminous energy (integral of Y over the sphere); s = seconds of one fit on one core.\n");
}

void add_env(CLI::App& root) {
    CLI::App* env = coif::cli::noun(
        root, "env",
        "Environment maps as SRBF lights: fit N spherical Gaussians to an HDR map, inspect a lights file");

    auto fo = std::make_shared<FitOptions>();
    CLI::App* fit = env->add_subcommand(
        "fit",
        "Fit N SRBF lights L(w) ~ sum_j L_j exp(2(w.w_j - 1)/lambda_j^2) (000 eq. 1) to an equirectangular map.\n"
        "The map (.hdr, .exr; 2:1, row 0 = +y, centre column = +x, quarter column = -z) is downsampled to the fit\n"
        "grid; the lights are initialised by a k-means clustering of the map's energy and refined by Ceres\n"
        "(Levenberg-Marquardt) minimising the solid-angle-weighted squared error; bandwidths are kept within\n"
        "[lambda-min, lambda-max]. Prints the relative L2 error (full map and fit grid) and the energy error.\n"
        "Same map, options and seed give the same lights. 8-bit images are accepted with a warning; maps that are\n"
        "not 2:1 or hold NaN, Inf or negative values are refused (exit 1, nothing written).");
    fit->add_option("map", fo->map, "Equirectangular HDR map (.hdr or .exr)")->required()->check(CLI::ExistingFile);
    fit->add_option("-n,--lights", fo->settings.lights, "Number of SRBF lights N (1.." + std::to_string(coif::kMaxSrbfLights) + ")")
        ->required();
    fit->add_option("-o,--output", fo->output, "Lights file to write (JSON; records the map's checksum and the fit)")
        ->required();
    fit->add_option("--preview", fo->preview,
                    "Also write the map (left) and the fitted lights (right) side by side: .png tone-mapped with one "
                    "exposure for both, or .exr/.hdr linear");
    fit->add_option("--exposure", fo->exposure,
                    "Preview exposure in stops (default: the map's log-average luminance brought to 0.18)");
    fit->add_option("--seed", fo->settings.seed, "Seed of the k-means++ initialisation");
    fit->add_option("--rotate", fo->rotate_deg,
                    "Turn the map by DEG degrees about +y (+x toward -z) before fitting, as coif render/reference "
                    "--rotate-lights turn it (recorded in the file's source)");
    fit->add_option("--fit-width", fo->settings.fit_width,
                    "Width of the fit grid in pixels (the map is box-filtered to W x W/2; capped at the map's width)");
    fit->add_option("--supersampling", fo->settings.supersampling,
                    "Sub-samples per fit-grid pixel side (the lights are box-filtered over each pixel like the map)");
    fit->add_option("--lambda-min", fo->settings.lambda_min,
                    "Smallest bandwidth (radians; 0 = one sub-sample, pi / (supersampling x fit-width/2))");
    fit->add_option("--lambda-max", fo->settings.lambda_max, "Largest bandwidth (radians)");
    fit->add_option("--max-iterations", fo->settings.max_iterations, "Levenberg-Marquardt iteration limit");
    coif::cli::add_json_flag(fit, fo->json);
    coif::cli::examples(fit,
                        "  coif env fit ../shared/data/blender_studiolight_courtyard.exr --lights 40 -o courtyard.json "
                        "--preview courtyard_fit.png\n"
                        "  coif env fit city.hdr -n 80 --fit-width 128 -o city80.json --json");
    fit->callback([fo] { fit_command(*fo); });

    struct InspectOptions {
        std::string file, map;
        bool json = false;
    };
    auto io = std::make_shared<InspectOptions>();
    CLI::App* inspect = env->add_subcommand(
        "inspect",
        "Read and validate a lights file and print its source map, fit settings and errors, and every light:\n"
        "coefficient L_j (RGB), direction (elevation, azimuth in degrees), bandwidth lambda_j and energy share.\n"
        "With --map, also check that the map is the one the lights were fitted to (checksum; exit 1 if not).");
    inspect->add_option("lights", io->file, "Lights file (JSON from `coif env fit`)")->required()->check(CLI::ExistingFile);
    inspect->add_option("--map", io->map, "Map to compare with the recorded checksum")->check(CLI::ExistingFile);
    coif::cli::add_json_flag(inspect, io->json);
    coif::cli::examples(inspect, "  coif env inspect courtyard.json\n"
                                 "  coif env inspect courtyard.json --map ../shared/data/blender_studiolight_courtyard.exr --json");
    inspect->callback([io] { inspect_command(io->file, io->map, io->json); });

    struct DownsampleOptions {
        std::string map, output;
        int width = 256;
    };
    auto dso = std::make_shared<DownsampleOptions>();
    CLI::App* downsample = env->add_subcommand(
        "downsample",
        "Write a smaller copy of an equirectangular map: box-filtered over solid angle, so the integral of L over\n"
        "the sphere is unchanged; the same validation as `env fit` (tiny DWAB negatives clamped to 0).\n"
        "Output .hdr (RGBE), .exr (half float) or .png (tone-mapped preview), written atomically.");
    downsample->add_option("map", dso->map, "Equirectangular map (.hdr, .exr)")->required()->check(CLI::ExistingFile);
    downsample->add_option("--width", dso->width, "Width of the copy in pixels (even; height = width / 2)");
    downsample->add_option("-o,--output", dso->output, "File to write")->required();
    coif::cli::examples(downsample, "  coif env downsample ../shared/data/blender_studiolight_courtyard.exr --width 256 "
                                    "-o tools/assets/default_env.hdr");
    downsample->callback([dso] {
        coif::cli::lock_output(dso->output);
        coif::EnvMapLoadInfo info;
        const coif::EnvMap map = coif::load_envmap(dso->map, &info);
        for (const std::string& w : info.warnings) std::fprintf(stderr, "coif: warning: %s\n", w.c_str());
        const coif::EnvMap small = coif::downsample_envmap(map, dso->width);
        coif::WriteOptions wo;
        wo.exposure = coif::envmap_preview_exposure(small);
        wo.description = "coif env downsample of " + fs::path(dso->map).filename().string() + " (" +
                         std::to_string(map.width) + "x" + std::to_string(map.height) + ")";
        coif::write_image(dso->output, coif::envmap_to_image(small), wo);
        std::fprintf(stderr, "wrote %s (%dx%d)\n", dso->output.c_str(), small.width, small.height);
    });

    auto bo = std::make_shared<BenchOptions>();
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    CLI::App* benv = bench->add_subcommand(
        "env",
        "Fit SRBF lights to every map given for each N (and each fit-grid width) and print a table of the relative\n"
        "L2 error (full map and fit grid), the energy error, iterations and fitting time (one core).");
    benv->add_option("maps", bo->maps, "Equirectangular maps (.hdr, .exr)")->required()->check(CLI::ExistingFile);
    benv->add_option("-n,--lights", bo->lights, "Light counts N to fit")->delimiter(',');
    benv->add_option("--fit-width", bo->fit_widths, "Fit-grid widths to try (the downsampling study)")->delimiter(',');
    benv->add_option("--seed", bo->settings.seed, "Seed of the k-means++ initialisation");
    benv->add_option("--max-iterations", bo->settings.max_iterations, "Levenberg-Marquardt iteration limit");
    coif::cli::add_json_flag(benv, bo->json);
    coif::cli::examples(benv, "  coif bench env ../shared/data/*.exr ../shared/data/*.hdr\n"
                              "  coif bench env ../shared/data/blender_studiolight_city.exr -n 40 --fit-width 32,64,128 --json");
    benv->callback([bo] { bench_command(*bo); });
}

COIF_REGISTER_COMMAND(30, add_env);

}  // namespace
