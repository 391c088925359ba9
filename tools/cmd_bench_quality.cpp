// coif bench quality — image quality of `coif render` against `coif reference` for the default scene and
// every strand model in the shared data folder (as lit strand lines and as a fitted SATF style), plus
// lighting-only cases (sparse hair and a single strand, single scattering), with both times and their
// ratio, and the reference's own noise floor (two seeds). Both renderers always see the same SRBF lights
// (or the map and its fit) and the same hair parameters.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "models/core/atomic_file.h"
#include "models/core/error.h"
#include "models/core/image.h"
#include "models/strands.h"
#include "offline/envmap.h"
#include "models/core/image_metrics.h"
#include "offline/srbf_fit.h"
#include "offline/srbf_lights.h"
#include "online/shells/shell_settings.h"
#include "tools/assets.h"
#include "tools/cli.h"
#include "tools/compare_report.h"
#include "tools/reference_options.h"
#include "tools/scene_options.h"
#include "tools/subprocess.h"

namespace {

namespace fs = std::filesystem;

// Every n-th strand of the default model makes the lighting-only scene: sparse enough that fibres barely
// shadow each other, so that single scattering is nearly all there is and the renderer's lighting is
// measured alone.
constexpr int kSparseStride = 20;
// Clusters of the styles fitted to the models for their SATF rows (`coif style import --clusters`); the
// embedded default style has 64 too.
constexpr int kDefaultFitClusters = 64;
// Samples per pixel of the lighting-only rows' references: single scattering of a few hundred fibres costs
// little, and at the rows' default of 16–32 spp the reference's own noise (sub-pixel fibres hit or missed)
// is above the lighting error (docs/quality.md), so these rows get more.
constexpr int kDefaultLightingSpp = 256;

struct QualityOptions {
    coif::cli::ReferenceCliOptions reference;
    int width = 360, height = 240;
    double azimuth_deg = 20, elevation_deg = 10, fov_deg = 40;
    std::string data = "../shared/data";
    std::string keep;
    std::string db;
    int clusters = kDefaultFitClusters;
    int lighting_spp = kDefaultLightingSpp;
    bool fit_models = true;
    bool convergence = true;
    bool json = false;
};

using coif::cli::RunTimes;
using coif::cli::run_self;
using coif::cli::shell_quote;

// Which renderer a row measures (docs/quality.md says what each attributes).
enum class Renderer {
    shells,            // the SATF shell renderer (coif render --style)
    lines,             // the lit strand lines, lighting per strand point (coif render --strands)
    lines_per_fragment // the lit strand lines, lighting per fragment (--per-fragment)
};
const char* renderer_name(Renderer r) {
    return r == Renderer::shells ? "SATF shells" : r == Renderer::lines ? "lit lines" : "lit lines, per fragment";
}

struct Scene {
    std::string name;
    std::string strands_arg;   // the reference's strands; "" = the embedded default style's sampled strands
    Renderer renderer = Renderer::shells;
    std::string fit_model;     // shells: fit a style to this strand file first ("" = the embedded default style)
    bool lighting_only = false;  // reference depth 1, render without multiple scattering, SRBF lights only
    bool reference_shadows = true;  // false: coif reference --no-shadows (the lighting alone)
};

struct ReferenceRun {
    fs::path image;
    RunTimes times;
    coif::CompareResult convergence;
    coif::CompareResult radiance_convergence;  // straight-alpha rows: the radiance where both seeds hit
};

// A straight-alpha image (coif render/reference --alpha) over the background: what its pixels show,
// exactly what the renderers composite without --alpha (A·L + (1 − A)·background).
coif::Image over_background(const coif::Image& straight, const glm::vec3& background) {
    coif::Image out(straight.width, straight.height, 3);
    for (int y = 0; y < straight.height; ++y)
        for (int x = 0; x < straight.width; ++x) {
            const float* p = straight.at(x, y);
            const float a = straight.channels == 4 ? p[3] : 1.0f;
            for (int c = 0; c < 3; ++c) out.at(x, y)[c] = a * p[c] + (1.0f - a) * background[c];
        }
    return out;
}

// Two straight-alpha images reduced to the pixels both cover (A > kMaskAlphaThreshold in both; elsewhere
// RGBA = 0): their RGB is the hair's radiance alone, so their metrics measure lighting, not coverage.
std::pair<coif::Image, coif::Image> where_both_cover(const coif::Image& a, const coif::Image& b) {
    std::pair<coif::Image, coif::Image> out{a, b};
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            if (!(a.at(x, y)[3] > coif::kMaskAlphaThreshold && b.at(x, y)[3] > coif::kMaskAlphaThreshold))
                for (int c = 0; c < 4; ++c) out.first.at(x, y)[c] = out.second.at(x, y)[c] = 0.0f;
    return out;
}

struct CoverageStats {
    double ratio = 0;     // Σ A of the render / Σ A of the reference
    double mean_abs = 0;  // mean |A_render − A_reference| over the pixels either covers
};
CoverageStats coverage_stats(const coif::Image& ref, const coif::Image& ren) {
    double sum_ref = 0, sum_ren = 0, abs_sum = 0;
    std::size_t n = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            const float a = ref.at(x, y)[3], b = ren.at(x, y)[3];
            sum_ref += a;
            sum_ren += b;
            if (a > coif::kMaskAlphaThreshold || b > coif::kMaskAlphaThreshold) {
                abs_sum += std::abs(double(a) - b);
                ++n;
            }
        }
    return {sum_ref > 0 ? sum_ren / sum_ref : 0.0, n ? abs_sum / double(n) : 0.0};
}

using coif::cli::compare_json;
using coif::cli::metric_json;

// One line of the appearance metrics under a row of the table.
void print_appearance(const coif::AppearanceMetrics& m, const char* what) {
    std::printf("  %-38s radiance ratio %s | IoU %s | blurred PSNR %s dB, SSIM %.3f | detail ratio %s\n", what,
                coif::cli::format_rgb(m.radiance_ratio, 3).c_str(), coif::format_metric(m.mask_iou, 3).c_str(),
                coif::format_metric(m.blurred_psnr_db, 2).c_str(), m.blurred_ssim, coif::format_metric(m.detail_ratio, 3).c_str());
}
struct RenderRun {
    fs::path image;
    RunTimes times;
    double fit_seconds = 0;
};


// The lights both renderers see, as files: `render` for coif render --env, `reference` for coif reference's
// lighting options; the lighting-only rows use `single_render`/`single_reference`, always SRBF lights.
struct BenchLighting {
    std::string render, reference, single_render, single_reference, words;
};

BenchLighting bench_lighting(const coif::cli::ReferenceCliOptions& ref, const fs::path& dir) {
    BenchLighting b;
    if (!ref.lights.empty()) {
        b.render = b.single_render = ref.lights;
        b.reference = b.single_reference = " --lights " + shell_quote(ref.lights);
        b.words = "SRBF lights " + ref.lights;
    } else if (!ref.env.empty()) {
        // coif render would fit the map itself; fitting once here gives every row the same lights and lets the
        // lighting-only rows light the reference with them too (no env-fit error there).
        std::fprintf(stderr, "fitting SRBF lights to %s once for every coif render\n", ref.env.c_str());
        coif::SrbfLightSet set;
        set.lights = coif::fit_srbf_lights(coif::load_envmap(ref.env), coif::SrbfFitSettings{}).lights;
        const fs::path path = dir / "fitted_lights.json";
        coif::write_srbf_lights(path, set);
        b.render = b.single_render = path.string();
        b.reference = " --env " + shell_quote(ref.env);
        b.single_reference = " --lights " + shell_quote(path.string());
        b.words = "map " + ref.env + " (reference; coif render and the lighting-only rows: its 40 fitted SRBF lights)";
    } else if (ref.env_constant.size() == 3) {
        // A constant environment as one SRBF light of the broadest bandwidth: G_j varies by < 4e-4 over the sphere
        // (exp(−2·2/λ²) at λ = 100), so the reference keeps the exact constant for every row.
        coif::SrbfLightSet set;
        set.lights.push_back({glm::vec3(ref.env_constant[0], ref.env_constant[1], ref.env_constant[2]), glm::vec3(0, 1, 0),
                              coif::shading::kMaxLambda});
        const fs::path path = dir / "constant_light.json";
        coif::write_srbf_lights(path, set);
        b.render = b.single_render = path.string();
        b.reference = b.single_reference = ref.lighting_args();
        b.words = "constant environment (coif render: one SRBF light of λ = 100)";
    } else {
        const std::vector<std::byte> bytes = coif::asset_bytes("default_lights.json");
        const fs::path path = dir / "default_lights.json";
        coif::write_file_atomic(path, bytes);
        b.render = b.single_render = path.string();
        b.reference = b.single_reference = " --lights " + shell_quote(path.string());
        b.words = "the embedded default lights (40 SRBF lights, courtyard)";
    }
    return b;
}

void add_bench_quality(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<QualityOptions>();
    o->reference.settings.samples_per_pixel = 16;
    CLI::App* cmd = bench->add_subcommand(
        "quality",
        "Image quality of `coif render` against the brute-force `coif reference` at the same camera, lights and hair\n"
        "parameters. Rows: the embedded default style (SATF shells); every .hair/.data model in --data twice, as lit\n"
        "strand lines (the renderer's lighting without SATF or shadows) and as a style fitted to it (`coif style\n"
        "import --clusters N`, SATF shells, framed on the model); and two lighting-only cases, every 20th strand of\n"
        "the default model and a single strand, lit strand lines per fragment without multiple scattering against\n"
        "the reference at depth 1 (single scattering): fibres barely occlude each other, so the error is the lighting\n"
        "alone. Lights: --lights, else --env (coif render gets its fitted SRBF lights; the lighting-only rows light\n"
        "the reference with them too), else --env-constant, else the embedded default lights. Both commands run as\n"
        "subprocesses of this coif. Prints PSNR, SSIM and mean FLIP over hair pixels (see `coif compare --help`),\n"
        "both wall times and their ratio, and the reference's noise floor: the same metrics between two reference\n"
        "renders with different seeds. docs/quality.md explains what each row attributes.");
    o->reference.add_to(cmd);
    cmd->add_option("--width", o->width, "Image width in pixels")->check(CLI::Range(8, 4096));
    cmd->add_option("--height", o->height, "Image height in pixels")->check(CLI::Range(8, 4096));
    cmd->add_option("--azimuth", o->azimuth_deg, "Camera azimuth about +y in degrees");
    cmd->add_option("--elevation", o->elevation_deg, "Camera elevation in degrees")->check(CLI::Range(-89.0, 89.0));
    cmd->add_option("--fov", o->fov_deg, "Vertical field of view in degrees")->check(CLI::Range(1.0, 150.0));
    cmd->add_option("--data", o->data, "Folder whose .hair and .data models are benchmarked");
    cmd->add_option("--clusters", o->clusters, "Clusters of the styles fitted to the models (SATF rows)")
        ->check(CLI::Range(1, 100000))->capture_default_str();
    cmd->add_flag("!--no-fit", o->fit_models, "Skip the SATF rows of the models (no style fitting)");
    cmd->add_option("--lighting-spp", o->lighting_spp, "Samples per pixel of the lighting-only rows' references")
        ->check(CLI::Range(1, coif::kMaxReferenceSpp))->capture_default_str();
    cmd->add_option("--db", o->db, "HRIR database for the SATF rows (default: coif render's cached default database)");
    cmd->add_option("--keep", o->keep, "Keep the images here (default: a temporary folder, removed)");
    cmd->add_flag("!--no-convergence", o->convergence, "Skip the second reference render (the noise floor)");
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif bench quality\n"
                             "  coif bench quality --spp 64 --env ../shared/data/blender_studiolight_city.exr --keep quality/\n"
                             "  coif bench quality --no-fit --json > quality.json");
    cmd->callback([o] {
        // Validate the shared options up front (clear errors before minutes of rendering).
        const coif::gl::ShellSettings params = o->reference.hair.settings();
        (void)o->reference.environment();
        const coif::ReferenceSettings settings = o->reference.reference_settings();

        const coif::cli::WorkFolder work(o->keep, "coif-bench-quality-");
        const fs::path& dir = work.path();
        const bool temporary = work.temporary();

        const BenchLighting lighting = bench_lighting(o->reference, dir);
        const fs::path params_full = dir / "params.json", params_single = dir / "params_single_scattering.json";
        // One parameters file for both commands (the reference reads its fibre keys); the lighting-only rows
        // render without multiple scattering.
        coif::gl::ShellSettings single_scattering = params;
        single_scattering.hair.multiple = false;
        coif::gl::write_shell_settings(params_full, params);
        coif::gl::write_shell_settings(params_single, single_scattering);

        std::vector<Scene> scenes{{"default (SATF shells)", "", Renderer::shells, "", false}};
        if (fs::is_directory(o->data)) {
            std::vector<fs::path> models;
            for (const auto& e : fs::directory_iterator(o->data))
                if (e.path().extension() == ".hair" || e.path().extension() == ".data") models.push_back(e.path());
            std::sort(models.begin(), models.end());
            for (const auto& m : models) {
                const std::string name = m.filename().string();
                scenes.push_back({name + " (lit lines)", m.string(), Renderer::lines, "", false});
                if (o->fit_models)
                    scenes.push_back({name + " (SATF, " + std::to_string(o->clusters) + " clusters)", m.string(), Renderer::shells,
                                      m.string(), false});
            }
        } else {
            std::fprintf(stderr, "note: %s is not a folder; only the default scene and the lighting-only cases\n", o->data.c_str());
        }
        {
            coif::cli::SceneOptions def;
            const coif::Strands all = def.load_strands();
            coif::Strands sparse, single;
            const auto strand = [&](size_t s) {
                return std::vector<glm::vec3>(all.points.begin() + all.offsets[s], all.points.begin() + all.offsets[s + 1]);
            };
            for (size_t s = 0; s < all.strand_count(); s += kSparseStride) sparse.add_strand(strand(s));
            single.add_strand(strand(all.strand_count() / 2));
            const fs::path sparse_path = dir / "lighting_only_sparse.hair", single_path = dir / "lighting_only_single.hair";
            coif::write_hair(sparse_path, sparse);
            coif::write_hair(single_path, single);
            scenes.push_back({"lighting only: default/20, no shadows", sparse_path.string(), Renderer::lines_per_fragment, "", true, false});
            scenes.push_back({"lighting + shadows: default/20", sparse_path.string(), Renderer::lines_per_fragment, "", true, true});
            scenes.push_back({"lighting only: single strand", single_path.string(), Renderer::lines_per_fragment, "", true, false});
        }

        char camera_args[256];
        std::snprintf(camera_args, sizeof camera_args, " --width %d --height %d --azimuth %.9g --elevation %.9g --fov %.9g", o->width,
                      o->height, o->azimuth_deg, o->elevation_deg, o->fov_deg);
        const std::string params_arg = " --params " + shell_quote(params_full.string());
        std::ostringstream radius_arg;
        if (settings.fiber_radius > 0) radius_arg << " --radius " << settings.fiber_radius;
        std::ostringstream both_args;  // what both renderers are given alike: background, light rotation
        if (!o->reference.background.empty())
            both_args << " --background " << settings.background.x << ' ' << settings.background.y << ' ' << settings.background.z;
        if (o->reference.rotate_lights_deg != 0) both_args << " --rotate-lights " << o->reference.rotate_lights_deg;  // both renderers

        std::map<std::string, ReferenceRun> references;  // by arguments: rows of one model share its reference
        std::map<std::string, RenderRun> renders;        // by arguments: the sparse rows share their render
        nlohmann::json rows = nlohmann::json::array();
        if (!o->json)
            std::printf("%-40s %7s %8s %8s %7s | %8s %8s %7s %7s | %8s %7s\n", "scene (renderer)", "strands", "render s", "ref s",
                        "ratio", "PSNR lin", "PSNR tm", "SSIM tm", "FLIP tm", "conv PSNR", "conv FLIP");
        for (const Scene& sc : scenes) {
            const std::string stem = std::to_string(rows.size());
            const std::string strands_arg = sc.strands_arg.empty() ? std::string() : " --strands " + shell_quote(sc.strands_arg);

            // The reference (once per distinct set of arguments).
            std::ostringstream ref_args;
            ref_args << strands_arg << camera_args << (sc.lighting_only ? lighting.single_reference : lighting.reference) << params_arg
                     << " --spp " << (sc.lighting_only ? o->lighting_spp : settings.samples_per_pixel)
                     << " --max-depth " << (sc.lighting_only ? 1 : settings.max_depth)
                     << " --threads " << settings.threads << radius_arg.str() << (sc.reference_shadows ? "" : " --no-shadows")
                     << (sc.lighting_only ? " --alpha" : "");
            ref_args << both_args.str();
            auto ref_it = references.find(ref_args.str());
            if (ref_it == references.end()) {
                ReferenceRun run;
                run.image = dir / (stem + "_reference.exr");
                run.times = run_self("reference" + ref_args.str() + " --seed " + std::to_string(settings.seed) + " -o " +
                                         shell_quote(run.image.string()),
                                     dir / (stem + "_reference.log"));
                if (o->convergence) {
                    const fs::path second = dir / (stem + "_reference_seed2.exr");
                    run_self("reference" + ref_args.str() + " --seed " + std::to_string(settings.seed + 1) + " -o " + shell_quote(second.string()),
                             dir / (stem + "_reference_seed2.log"));
                    const coif::Image a = coif::read_image(run.image), b = coif::read_image(second);
                    if (sc.lighting_only) {
                        run.convergence = coif::compare_images(over_background(a, settings.background), over_background(b, settings.background),
                                                               {}, run.image.string(), second.string());
                        const auto [ra, rb] = where_both_cover(a, b);
                        run.radiance_convergence = coif::compare_images(ra, rb, {coif::MaskMode::alpha}, run.image.string(), second.string());
                    } else {
                        run.convergence = coif::compare_images(a, b, {}, run.image.string(), second.string());
                    }
                }
                ref_it = references.emplace(ref_args.str(), run).first;
            }
            const ReferenceRun& ref_run = ref_it->second;

            // The render (once per distinct set of arguments).
            std::string render_args = std::string(camera_args) + both_args.str() + " --env " + shell_quote(sc.lighting_only ? lighting.single_render : lighting.render) +
                                      " --params " + shell_quote((sc.lighting_only ? params_single : params_full).string());
            if (sc.renderer == Renderer::shells) {
                if (!sc.fit_model.empty()) render_args += " --frame-strands " + shell_quote(sc.fit_model);
                if (!o->db.empty()) render_args += " --db " + shell_quote(o->db);
            } else {
                render_args += strands_arg + radius_arg.str();
                if (sc.renderer == Renderer::lines_per_fragment) render_args += " --per-fragment";
                if (sc.lighting_only) render_args += " --alpha";
            }
            const std::string render_key = render_args + (sc.fit_model.empty() ? "" : " fitted to " + sc.fit_model);
            auto render_it = renders.find(render_key);
            if (render_it == renders.end()) {
                RenderRun run;
                std::string args = render_args;
                if (!sc.fit_model.empty()) {
                    const fs::path style = dir / (stem + "_style.json");
                    run.fit_seconds = run_self("style import " + shell_quote(sc.fit_model) + " --clusters " + std::to_string(o->clusters) +
                                                   " -o " + shell_quote(style.string()),
                                               dir / (stem + "_style.log"))
                                          .wall;
                    args += " --style " + shell_quote(style.string());
                }
                run.image = dir / (stem + "_render.exr");
                run.times = run_self("render" + args + " -o " + shell_quote(run.image.string()), dir / (stem + "_render.log"));
                render_it = renders.emplace(render_key, run).first;
            }
            const RenderRun& render_run = render_it->second;
            const fs::path& render_out = render_run.image;
            const RunTimes& tr = render_run.times;
            const double fit_seconds = render_run.fit_seconds;

            const coif::Image ref = coif::read_image(ref_run.image), ren = coif::read_image(render_out);
            // Lighting rows are straight alpha: composited for the row's metrics, and also compared where both hit.
            const coif::CompareResult q =
                sc.lighting_only ? coif::compare_images(over_background(ref, settings.background), over_background(ren, settings.background), {},
                                                        ref_run.image.string(), render_out.string())
                                 : coif::compare_images(ref, ren, {}, ref_run.image.string(), render_out.string());
            coif::CompareResult radiance;
            CoverageStats coverage;
            if (sc.lighting_only) {
                const auto [ra, rb] = where_both_cover(ref, ren);
                radiance = coif::compare_images(ra, rb, {coif::MaskMode::alpha}, ref_run.image.string(), render_out.string());
                coverage = coverage_stats(ref, ren);
            }
            const coif::CompareResult& conv = ref_run.convergence;
            const size_t n_strands = sc.strands_arg.empty() ? coif::cli::SceneOptions{}.load_strands().strand_count()
                                                            : coif::read_strands(sc.strands_arg).strand_count();
            const RunTimes& tf = ref_run.times;
            nlohmann::json row = {{"scene", sc.name},
                                  {"renderer", renderer_name(sc.renderer)},
                                  {"reference_max_depth", sc.lighting_only ? 1 : settings.max_depth},
                                  {"reference_spp", sc.lighting_only ? o->lighting_spp : settings.samples_per_pixel},
                                  {"reference_shadows", sc.reference_shadows},
                                  {"render_multiple_scattering", !sc.lighting_only},
                                  {"strands", n_strands},
                                  {"render_seconds", tr.wall},
                                  {"render_cpu_seconds", tr.cpu},
                                  {"reference_seconds", tf.wall},
                                  {"reference_cpu_seconds", tf.cpu},
                                  {"time_ratio", tf.wall / tr.wall},
                                  {"mask_pixels", q.mask.count}};
            row.update(compare_json(q));  // linear, tone_mapped, appearance, ...
            if (fit_seconds > 0) row["style_fit_seconds"] = fit_seconds;
            if (sc.lighting_only) {
                row["radiance_where_both_hit"] = compare_json(radiance);
                if (o->convergence) row["radiance_where_both_hit"]["reference_convergence"] = compare_json(ref_run.radiance_convergence);
                row["coverage"] = {{"render_over_reference", coverage.ratio}, {"mean_abs_difference", coverage.mean_abs}};
            }
            if (o->convergence)
                row["reference_convergence"] = {{"psnr_db_tone_mapped", metric_json(conv.tone_mapped.psnr_db)},
                                                {"psnr_db_linear", metric_json(conv.linear.psnr_db)},
                                                {"ssim_tone_mapped", conv.tone_mapped.ssim},
                                                {"flip_mean_tone_mapped", conv.tone_mapped.flip}};
            rows.push_back(row);
            if (!o->json) {
                std::printf("%-40s %7zu %8.2f %8.2f %7.1f | %8s %8s %7.4f %7.4f | %8s %7s\n", sc.name.c_str(), n_strands, tr.wall, tf.wall,
                            tf.wall / tr.wall, coif::format_metric(q.linear.psnr_db, 2).c_str(),
                            coif::format_metric(q.tone_mapped.psnr_db, 2).c_str(), q.tone_mapped.ssim, q.tone_mapped.flip,
                            o->convergence ? coif::format_metric(conv.tone_mapped.psnr_db, 2).c_str() : "-",
                            o->convergence ? coif::format_metric(conv.tone_mapped.flip, 4).c_str() : "-");
                print_appearance(q.appearance, "appearance");
                if (o->convergence) print_appearance(conv.appearance, "reference seed vs seed");
                if (sc.lighting_only) {
                    const coif::CompareResult& rc = ref_run.radiance_convergence;
                    std::printf("  radiance where both hit (%6zu px)    coverage ratio %5.3f, |dA| %5.3f | %8s %8s %7.4f %7.4f | %8s %7s\n",
                                radiance.mask.count, coverage.ratio, coverage.mean_abs, coif::format_metric(radiance.linear.psnr_db, 2).c_str(),
                                coif::format_metric(radiance.tone_mapped.psnr_db, 2).c_str(), radiance.tone_mapped.ssim, radiance.tone_mapped.flip,
                                o->convergence ? coif::format_metric(rc.tone_mapped.psnr_db, 2).c_str() : "-",
                                o->convergence ? coif::format_metric(rc.tone_mapped.flip, 4).c_str() : "-");
                }
                std::fflush(stdout);
            }
        }
        const nlohmann::json doc = {{"width", o->width},
                                    {"height", o->height},
                                    {"samples_per_pixel", settings.samples_per_pixel},
                                    {"max_depth", settings.max_depth},
                                    {"lighting_samples_per_pixel", o->lighting_spp},
                                    {"seed", settings.seed},
                                    {"lighting", lighting.words},
                                    {"goal", "mean FLIP <= 0.10 and PSNR >= 30 dB on hair pixels (tone-mapped)"},
                                    {"scenes", rows}};
        if (o->json) {
            coif::cli::print_json(doc);
            return;
        }
        std::printf("\n%dx%d, reference %d spp, max depth %d (lighting rows: %d spp, depth 1), seed %llu; lit by %s.\n"
                    "Metrics over hair pixels, tm = tone-mapped (the PNG tone map), lin = linear; ratio = reference time /\n"
                    "render time (wall, process start included; SATF rows of models: style fitting not included);\n"
                    "conv = reference seed %llu vs seed %llu (the noise floor). Goal: mean FLIP <= 0.10 and PSNR >= 30 dB.\n",
                    o->width, o->height, settings.samples_per_pixel, settings.max_depth, o->lighting_spp,
                    static_cast<unsigned long long>(settings.seed), lighting.words.c_str(), static_cast<unsigned long long>(settings.seed),
                    static_cast<unsigned long long>(settings.seed + 1));
        if (!temporary) std::printf("images and logs in %s\n", dir.string().c_str());
    });
}

COIF_REGISTER_COMMAND(91, add_bench_quality);

}  // namespace
