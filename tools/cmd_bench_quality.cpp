// coif bench quality — image quality of `coif render` against `coif reference` for the default scene and
// every strand model in the shared data folder, plus a lighting-only case, with both times and their ratio,
// and the reference's own noise floor (two seeds).
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "models/core/error.h"
#include "models/core/image.h"
#include "models/strands.h"
#include "offline/image_metrics.h"
#include "tools/cli.h"
#include "tools/reference_options.h"
#include "tools/scene_options.h"

namespace {

namespace fs = std::filesystem;

// Every n-th strand of the default model makes the lighting-only scene: sparse enough that fibres barely
// shadow each other, so that single scattering is nearly all there is and the renderer's lighting is
// measured alone.
constexpr int kSparseStride = 20;

struct QualityOptions {
    coif::cli::ReferenceCliOptions reference;
    int width = 360, height = 240;
    double azimuth_deg = 20, elevation_deg = 10, fov_deg = 40;
    std::string data = "../shared/data";
    std::string keep;
    bool convergence = true;
    bool json = false;
};

std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string self_exe() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw coif::Error::parameter("coif bench quality", "cannot find the coif executable (/proc/self/exe)");
    return p.string();
}

struct RunTimes {
    double wall = 0, cpu = 0;
};

double children_cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_CHILDREN, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string read_text(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs `coif <args>`; throws coif::Error with the tail of its stderr on failure.
RunTimes run_coif(const std::string& args, const fs::path& log) {
    const double cpu0 = children_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    const std::string cmd = quote(self_exe()) + " " + args + " >" + quote(log.string()) + " 2>&1";
    const int status = std::system(cmd.c_str());
    RunTimes t;
    t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    t.cpu = children_cpu_seconds() - cpu0;
    if (status != 0) {
        std::string text = read_text(log);
        if (text.size() > 600) text = "..." + text.substr(text.size() - 600);
        throw coif::Error(log, "command `coif " + args + "`", "failed:\n" + text);
    }
    return t;
}

struct Scene {
    std::string name;
    std::string strands_arg;   // "" = embedded default
    bool lighting_only = false;
};

nlohmann::json metric_value(double v) {
    if (std::isinf(v)) return "inf";
    return v;
}

void add_bench_quality(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<QualityOptions>();
    o->reference.settings.samples_per_pixel = 16;
    CLI::App* cmd = bench->add_subcommand(
        "quality",
        "Image quality of `coif render` against the brute-force `coif reference` at the same camera and parameters:\n"
        "for the embedded default scene, every .hair/.data model in --data, and a lighting-only case (every 20th\n"
        "strand of the default model, single scattering: fibres barely occlude each other, so the error is the\n"
        "renderer's lighting alone). Both commands run as subprocesses of this coif; lighting and hair options are\n"
        "passed to `coif render` only where its --help lists them (the note says which were not). Prints PSNR,\n"
        "SSIM and mean FLIP over hair pixels (see `coif compare --help`), both wall times and their ratio, and\n"
        "the reference's noise floor: the same metrics between two reference renders with different seeds.");
    o->reference.add_to(cmd);
    cmd->add_option("--width", o->width, "Image width in pixels")->check(CLI::Range(8, 4096));
    cmd->add_option("--height", o->height, "Image height in pixels")->check(CLI::Range(8, 4096));
    cmd->add_option("--azimuth", o->azimuth_deg, "Camera azimuth about +y in degrees");
    cmd->add_option("--elevation", o->elevation_deg, "Camera elevation in degrees")->check(CLI::Range(-89.0, 89.0));
    cmd->add_option("--fov", o->fov_deg, "Vertical field of view in degrees")->check(CLI::Range(1.0, 150.0));
    cmd->add_option("--data", o->data, "Folder whose .hair and .data models are benchmarked");
    cmd->add_option("--keep", o->keep, "Keep the images here (default: a temporary folder, removed)");
    cmd->add_flag("!--no-convergence", o->convergence, "Skip the second reference render (the noise floor)");
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif bench quality\n"
                             "  coif bench quality --spp 64 --env ../shared/data/blender_studiolight_city.exr --keep quality/\n"
                             "  coif bench quality --json > quality.json");
    cmd->callback([o] {
        // Validate the shared options up front (clear errors before minutes of rendering).
        (void)o->reference.hair_params();
        (void)o->reference.environment();
        const coif::ReferenceSettings settings = o->reference.reference_settings();

        fs::path dir;
        const bool temporary = o->keep.empty();
        if (temporary) {
            dir = fs::temp_directory_path() / ("coif-bench-quality-" + std::to_string(::getpid()));
            fs::create_directories(dir);
        } else {
            dir = o->keep;
            std::error_code ec;
            fs::create_directories(dir, ec);
            if (!fs::is_directory(dir)) throw coif::Error(dir, "option --keep", "cannot create this folder");
        }
        struct Cleanup {
            fs::path dir;
            bool active;
            ~Cleanup() {
                std::error_code ec;
                if (active) fs::remove_all(dir, ec);
            }
        } cleanup{dir, temporary};

        std::vector<Scene> scenes{{"default", "", false}};
        if (fs::is_directory(o->data)) {
            std::vector<fs::path> models;
            for (const auto& e : fs::directory_iterator(o->data))
                if (e.path().extension() == ".hair" || e.path().extension() == ".data") models.push_back(e.path());
            std::sort(models.begin(), models.end());
            for (const auto& m : models) scenes.push_back({m.filename().string(), m.string(), false});
        } else {
            std::fprintf(stderr, "note: %s is not a folder; only the default scene and the lighting-only case\n", o->data.c_str());
        }
        {
            coif::cli::SceneOptions def;
            coif::Strands all = def.load_strands();
            coif::Strands sparse;
            for (size_t s = 0; s < all.strand_count(); s += kSparseStride)
                sparse.add_strand(std::vector<glm::vec3>(all.points.begin() + all.offsets[s], all.points.begin() + all.offsets[s + 1]));
            const fs::path path = dir / "lighting_only_sparse.hair";
            coif::write_hair(path, sparse);
            scenes.push_back({"lighting only (default/20, depth 1)", path.string(), true});
        }

        char camera_args[256];
        std::snprintf(camera_args, sizeof camera_args, " --width %d --height %d --azimuth %.9g --elevation %.9g --fov %.9g", o->width,
                      o->height, o->azimuth_deg, o->elevation_deg, o->fov_deg);
        // Which of our options `coif render` understands.
        const fs::path help_log = dir / "render_help.txt";
        run_coif("render --help", help_log);
        const std::string render_help = read_text(help_log);
        std::vector<std::string> render_ignores;
        const auto render_accepts = [&](const std::string& flag) { return render_help.find(flag + " ") != std::string::npos ||
                                                                          render_help.find(flag + "\n") != std::string::npos ||
                                                                          render_help.find(flag + ",") != std::string::npos; };
        const std::string lighting = o->reference.lighting_args(), hair = o->reference.hair_args();
        std::string render_extra;
        const auto pass = [&](const std::string& args, const char* what) {
            if (args.empty()) return;
            const std::string flag = args.substr(1, args.find(' ', 1) - 1);
            if (render_accepts(flag)) render_extra += args;
            else render_ignores.push_back(std::string(what) + " (" + flag + ")");
        };
        // `coif render --env` takes either a map or a lights file; the reference names the latter --lights.
        const bool lights_via_env = lighting.rfind(" --lights ", 0) == 0 && !render_accepts("--lights") && render_accepts("--env");
        pass(lights_via_env ? " --env" + lighting.substr(std::string(" --lights").size()) : lighting, "lighting");
        pass(hair, "hair parameters");
        if (lighting.empty() && !render_accepts("--env") && !render_accepts("--lights"))
            render_ignores.push_back("lighting (coif render has no --env/--lights: its own light)");

        nlohmann::json rows = nlohmann::json::array();
        if (!o->json)
            std::printf("%-36s %7s %8s %8s %7s | %8s %8s %7s %7s | %8s %7s\n", "scene", "strands", "render s", "ref s", "ratio",
                        "PSNR lin", "PSNR tm", "SSIM tm", "FLIP tm", "conv PSNR", "conv FLIP");
        for (const Scene& sc : scenes) {
            const std::string stem = std::to_string(rows.size());
            const std::string strands_arg = sc.strands_arg.empty() ? std::string() : " --strands " + quote(sc.strands_arg);
            const fs::path render_out = dir / (stem + "_render.exr"), ref_out = dir / (stem + "_reference.exr"),
                           ref2_out = dir / (stem + "_reference_seed2.exr");
            std::ostringstream ref_args;
            ref_args << strands_arg << camera_args << lighting << hair << " --spp " << settings.samples_per_pixel << " --max-depth "
                     << (sc.lighting_only ? 1 : settings.max_depth) << " --threads " << settings.threads;
            if (settings.fiber_radius > 0) ref_args << " --radius " << settings.fiber_radius;
            if (!o->reference.background.empty())
                ref_args << " --background " << settings.background.x << ' ' << settings.background.y << ' ' << settings.background.z;
            const RunTimes tr = run_coif("render" + strands_arg + camera_args + render_extra + " -o " + quote(render_out.string()),
                                         dir / (stem + "_render.log"));
            const RunTimes tf = run_coif("reference" + ref_args.str() + " --seed " + std::to_string(settings.seed) + " -o " +
                                             quote(ref_out.string()),
                                         dir / (stem + "_reference.log"));
            const coif::Image ref = coif::read_image(ref_out), ren = coif::read_image(render_out);
            const coif::CompareResult q = coif::compare_images(ref, ren, {}, ref_out.string(), render_out.string());
            coif::CompareResult conv;
            if (o->convergence) {
                run_coif("reference" + ref_args.str() + " --seed " + std::to_string(settings.seed + 1) + " -o " + quote(ref2_out.string()),
                         dir / (stem + "_reference_seed2.log"));
                conv = coif::compare_images(ref, coif::read_image(ref2_out), {}, ref_out.string(), ref2_out.string());
            }
            const size_t n_strands = sc.strands_arg.empty() ? coif::cli::SceneOptions{}.load_strands().strand_count()
                                                            : coif::read_strands(sc.strands_arg).strand_count();
            nlohmann::json row = {{"scene", sc.name},
                                  {"strands", n_strands},
                                  {"render_seconds", tr.wall},
                                  {"render_cpu_seconds", tr.cpu},
                                  {"reference_seconds", tf.wall},
                                  {"reference_cpu_seconds", tf.cpu},
                                  {"time_ratio", tf.wall / tr.wall},
                                  {"mask_pixels", q.mask.count},
                                  {"linear", {{"psnr_db", metric_value(q.linear.psnr_db)}, {"ssim", q.linear.ssim}, {"flip_mean", q.linear.flip}}},
                                  {"tone_mapped",
                                   {{"psnr_db", metric_value(q.tone_mapped.psnr_db)}, {"ssim", q.tone_mapped.ssim}, {"flip_mean", q.tone_mapped.flip}}}};
            if (o->convergence)
                row["reference_convergence"] = {{"psnr_db_tone_mapped", metric_value(conv.tone_mapped.psnr_db)},
                                                {"psnr_db_linear", metric_value(conv.linear.psnr_db)},
                                                {"ssim_tone_mapped", conv.tone_mapped.ssim},
                                                {"flip_mean_tone_mapped", conv.tone_mapped.flip}};
            rows.push_back(row);
            if (!o->json) {
                std::printf("%-36s %7zu %8.2f %8.2f %7.1f | %8s %8s %7.4f %7.4f | %8s %7s\n", sc.name.c_str(), n_strands, tr.wall, tf.wall,
                            tf.wall / tr.wall, coif::format_metric(q.linear.psnr_db, 2).c_str(),
                            coif::format_metric(q.tone_mapped.psnr_db, 2).c_str(), q.tone_mapped.ssim, q.tone_mapped.flip,
                            o->convergence ? coif::format_metric(conv.tone_mapped.psnr_db, 2).c_str() : "-",
                            o->convergence ? coif::format_metric(conv.tone_mapped.flip, 4).c_str() : "-");
                std::fflush(stdout);
            }
        }
        std::string ignores;
        for (const auto& s : render_ignores) ignores += (ignores.empty() ? "" : "; ") + s;
        const nlohmann::json doc = {{"width", o->width},
                                    {"height", o->height},
                                    {"samples_per_pixel", settings.samples_per_pixel},
                                    {"max_depth", settings.max_depth},
                                    {"seed", settings.seed},
                                    {"environment", lighting.empty() ? std::string("constant 1 1 1") : lighting.substr(1)},
                                    {"render_ignores", ignores},
                                    {"goal", "mean FLIP <= 0.10 and PSNR >= 30 dB on hair pixels (tone-mapped)"},
                                    {"scenes", rows}};
        if (o->json) {
            coif::cli::print_json(doc);
            return;
        }
        std::printf("\n%dx%d, reference %d spp, max depth %d (lighting only: 1), seed %llu; metrics over hair pixels, tm = tone-mapped\n"
                    "(the PNG tone map), lin = linear; ratio = reference time / render time (wall, process start included);\n"
                    "conv = reference seed %llu vs seed %llu (the noise floor). Goal: mean FLIP <= 0.10 and PSNR >= 30 dB.\n",
                    o->width, o->height, settings.samples_per_pixel, settings.max_depth, static_cast<unsigned long long>(settings.seed),
                    static_cast<unsigned long long>(settings.seed), static_cast<unsigned long long>(settings.seed + 1));
        if (!ignores.empty()) std::printf("note: coif render ignores %s, so it is not lit or shaded like the reference.\n", ignores.c_str());
        if (!temporary) std::printf("images and logs in %s\n", dir.string().c_str());
    });
}

COIF_REGISTER_COMMAND(91, add_bench_quality);

}  // namespace
