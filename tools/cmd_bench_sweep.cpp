// coif bench sweep — issue 16's sweeps of lighting and views that no one tuned for: `coif render` against `coif
// reference` under one narrow SRBF light from 26 directions, under every map of a folder turned about +y, and from a
// ring of views, each case compared by the appearance metrics (docs/quality.md). The sweeps that docs/quality.md
// measures item 1 by, as one command.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <type_traits>
#include <variant>

#include "models/core/error.h"
#include "models/core/image.h"
#include "models/core/image_metrics.h"
#include "models/core/progress.h"
#include "offline/srbf_lights.h"
#include "shaders/hair_parameters.h"
#include "online/shells/shell_settings.h"
#include "tools/cli.h"
#include "tools/scene_options.h"
#include "tools/subprocess.h"

namespace {

namespace fs = std::filesystem;
using coif::cli::read_text;
using coif::cli::shell_quote;

// The band for each channel's radiance ratio, render / reference.
constexpr double kBandLow = 0.8, kBandHigh = 1.25;
// --where-lit's cells, in pixels: 4 × 4 at the sweeps' 96 × 64 (docs/quality.md, "Where the light reaches").
constexpr int kLitCell = 4;
// The narrow light of the single-light sweep: λ = 0.1, L = 300 (docs/quality.md, "The fibres' tangents about the axis").
constexpr float kNarrowLambda = 0.1f, kNarrowRadiance = 300.0f;
const char* const kSets[] = {"lights", "maps", "ring"};

// 16 hex digits of std::hash over `bytes`: the kept references' names, and the strands' part of their key.
std::string hash_hex(const std::string& bytes) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016zx", std::hash<std::string>{}(bytes));
    return hex;
}

struct SweepOptions {
    std::vector<std::string> sets{"lights"};
    std::string params, db, data = "../shared/data", references, keep;
    std::vector<std::string> cases;
    int width = 96, height = 64, spp = 64, max_depth = 10, map_lights = 40;
    bool no_shadows = false, where_lit = false, list = false, json = false;
};

// One case: the same lights file and the same `how` (a rotation or a view) given to both renderers.
struct Case {
    std::string set, name;
    fs::path lights;
    std::string how;
    glm::ivec3 direction{0};  // lights: the narrow light's direction (unnormalised)
    fs::path map;             // maps and ring: the map `lights` is fitted to
};

struct Row {
    const Case* c = nullptr;
    double ratio[3] = {};
    double blurred_psnr_db = 0, flip = 0;
};

// The maps of `data` (.exr, .hdr), sorted; their names without the Blender studio lights' prefix.
std::vector<std::pair<std::string, fs::path>> maps_in(const fs::path& data) {
    std::error_code ec;
    if (!fs::is_directory(data, ec)) throw coif::Error(data, "option --data", "is not a folder (the maps and the ring need its maps)");
    std::vector<std::pair<std::string, fs::path>> maps;
    for (const auto& e : fs::directory_iterator(data)) {
        const std::string ext = e.path().extension().string();
        if (ext != ".exr" && ext != ".hdr") continue;
        std::string name = e.path().stem().string();
        const std::string prefix = "blender_studiolight_";
        if (name.rfind(prefix, 0) == 0) name = name.substr(prefix.size());
        maps.emplace_back(name, e.path());
    }
    // One map per name: its .exr where a folder holds both (the shared data's maps come as both).
    std::sort(maps.begin(), maps.end());
    maps.erase(std::unique(maps.begin(), maps.end(), [](const auto& a, const auto& b) { return a.first == b.first; }), maps.end());
    if (maps.empty()) throw coif::Error(data, "option --data", "holds no .exr or .hdr map");
    return maps;
}

std::vector<Case> sweep_cases(const SweepOptions& o, const fs::path& dir) {
    std::vector<Case> cases;
    const auto wants = [&](const char* set) { return std::find(o.sets.begin(), o.sets.end(), set) != o.sets.end(); };
    if (wants("lights"))
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z) {
                    if (x == 0 && y == 0 && z == 0) continue;
                    const std::string name = "light " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z);
                    const fs::path file = dir / ("light_" + std::to_string(x) + "_" + std::to_string(y) + "_" + std::to_string(z) + ".json");
                    cases.push_back({"lights", name, file, "", glm::ivec3(x, y, z), {}});
                }
    if (wants("maps") || wants("ring")) {
        const auto maps = maps_in(o.data);
        if (wants("maps"))
            for (const auto& [name, path] : maps)
                for (int turn = 0; turn < 360; turn += 90)
                    cases.push_back({"maps", name + " " + std::to_string(turn), dir / ("map_" + name + ".json"),
                                     " --rotate-lights " + std::to_string(turn), glm::ivec3(0), path});
        if (wants("ring")) {
            // The courtyard's lights (issue 16's ring), else the first map's.
            auto it = std::find_if(maps.begin(), maps.end(), [](const auto& m) { return m.first == "courtyard"; });
            if (it == maps.end()) it = maps.begin();
            for (int azimuth = 0; azimuth < 360; azimuth += 45)
                for (int elevation : {-20, 10, 40})
                    cases.push_back({"ring", "view " + std::to_string(azimuth) + " " + std::to_string(elevation),
                                     dir / ("map_" + it->first + ".json"),
                                     " --azimuth " + std::to_string(azimuth) + " --elevation " + std::to_string(elevation),
                                     glm::ivec3(0), it->second});
        }
    }
    if (!o.cases.empty()) {
        std::vector<Case> chosen;
        for (const std::string& want : o.cases) {
            auto it = std::find_if(cases.begin(), cases.end(), [&](const Case& c) { return c.name == want; });
            if (it == cases.end())
                throw coif::Error::parameter("--case", "no case named '" + want + "' in the sets asked for (`--list` prints them)");
            chosen.push_back(*it);
        }
        cases = std::move(chosen);
    }
    return cases;
}

// What each set's rows add up to: the channel ratios in the band, their spread, and the picture's metrics. `level` is
// the ratios' geometric mean and `in_band_level_removed` the ratios in the band once it is divided out: how many a
// change of the whole image's brightness alone could bring in, so that a change's shape is told apart from its level.
struct Summary {
    int in_band = 0, ratios = 0, in_band_level_removed = 0;
    double mean_abs_ln = 0, sd_ln = 0, level = 1, lo = 0, hi = 0, blurred_mean = 0, blurred_worst = 0, flip_mean = 0;
};
Summary summarize(const std::vector<Row>& rows) {
    Summary s;
    std::vector<double> ln;
    double blurred = 0, flip = 0;
    s.lo = 1e300;
    s.blurred_worst = 1e300;
    for (const Row& r : rows) {
        for (double v : r.ratio) {
            ++s.ratios;
            if (v >= kBandLow && v <= kBandHigh) ++s.in_band;
            s.lo = std::min(s.lo, v);
            s.hi = std::max(s.hi, v);
            ln.push_back(std::log(v));
        }
        blurred += r.blurred_psnr_db;
        flip += r.flip;
        s.blurred_worst = std::min(s.blurred_worst, r.blurred_psnr_db);
    }
    const double n = double(ln.size()), mean = std::accumulate(ln.begin(), ln.end(), 0.0) / n;
    for (double v : ln) {
        s.mean_abs_ln += std::abs(v) / n;
        s.sd_ln += (v - mean) * (v - mean) / n;
        const double shape = std::exp(v - mean);
        if (shape >= kBandLow && shape <= kBandHigh) ++s.in_band_level_removed;
    }
    s.sd_ln = std::sqrt(s.sd_ln);
    s.level = std::exp(mean);
    s.blurred_mean = blurred / double(rows.size());
    s.flip_mean = flip / double(rows.size());
    return s;
}

void add_bench_sweep(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<SweepOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "sweep",
        "Lighting and views that no one tuned for (issue 16, item 1): `coif render` against `coif reference` of the\n"
        "same style's strands, both given the same lights, camera and parameters, over black. Sets (--set, repeatable):\n"
        "  lights  one narrow SRBF light (L = 300, λ = 0.1) from each of the 26 directions (x, y, z) ∈ {−1, 0, 1}³;\n"
        "  maps    every .exr/.hdr map in --data fitted to --map-lights lights (`coif env fit`), turned about +y by\n"
        "          0°, 90°, 180° and 270° (`--rotate-lights` on both renderers);\n"
        "  ring    the courtyard map's lights (else the first map's) seen from azimuth every 45° at elevations −20°,\n"
        "          10° and 40°.\n"
        "Each case prints the radiance ratio per channel (render / reference, the coverage-weighted mean hair radiance:\n"
        "`coif compare`'s), the blurred PSNR (σ 2 px) and the tone-mapped FLIP. Each set prints how many channel\n"
        "ratios lie in the issue's band [0.8, 1.25], the mean |ln ratio|, the standard deviation of ln ratio (what one\n"
        "overall factor cannot remove), the level (the ratios' geometric mean) and how many lie in the band with it\n"
        "divided out, the blurred PSNR's mean and worst, and the mean FLIP. The references do not\n"
        "depend on the renderer's settings: --references keeps them in a folder and reuses them (named by a hash of\n"
        "the lights, the fibre's parameters, the view, the size, the samples and the strands drawn), so that a second\n"
        "run with other --params for the shells renders the shells alone. Both renderers run as subprocesses of this coif.\n"
        "docs/quality.md holds the figures.");
    cmd->add_option("--set", o->sets, "Sets to run: lights, maps, ring (default lights)")->check(CLI::IsMember({"lights", "maps", "ring"}));
    cmd->add_option("--params", o->params, "Parameters file for both renderers, as `coif render --params` reads it (default: the renderer's defaults; {\"lod_pixels\": 0} draws full meshes, as docs/quality.md's sweeps do)");
    cmd->add_option("--db", o->db, "HRIR database for coif render (default: its cached default database)");
    cmd->add_option("--spp", o->spp, "Samples per pixel of the references (default 64)")->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--max-depth", o->max_depth, "The references' most scattering events per path (default 10; 1 = single scattering, to set beside {\"multiple\": false})")->check(CLI::Range(1, 1000));
    cmd->add_flag("--no-shadows", o->no_shadows, "The references light every fibre unshadowed (set beside {\"shadows\": false, \"own_cluster_shadow\": false})");
    const std::string cells = std::to_string(kLitCell) + " x " + std::to_string(kLitCell) + "-pixel cells";
    cmd->add_flag("--where-lit", o->where_lit,
                  "With --no-shadows: weigh each case's radiance ratio by where the light reaches, " + cells + " each weighed by "
                  "the share of the light a second reference, with shadows, keeps there (the lighting at the fibres' tangents where "
                  "the shadowed image takes it; docs/quality.md, \"Where the light reaches\")");
    cmd->add_option("--width", o->width, "Image width in pixels (default 96)")->check(CLI::Range(8, 4096));
    cmd->add_option("--height", o->height, "Image height in pixels (default 64)")->check(CLI::Range(8, 4096));
    cmd->add_option("--data", o->data, "Folder of the maps for the maps and ring sets (default ../shared/data)");
    cmd->add_option("--map-lights", o->map_lights, "SRBF lights fitted to each map (default 40)")->check(CLI::Range(1, 1000));
    cmd->add_option("--case", o->cases, "Run only the case of this name, as the table prints it (repeatable; e.g. \"light -1 0 0\", \"city 90\", \"view 270 -20\")");
    cmd->add_flag("--list", o->list, "Print the cases' names and stop");
    cmd->add_option("--references", o->references, "Keep the references in this folder and reuse them (default: rendered each run)");
    cmd->add_option("--keep", o->keep, "Keep the renders, lights and logs here (default: a temporary folder, removed)");
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd,
                        "  coif bench sweep --params full.json --references refs/            # full.json: {\"lod_pixels\": 0}\n"
                        "  coif bench sweep --set maps --set ring --params full.json --references refs/\n"
                        "  coif bench sweep --max-depth 1 --params single.json --case \"light -1 0 0\"   # {\"lod_pixels\": 0, \"multiple\": false}\n"
                        "  coif bench sweep --max-depth 1 --no-shadows --where-lit --params lit.json   # {\"debug\": 6, \"multiple\": false, \"fourier_order\": 0}");
    cmd->callback([o] {
        // Clear errors before minutes of rendering. What of the parameters the reference reads: the fibre's keys and
        // fiber_radius (tools/reference_options.cpp).
        std::string params_key;
        if (!o->params.empty()) {
            const coif::gl::ShellSettings p = coif::gl::read_shell_settings(o->params);
            const auto add = [&](float v) {
                char text[32];
                std::snprintf(text, sizeof text, " %.9g", v);
                params_key += text;
            };
            for (const auto& field : coif::shading::kHairParamsFields)
                std::visit(
                    [&](auto member) {
                        if constexpr (std::is_floating_point_v<std::decay_t<decltype(p.hair.fibre.*member)>>)
                            add(p.hair.fibre.*member);
                        else
                            for (int c = 0; c < 3; ++c) add((p.hair.fibre.*member)[c]);
                    },
                    field.member);
            add(p.fiber_radius);
        }
        if (!o->db.empty() && !fs::is_regular_file(o->db)) throw coif::Error(o->db, "option --db", "is not a file");
        if (o->where_lit && !o->no_shadows)
            throw coif::Error::parameter("--where-lit", "weighs an unshadowed sweep by where the light reaches: add --no-shadows");
        const coif::cli::WorkFolder work(o->keep, "coif-bench-sweep-");
        const fs::path& dir = work.path();
        const bool temporary = work.temporary();
        std::error_code ec;
        if (!o->references.empty()) {
            fs::create_directories(o->references, ec);
            if (!fs::is_directory(o->references)) throw coif::Error(o->references, "option --references", "cannot create this folder");
        }

        const std::vector<Case> cases = sweep_cases(*o, dir);
        if (o->list) {
            for (const Case& c : cases) std::printf("%s\n", c.name.c_str());
            return;
        }
        // The lights files: one narrow light per direction, one fit per map.
        std::set<fs::path> written;
        for (const Case& c : cases) {
            if (written.count(c.lights)) continue;
            written.insert(c.lights);
            if (c.map.empty()) {
                coif::SrbfLightSet set;
                set.lights.push_back({glm::vec3(kNarrowRadiance), glm::normalize(glm::vec3(c.direction)), kNarrowLambda});
                coif::write_srbf_lights(c.lights, set);
            } else {
                std::fprintf(stderr, "fitting %d SRBF lights to %s\n", o->map_lights, c.map.string().c_str());
                coif::cli::run_self("env fit " + shell_quote(c.map.string()) + " -n " + std::to_string(o->map_lights) + " -o " +
                                        shell_quote(c.lights.string()),
                                    c.lights.parent_path() / ("fit_" + c.lights.stem().string() + ".log"));
            }
        }
        // What the references draw: the embedded default style's sampled strands, in the key too, so that references
        // kept by a coif whose default style or strand sampling differed are not reused.
        // Hashed once here: each case's key then carries 16 hex digits, not the strands' megabytes.
        std::string strands_key;
        if (!o->references.empty()) {
            const coif::Strands drawn = coif::cli::SceneOptions{}.load_strands();
            std::string bytes(reinterpret_cast<const char*>(drawn.points.data()), drawn.points.size() * sizeof(drawn.points[0]));
            bytes.append(reinterpret_cast<const char*>(drawn.offsets.data()), drawn.offsets.size() * sizeof(drawn.offsets[0]));
            strands_key = " strands " + hash_hex(bytes);
        }
        const std::string size = " --width " + std::to_string(o->width) + " --height " + std::to_string(o->height) + " --background 0 0 0";
        const std::string params = o->params.empty() ? std::string() : " --params " + shell_quote(o->params);
        std::vector<Row> rows;
        coif::Progress progress("bench sweep", cases.size());
        for (std::size_t i = 0; i < cases.size(); ++i) {
            const Case& c = cases[i];
            const std::string stem = "case" + std::to_string(i);
            const auto reference_of = [&](bool shadows, const std::string& name) {
                const std::string ref_args = " --lights " + shell_quote(c.lights.string()) + c.how + size + params + " --spp " +
                                             std::to_string(o->spp) + " --max-depth " + std::to_string(o->max_depth) +
                                             (shadows ? "" : " --no-shadows");
                fs::path reference = dir / (stem + "_" + name + ".exr");
                if (!o->references.empty()) {
                    // Named by what makes it: the lights' contents, the parameters the reference reads, the rotation or
                    // view, the size, the samples and the strands drawn (not the temporary paths).
                    const std::string key =
                        read_text(c.lights) + params_key + c.how + size + ref_args.substr(ref_args.find(" --spp")) + strands_key;
                    reference = fs::path(o->references) / ("reference_" + hash_hex(key) + ".exr");
                }
                if (!fs::exists(reference))
                    coif::cli::run_self("reference" + ref_args + " -o " + shell_quote(reference.string()), dir / (stem + "_" + name + ".log"));
                return reference;
            };
            const fs::path reference = reference_of(!o->no_shadows, "reference");
            const fs::path render = dir / (stem + "_render.exr");
            coif::cli::run_self("render --env " + shell_quote(c.lights.string()) + c.how + size + params +
                                    (o->db.empty() ? std::string() : " --db " + shell_quote(o->db)) + " -o " + shell_quote(render.string()),
                                dir / (stem + "_render.log"));
            const coif::Image reference_image = coif::read_image(reference), render_image = coif::read_image(render);
            const coif::CompareResult r =
                coif::compare_images(reference_image, render_image, {}, reference.string(), render.string());
            Row row;
            row.c = &c;
            for (int ch = 0; ch < 3; ++ch) row.ratio[ch] = r.appearance.radiance_ratio[ch];
            if (o->where_lit) {
                const fs::path shadowed = reference_of(true, "reference_shadowed");
                const std::array<double, 3> lit =
                    coif::lit_weighted_ratio(reference_image, coif::read_image(shadowed), render_image, kLitCell,
                                             reference.string() + ", " + shadowed.string() + ", " + render.string());
                for (int ch = 0; ch < 3; ++ch) row.ratio[ch] = lit[ch];
            }
            row.blurred_psnr_db = r.appearance.blurred_psnr_db;
            row.flip = r.tone_mapped.flip;
            rows.push_back(row);
            progress.advance();
        }
        progress.finish();

        std::map<std::string, std::vector<Row>> by_set;
        for (const Row& r : rows) by_set[r.c->set].push_back(r);
        if (o->json) {
            nlohmann::json doc = {{"width", o->width}, {"height", o->height}, {"spp", o->spp}, {"max_depth", o->max_depth},
                                  {"no_shadows", o->no_shadows}, {"where_lit", o->where_lit}, {"params", o->params},
                                  {"band", {kBandLow, kBandHigh}}};
            doc["cases"] = nlohmann::json::array();
            for (const Row& r : rows)
                doc["cases"].push_back({{"set", r.c->set}, {"name", r.c->name}, {"radiance_ratio", {r.ratio[0], r.ratio[1], r.ratio[2]}},
                                        {"blurred_psnr_db", r.blurred_psnr_db}, {"flip", r.flip}});
            for (const auto& [set, set_rows] : by_set) {
                const Summary s = summarize(set_rows);
                doc["sets"][set] = {{"in_band", s.in_band}, {"ratios", s.ratios}, {"mean_abs_ln_ratio", s.mean_abs_ln},
                                    {"sd_ln_ratio", s.sd_ln}, {"level", s.level},
                                    {"in_band_level_removed", s.in_band_level_removed}, {"min_ratio", s.lo}, {"max_ratio", s.hi},
                                    {"blurred_psnr_db_mean", s.blurred_mean}, {"blurred_psnr_db_worst", s.blurred_worst},
                                    {"flip_mean", s.flip_mean}};
            }
            coif::cli::print_json(doc);
            return;
        }
        std::printf("%-16s %-20s %-14s %s\n", "case", "radiance ratio RGB", "blurred PSNR", "FLIP (tone-mapped)");
        for (const Row& r : rows)
            std::printf("%-16s %.3f %.3f %.3f    %6.2f dB      %.3f%s\n", r.c->name.c_str(), r.ratio[0], r.ratio[1], r.ratio[2],
                        r.blurred_psnr_db, r.flip,
                        std::all_of(std::begin(r.ratio), std::end(r.ratio), [](double v) { return v >= kBandLow && v <= kBandHigh; }) ? "" : "   out of the band");
        for (const char* set : kSets) {
            if (!by_set.count(set)) continue;
            const Summary s = summarize(by_set[set]);
            std::printf("%s: %d of %d channel ratios in [%.2f, %.2f]; mean |ln ratio| %.3f, sd of ln ratio %.3f, range %.3f-%.3f; "
                        "level (their geometric mean) %.3f, %d in the band with it divided out; "
                        "blurred PSNR mean %.2f dB, worst %.2f dB; mean FLIP %.3f\n",
                        set, s.in_band, s.ratios, kBandLow, kBandHigh, s.mean_abs_ln, s.sd_ln, s.lo, s.hi, s.level,
                        s.in_band_level_removed, s.blurred_mean, s.blurred_worst, s.flip_mean);
        }
        std::printf("%dx%d over black, references %d spp at depth %d%s%s%s%s.\n", o->width, o->height, o->spp, o->max_depth,
                    o->no_shadows ? " without shadows" : "",
                    o->where_lit ? (", radiance ratios weighed by where the light reaches (" + std::to_string(kLitCell) + " x " +
                                    std::to_string(kLitCell) + "-pixel cells)").c_str()
                                 : "",
                    o->params.empty() ? "" : ", parameters ", o->params.c_str());
        if (!temporary) std::printf("renders, lights and logs in %s\n", dir.string().c_str());
    });
}

COIF_REGISTER_COMMAND(99, add_bench_sweep);

}  // namespace
