// coif style import|inspect|export-strands|paint-absorption — cluster hairstyles (JSON, models/hair_style.h).
#include <chrono>
#include <cstdio>
#include <numbers>
#include <optional>
#include <sstream>

#include "models/absorption_map.h"
#include "models/core/error.h"
#include "models/core/progress.h"
#include "models/follow_strands.h"
#include "models/hair_style.h"
#include "models/sector_density.h"
#include "models/strands.h"
#include "models/style_fit.h"
#include "models/style_strands.h"
#include "shaders/lighting.h"
#include "tools/assets.h"
#include "models/core/image_metrics.h"
#include "offline/reference.h"
#include "offline/reference_fiber.h"
#include "tools/cli.h"
#include "tools/compare_report.h"
#include "tools/scene_options.h"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

using coif::cli::kDefaultStyleName;
using coif::cli::load_style;

std::string orientation_words(const glm::dmat3& r) {
    if (r == glm::dmat3(1.0)) return "unchanged (the hair already hangs along -y)";
    const glm::dvec3 from = glm::transpose(r) * glm::dvec3(0, -1, 0);
    char b[160];
    std::snprintf(b, sizeof b, "rotated so that the file's (%.0f, %.0f, %.0f) hangs along -y (coif is y-up)", from.x, from.y, from.z);
    return b;
}

json error_json(const coif::FitError& e) {
    return {{"points", e.points},
            {"inside_fraction", e.inside_fraction()},
            {"rms_outside", e.rms_outside},
            {"max_outside", e.max_outside},
            {"strands", e.strands},
            {"assigned", e.assigned},
            {"assigned_share", e.assigned_share()}};
}

json stray_json(const coif::StrayReport& s) {
    return {{"worst_cluster_radii", s.worst},
            {"worst_cluster", s.worst_cluster},
            {"worst_t", s.worst_t},
            {"median_cluster_radii", s.median_cluster},
            {"clusters", s.clusters}};
}

// `style import --check`: the fitted style's sampled strands and the file's own (turned as the style was),
// path-traced alike (single scattering with shadows under a constant sky: the silhouette and the shading of
// the geometry, no multiple-scattering noise), compared with coif compare's appearance metrics.
constexpr int kCheckWidth = 180, kCheckHeight = 120, kCheckSpp = 16;

json check_json(const coif::AppearanceMetrics& m) {
    return {{"mask_iou", coif::cli::metric_json(m.mask_iou)},
            {"blurred_psnr_db", coif::cli::metric_json(m.blurred_psnr_db)},
            {"blur_sigma_px", m.blur_sigma},
            {"radiance_ratio", {m.radiance_ratio[0], m.radiance_ratio[1], m.radiance_ratio[2]}},
            {"width", kCheckWidth},
            {"height", kCheckHeight},
            {"samples_per_pixel", kCheckSpp}};
}

coif::AppearanceMetrics fit_check(const coif::HairStyle& style, const coif::Strands& file, const glm::dmat3& rotation, bool quiet) {
    coif::Strands original = file;
    for (auto& p : original.points) p = glm::vec3(rotation * glm::dvec3(p));
    const coif::Strands fitted = coif::sample_strands(style, coif::StrandSampling{});
    coif::cli::SceneOptions view;  // coif render's and coif reference's default view, framing the file's strands
    view.width = kCheckWidth;
    view.height = kCheckHeight;
    const coif::Camera camera = view.camera_for(original);
    coif::ReferenceSettings s;
    s.samples_per_pixel = kCheckSpp;
    s.max_depth = 1;
    s.alpha = true;
    s.progress = !quiet;
    s.fiber_radius = coif::auto_fiber_radius(original);  // one radius for both: the file's
    const coif::ReferenceEnvironment env = coif::ReferenceEnvironment::constant(glm::vec3(1.0f));
    const coif::MarschnerFiber fibre(coif::shading::default_hair_params());
    const coif::Image a = coif::ReferenceRenderer(original, env, fibre, s).render(camera);
    const coif::Image b = coif::ReferenceRenderer(fitted, env, fibre, s).render(camera);
    return coif::compare_images(a, b, {}, "the file's strands", "the fitted style's strands").appearance;
}

json counts_json(const coif::HairStyle& s) {
    const coif::StyleCounts c = coif::style_counts(s);
    return {{"clusters", c.clusters},
            {"prototypes", c.prototypes},
            {"instances", c.instances},
            {"macro_clusters", c.macro_clusters},
            {"macro_clusters_with_instances", c.shared_macro_clusters},
            {"layers", c.layers},
            {"hsvs", c.hsvs},
            {"sectors", c.sectors},
            {"stored_strands", c.stored_strands},
            {"memory_bytes", {{"geometry", c.geometry_bytes}, {"density_grids", c.density_bytes}, {"layer_meshes", c.mesh_bytes}}}};
}

void add_style(CLI::App& root) {
    CLI::App* style = coif::cli::noun(
        root, "style",
        "Cluster hairstyles (JSON): fit them to strand files, inspect them, turn them back into strands");

    // ── import ──
    struct ImportOptions {
        std::string in, out, name, skinning;
        coif::FitOptions fit;
        std::vector<int> grid{8, 4};
        std::optional<double> gaussian_width;  // absent: automatic (models/style_fit.h)
        coif::FollowOptions follow;
        bool no_orient = false, json = false, check = false;
    };
    auto io = std::make_shared<ImportOptions>();
    CLI::App* imp = style->add_subcommand(
        "import",
        "Fit a cluster hairstyle to a strand file (.hair, .data, .tfx or .ply): k-means clustering of the strands by root\n"
        "position and shape, a least-squares B-spline trajectory per cluster, elliptic cross-sections A, B, θ\n"
        "from the principal axes of the strands' crossings, sector densities from the member strands, and\n"
        "macro-clusters (clusters whose envelopes match after a similarity alignment become instances).\n"
        "Prints the fitting error: the share of strand points inside their cluster's envelope, the RMS distance\n"
        "of the points outside to the envelope (in the file's units), and the share of strands assigned.\n"
        "Strands that hang along -x or ±z (e.g. the CT2Hair-derived files) are rotated to hang along -y; the\n"
        "rotation is recorded in the style's \"source\". Units are kept as in the file.");
    imp->add_option("model", io->in, "Strand file to fit (" + coif::strand_extensions() + ")")->required()->check(CLI::ExistingFile);
    imp->add_option("-o,--output", io->out, "Style file to write (JSON; written atomically)")->required();
    imp->add_option("--clusters", io->fit.clusters, "Number of clusters N (capped at the strand count)")->capture_default_str()->check(CLI::Range(1, 100000));
    imp->add_option("--layers", io->fit.layout.layers, "Layered shells L per cluster")->capture_default_str()->check(CLI::Range(1, coif::kMaxLayers));
    imp->add_option("--s-t", io->fit.layout.s_t, "HSVs along each cluster (s_t + 1 sector planes)")->capture_default_str()->check(CLI::Range(1, 256));
    imp->add_option("--s-u", io->fit.layout.s_u, "HSVs around each cluster")->capture_default_str()->check(CLI::Range(1, 256));
    imp->add_option("--core-radius", io->fit.layout.core_radius, "Relative radius v of the transparent core, in [0, 1)")->capture_default_str()->check(CLI::Range(0.0, 0.99));
    imp->add_option("--grid", io->grid, "Density grid cells per sector along s (track) and r (across)")->expected(2)->capture_default_str()->check(CLI::Range(1, coif::kMaxGridCells));
    imp->add_option("--gaussian-width", io->gaussian_width,
                    "Width λ of each strand's density Gaussian exp(-d²/λ²), in the model file's units (e.g. the CT units of\n"
                    "Bangs_100/Curly_100), also the floor of the cluster half-axes. Default: the median distance between\n"
                    "neighbouring roots. Must be finite, > 0, and between 1e-6 and 1 times the diagonal of the model's bounding\n"
                    "box. The HRIR database covers sectors 1.25-13 λ deep (coif db coverage); a sector is (1 - core radius) /\n"
                    "layers = 0.2 of its cluster's half-axis deep, so a sparse model (few strands per cluster, e.g. 100 guide\n"
                    "strands) is covered only with few clusters and a λ well below its root spacing")
        ->type_name("W");
    imp->add_option("--coverage", io->fit.coverage, "Share of strand crossings each fitted ellipse encloses, (0, 1]")->capture_default_str()->check(CLI::Range(0.01, 1.0));
    imp->add_option("--macro-tolerance", io->fit.macro_tolerance,
                    "Clusters whose envelopes match a prototype's within this fraction of their mean radius become its "
                    "instances; 0 disables macro-clusters")->capture_default_str()->check(CLI::Range(0.0, 10.0));
    imp->add_option("--store-every", io->fit.store_every,
                    "Store every n-th member strand's crossings (each then counts n times): smaller files")->capture_default_str()->check(CLI::Range(1, 1000));
    imp->add_option("--seed", io->fit.seed, "Seed of the k-means++ initialisation")->capture_default_str();
    imp->add_option("--name", io->name, "Name written into the style (default: the model's file name)");
    imp->add_flag("--no-orient", io->no_orient, "Keep the file's axes even if the hair does not hang along -y");
    imp->add_option("--strands-per-guide", io->follow.strands_per_guide,
                    "Treat the file's strands as guides and fill each with N - 1 follow strands before fitting, as AMD TressFX\n"
                    "does with its follow hairs (models/follow_strands.h): each follower is its guide moved by an offset drawn\n"
                    "from a disc across the guide's root, widening toward the tip. For guide-strand files (TressFX .tfx) and\n"
                    "sparse ones (Curly_100, Bangs_100), whose clusters are otherwise far sparser than the HRIR database's\n"
                    "sectors. Skinning weights follow their guide's")
        ->capture_default_str()->check(CLI::Range(1, coif::kMaxStrandsPerGuide));
    imp->add_option("--follow-radius", io->follow.radius,
                    "Radius of the disc the followers' root offsets are drawn from, in the file's units; 0: the median\n"
                    "distance between neighbouring roots")
        ->capture_default_str()->check(CLI::NonNegativeNumber);
    imp->add_option("--tip-separation", io->follow.tip_separation,
                    "How much wider the followers spread at the tip than at the root (TressFX's tip separation factor)")
        ->capture_default_str()->check(CLI::Range(0.0, 100.0));
    imp->add_option("--skinning", io->skinning,
                    "The strands' bone weights (AMD TressFX .tfxbone, one record per strand of the model): each cluster gets the\n"
                    "mean of its strands' weights (the four largest, renormalised), written into the style for `coif render\n"
                    "--animate` (models/skinning.h)")
        ->check(CLI::ExistingFile);
    imp->add_flag("--check", io->check,
                  "Also path-trace the fitted style's strands and the file's own (coif reference, 180x120, 16 spp, single\n"
                  "scattering under a constant sky, the same camera and fibre radius) and print the hair-mask IoU and the\n"
                  "blurred PSNR between them (coif compare's appearance metrics): how closely the fit keeps the silhouette");
    coif::cli::add_json_flag(imp, io->json);
    coif::cli::examples(imp, "  coif style import ../shared/data/harolongo.data --clusters 64 -o harolongo64.json\n"
                             "  coif style import ../shared/data/Bangs_100.hair --clusters 32 -o bangs.json --json\n"
                             "  coif style import ../shared/data/Curly_100.hair --clusters 8 --gaussian-width 2 -o curly8.json\n"
                             "  coif style import ../shared/data/Ratboy_mohawk.tfx --skinning ../shared/data/Ratboy_mohawk.tfxbone -o mohawk.json\n"
                             "  coif style import ../shared/data/Ratboy_mohawk.tfx --strands-per-guide 8 -o mohawk8.json");
    imp->callback([io] {
        const auto t0 = std::chrono::steady_clock::now();
        coif::cli::lock_output(io->out);
        coif::FitOptions fit = io->fit;
        fit.layout.gaussian_width = io->gaussian_width.value_or(0.0);  // 0: automatic
        fit.layout.grid_s = io->grid[0];
        fit.layout.grid_r = io->grid[1];
        fit.orient_y_up = !io->no_orient;
        fit.progress = !io->json;
        coif::Strands strands = coif::read_strands(io->in);
        const std::size_t file_strands = strands.strand_count();
        std::optional<coif::StrandSkinning> skinning;
        if (!io->skinning.empty()) {
            skinning = coif::read_tfxbone(io->skinning);
            if (skinning->strands.size() != strands.strand_count())
                throw coif::Error(io->skinning, "strand count",
                                  std::to_string(skinning->strands.size()) + " skinned strands, but " + io->in + " has " +
                                      std::to_string(strands.strand_count()));
        }
        double follow_radius = 0;
        if (io->follow.strands_per_guide > 1) {
            io->follow.seed = io->fit.seed;
            std::vector<std::uint32_t> guide_of;
            strands = coif::follow_strands(strands, io->follow, &guide_of, &follow_radius);
            if (skinning) {  // each follower takes its guide's weights
                std::vector<coif::BoneInfluence> per_strand;
                per_strand.reserve(guide_of.size());
                for (const std::uint32_t g : guide_of) per_strand.push_back(skinning->strands[g]);
                skinning->strands = std::move(per_strand);
            }
        } else if (!io->json && (strands.axes_stated || file_strands < 1000)) {
            std::fprintf(stderr, "coif: note: %s holds %s: --strands-per-guide N fills each with followers as TressFX does, so that "
                                 "its clusters are as dense as the database's sectors\n",
                         io->in.c_str(), strands.axes_stated ? "TressFX guide strands" : (std::to_string(file_strands) + " strands").c_str());
        }
        if (io->gaussian_width) coif::check_gaussian_width(*io->gaussian_width, strands, "--gaussian-width");
        const double seconds_read = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        coif::FitReport report;
        coif::HairStyle style = coif::fit_style(strands, fit, &report);
        style.name = io->name.empty() ? fs::path(io->in).filename().string() + " (" + std::to_string(style.clusters.size()) + " clusters)" : io->name;
        style.units = "as in the source file";
        if (skinning) style.skinning = coif::cluster_influences(*skinning, report.strand_cluster, style.clusters.size());
        const coif::FitError& e = report.error;
        const coif::StrayReport& sr = report.stray;
        const glm::dmat3& r = report.rotation;
        std::optional<coif::AppearanceMetrics> check;
        if (io->check) check = fit_check(style, strands, r, io->json);
        style.source = {{"file", fs::path(io->in).filename().string()},
                        {"strands", strands.strand_count()},
                        {"points", strands.points.size()},
                        {"rotation_applied", {{r[0][0], r[1][0], r[2][0]}, {r[0][1], r[1][1], r[2][1]}, {r[0][2], r[1][2], r[2][2]}}},
                        {"axes", fit.orient_y_up || strands.axes_stated ? coif::kStyleAxesYUp : "as in the source file"},
                        {"skinning", io->skinning.empty() ? nlohmann::json(nullptr) : nlohmann::json(fs::path(io->skinning).filename().string())},
                        {"follow", io->follow.strands_per_guide > 1
                                       ? nlohmann::json{{"strands_per_guide", io->follow.strands_per_guide}, {"radius", follow_radius},
                                                        {"tip_separation", io->follow.tip_separation}, {"guides", file_strands}}
                                       : nlohmann::json(nullptr)},
                        {"fit", {{"clusters_requested", fit.clusters}, {"coverage", fit.coverage}, {"macro_tolerance", fit.macro_tolerance},
                                 {"store_every", fit.store_every}, {"seed", fit.seed}}},
                        {"fitting_error", error_json(e)},
                        {"stray", stray_json(sr)}};
        coif::write_style(io->out, style);
        const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const coif::StyleCounts c = coif::style_counts(style);
        if (io->json) {
            coif::cli::print_json({{"model", io->in},
                                   {"output", io->out},
                                   {"orientation", orientation_words(r)},
                                   {"gaussian_width", style.layout.gaussian_width},
                                   {"strands", strands.strand_count()},
                                   {"follow_radius", io->follow.strands_per_guide > 1 ? nlohmann::json(follow_radius) : nlohmann::json(nullptr)},
                                   {"counts", counts_json(style)},
                                   {"fitting_error", error_json(e)},
                                   {"stray", stray_json(sr)},
                                   {"check", check ? check_json(*check) : nlohmann::json(nullptr)},
                                   {"seconds", {{"read", seconds_read}, {"clustering", report.seconds_clustering}, {"fitting", report.seconds_fitting},
                                                {"error", report.seconds_error}, {"total", total}}}});
            return;
        }
        std::printf("%s: %zu strands, %zu points -> %zu clusters (%zu prototypes; %zu instances in %zu macro-clusters)\n",
                    io->in.c_str(), strands.strand_count(), strands.points.size(), c.clusters, c.prototypes, c.instances,
                    c.shared_macro_clusters);
        if (io->follow.strands_per_guide > 1)
            std::printf("  follow strands   %zu guides, %d strands each, root offsets within %.4g (file units), %.3gx wider at the tips\n",
                        file_strands, io->follow.strands_per_guide, follow_radius, 1.0 + io->follow.tip_separation);
        std::printf("  orientation      %s\n", orientation_words(r).c_str());
        std::printf("  Gaussian width   %.4g (file units)\n", style.layout.gaussian_width);
        std::printf("  fitting error    %.2f %% of points inside their cluster's envelope; RMS distance of the others %.4g "
                    "(max %.4g, file units); %.2f %% of strands assigned\n",
                    100 * e.inside_fraction(), e.rms_outside, e.max_outside, 100 * e.assigned_share());
        std::printf("  strays           envelope up to %.2f cluster radii from its own strands (cluster %zu at t = %.2f); median "
                    "cluster %.2f\n",
                    sr.worst, sr.worst_cluster, sr.worst_t, sr.median_cluster);
        if (check)
            std::printf("  check            fitted strands vs the file's, path-traced: hair-mask IoU %.3f, blurred PSNR %.2f dB "
                        "(sigma %.0f px), radiance ratio %s\n",
                        check->mask_iou, check->blurred_psnr_db, check->blur_sigma, coif::cli::format_rgb(check->radiance_ratio, 3).c_str());
        std::printf("  time             read %.2f s, clustering %.2f s, fitting %.2f s, error %.2f s, total %.2f s\n", seconds_read,
                    report.seconds_clustering, report.seconds_fitting, report.seconds_error, total);
        std::printf("wrote %s (%llu bytes)\n", io->out.c_str(), static_cast<unsigned long long>(fs::file_size(io->out)));
    });

    // ── inspect ──
    struct InspectOptions {
        std::string file;
        bool json = false;
    };
    auto in = std::make_shared<InspectOptions>();
    CLI::App* inspect = style->add_subcommand(
        "inspect",
        "Read a style file, check it, and print its hierarchy (clusters, macro-clusters with their instances),\n"
        "its generalized-disk layout (layers, HSVs, sectors) and the memory its geometry, density grids and layer\n"
        "meshes take, with the mean density features of its sectors (004 §5.2). \"@default\" is the style built\n"
        "into coif. A bad file gets an error naming the JSON path (exit code 1).");
    inspect->add_option("style", in->file, "Style file (JSON), or @default")->required();
    coif::cli::add_json_flag(inspect, in->json);
    coif::cli::examples(inspect, "  coif style inspect harolongo64.json\n  coif style inspect @default --json");
    inspect->callback([in] {
        const coif::HairStyle s = load_style(in->file);
        const coif::DiskLayout& l = s.layout;
        // Mean features over all prototype sectors (instances share them).
        double mean_rho = 0, mean_cs = 0, mean_cr = 0, max_rho = 0;
        std::size_t sectors = 0;
        for (const auto& c : s.clusters) {
            if (c.instance_of) continue;
            for (const coif::SectorDensity& d : coif::cluster_sector_densities(*c.shape, l, *c.density)) {
                const auto f = coif::rich_features(d);
                mean_rho += f[coif::kMeanDensity];
                mean_cs += f[coif::kCentroidS];
                mean_cr += f[coif::kCentroidR];
                max_rho = std::max(max_rho, static_cast<double>(f[coif::kMeanDensity]));
                ++sectors;
            }
        }
        if (sectors) {
            mean_rho /= static_cast<double>(sectors);
            mean_cs /= static_cast<double>(sectors);
            mean_cr /= static_cast<double>(sectors);
        }
        glm::dvec3 lo(1e300), hi(-1e300);
        double length = 0;
        for (const auto& c : s.clusters) {
            for (int k = 0; k <= 8; ++k) {
                const glm::dvec3 p = c.placement.apply(c.shape->position(k / 8.0));
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
            length += c.shape->length() * c.placement.scale;
        }
        json macros = json::array();
        for (const auto& m : s.macro_clusters())
            if (m.members.size() > 1) {
                json names = json::array();
                for (std::size_t k : m.members) names.push_back(s.clusters[k].name);
                macros.push_back({{"prototype", s.clusters[m.prototype].name}, {"members", names}});
            }
        const json doc = {{"file", in->file},
                          {"name", s.name},
                          {"units", s.units},
                          {"counts", counts_json(s)},
                          {"layout", {{"core_radius", l.core_radius}, {"layers", l.layers}, {"s_t", l.s_t}, {"s_u", l.s_u},
                                      {"grid", {l.grid_s, l.grid_r}}, {"mesh", {l.mesh_t, l.mesh_u}}, {"gaussian_width", l.gaussian_width},
                                      {"hsvs_per_cluster", l.hsv_count()}, {"sectors_per_cluster", l.sector_count()}}},
                          {"axis_bbox", {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}}},
                          {"mean_cluster_length", length / static_cast<double>(s.clusters.size())},
                          {"density", {{"mean", mean_rho}, {"max_sector_mean", max_rho}, {"mean_centroid_s", mean_cs}, {"mean_centroid_r", mean_cr}}},
                          {"macro_clusters_with_instances", macros},
                          {"source", s.source}};
        if (in->json) {
            coif::cli::print_json(doc);
            return;
        }
        const coif::StyleCounts c = coif::style_counts(s);
        std::printf("%s  (%s)\n", in->file.c_str(), s.name.c_str());
        std::printf("  clusters          %zu  (%zu prototypes with geometry, %zu instances)\n", c.clusters, c.prototypes, c.instances);
        std::printf("  macro-clusters    %zu  (%zu with instances)\n", c.macro_clusters, c.shared_macro_clusters);
        std::printf("  layout            core v < %.3g, %d layers, s_t %d, s_u %d, grid %d x %d, mesh %d x %d per HSV, lambda %.4g\n",
                    l.core_radius, l.layers, l.s_t, l.s_u, l.grid_s, l.grid_r, l.mesh_t, l.mesh_u, l.gaussian_width);
        std::printf("  HSVs              %zu  (%zu per cluster)\n", c.hsvs, l.hsv_count());
        std::printf("  sectors           %zu  (%zu per cluster; prototypes' grids shared by instances)\n", c.sectors, l.sector_count());
        std::printf("  stored strands    %zu\n", c.stored_strands);
        std::printf("  memory            geometry %.1f KiB, density grids %.1f KiB, layer meshes %.1f KiB\n", c.geometry_bytes / 1024.0,
                    c.density_bytes / 1024.0, c.mesh_bytes / 1024.0);
        std::printf("  axis bounding box min (%.3g, %.3g, %.3g) max (%.3g, %.3g, %.3g), mean cluster length %.4g\n", lo.x, lo.y, lo.z,
                    hi.x, hi.y, hi.z, length / static_cast<double>(s.clusters.size()));
        std::printf("  sector density    mean %.4g, largest sector mean %.4g, mean centroid s %.3f r %.3f (0.5 = centred)\n", mean_rho,
                    max_rho, mean_cs, mean_cr);
        for (const auto& m : macros) std::printf("  macro-cluster     %s: %s\n", m["prototype"].get<std::string>().c_str(), m["members"].dump().c_str());
    });

    // ── export-strands ──
    struct ExportOptions {
        std::string file, out, from = "density";
        coif::StrandSampling sampling;
    };
    auto eo = std::make_shared<ExportOptions>();
    CLI::App* exp = style->add_subcommand(
        "export-strands",
        "Sample strands inside the clusters of a style and write them as a Yuksel .hair file, so that strand\n"
        "renderers (coif reference, other tools) can render the same hair. --from density (default) draws strands\n"
        "from each cluster's sector densities; --from members replays the member strands a fitted style stored.");
    exp->add_option("style", eo->file, "Style file (JSON), or @default")->required();
    exp->add_option("-o,--output", eo->out, "The .hair file to write (atomically)")->required();
    exp->add_option("--from", eo->from, "density | members")->capture_default_str()->check(CLI::IsMember({"density", "members"}));
    exp->add_option("--points-per-hsv", eo->sampling.points_per_hsv, "Strand segments per HSV length")->capture_default_str()->check(CLI::Range(1, 64));
    exp->add_option("--seed", eo->sampling.seed, "Seed of the sampling")->capture_default_str();
    coif::cli::examples(exp, "  coif style export-strands harolongo64.json -o harolongo64.hair\n"
                             "  coif style export-strands @default -o default.hair --from members");
    exp->callback([eo] {
        if (fs::path(eo->out).extension() != ".hair") throw coif::Error(eo->out, "", "the output must be a .hair file");
        coif::cli::lock_output(eo->out);
        const coif::HairStyle s = load_style(eo->file);
        coif::StrandSampling o = eo->sampling;
        o.from = eo->from == "members" ? coif::StrandSampling::From::Members : coif::StrandSampling::From::Density;
        const coif::Strands strands = coif::sample_strands(s, o);
        if (strands.strand_count() == 0) throw coif::Error(eo->file, "", "the style yields no strands (" + eo->from + ")");
        coif::write_hair(eo->out, strands);
        std::fprintf(stderr, "wrote %s: %zu strands, %zu points\n", eo->out.c_str(), strands.strand_count(), strands.points.size());
    });

    struct PaintOptions {
        std::string file, out, base;
        std::vector<float> root, tip;
        double tip_from = 0.0;
        int samples = 16;
        std::vector<std::string> streaks;
    };
    auto po = std::make_shared<PaintOptions>();
    CLI::App* paint = style->add_subcommand(
        "paint-absorption",
        "Paint the fibres' absorption σa per cluster and along the clusters (dyed tips, greying roots, streaks)\n"
        "Writes an absorption map (models/absorption_map.h: a float EXR, one row per cluster in the style's order,\n"
        "columns from root to tip, RGB = σa per unit fibre radius) for `coif render --absorption`. Start from --base or\n"
        "from a root-to-tip gradient (--root, --tip, blending from --tip-from to the tip), then paint --streak clusters\n"
        "in one colour. Any image editor that keeps float EXRs can paint the map further. σa values: 000's brown is\n"
        "0.432 0.612 0.98; lower is lighter (blond ~0.1 0.2 0.4), higher darker; equal RGB is grey.");
    paint->add_option("style", po->file, "Style file (JSON), or @default")->required();
    paint->add_option("-o,--output", po->out, "The absorption map to write (.exr, atomically)")->required();
    paint->add_option("--base", po->base, "Start from this absorption map instead of the gradient");
    paint->add_option("--root", po->root, "σa R G B at the roots (default: 000's brown)")->expected(3);
    paint->add_option("--tip", po->tip, "σa R G B at the tips (default: as the roots)")->expected(3);
    paint->add_option("--tip-from", po->tip_from, "Where along the cluster (0 root .. 1 tip) the blend to --tip starts")
        ->capture_default_str()->check(CLI::Range(0.0, 0.999));
    paint->add_option("--samples", po->samples, "Columns along each cluster")->capture_default_str()->check(CLI::Range(1, 4096));
    paint->add_option("--streak", po->streaks,
                      "CLUSTERS:R,G,B — these clusters (indices and ranges, e.g. 3,7,10-12) get σa R G B along their "
                      "whole length; repeatable");
    coif::cli::examples(paint, "  coif style paint-absorption @default --tip 0.05 0.12 0.3 --tip-from 0.6 -o dyed.exr\n"
                               "  coif style paint-absorption @default --streak 3,7,20-23:0.02,0.02,0.02 -o streaks.exr\n"
                               "  coif render --absorption dyed.exr -o dyed.png");
    paint->callback([po] {
        if (fs::path(po->out).extension() != ".exr") throw coif::Error(po->out, "", "the output must be a .exr file (float σa)");
        coif::cli::lock_output(po->out);
        const coif::HairStyle s = load_style(po->file);
        const int clusters = static_cast<int>(s.clusters.size());
        const auto colour = [](const std::vector<float>& v, const char* what, glm::vec3 fallback) {
            if (v.empty()) return fallback;
            for (float x : v)
                if (!std::isfinite(x) || x < 0.0f || x > coif::kMaxPaintedSigmaA)
                    throw coif::Error::parameter(what, "σa must be finite and in [0, 10000]");
            return glm::vec3(v[0], v[1], v[2]);
        };
        const glm::vec3 root = colour(po->root, "--root", coif::shading::default_hair_params().sigma_a);
        const glm::vec3 tip = colour(po->tip, "--tip", root);
        coif::AbsorptionMap map;
        if (!po->base.empty()) {
            map = coif::read_absorption_map(po->base, s.clusters.size());
        } else {
            map = coif::AbsorptionMap(clusters, po->samples, root);
            for (int c = 0; c < clusters; ++c)
                for (int i = 0; i < po->samples; ++i) {
                    const double t = po->samples > 1 ? static_cast<double>(i) / (po->samples - 1) : 0.0;
                    const float f = t <= po->tip_from ? 0.0f : static_cast<float>((t - po->tip_from) / (1.0 - po->tip_from));
                    map.at(c, i) = root * (1.0f - f) + tip * f;
                }
        }
        for (const std::string& streak : po->streaks) {
            const auto colon = streak.find(':');
            if (colon == std::string::npos) throw coif::Error::parameter("--streak", "expected CLUSTERS:R,G,B, got '" + streak + "'");
            std::vector<float> rgb;
            std::stringstream cs(streak.substr(colon + 1));
            for (std::string item; std::getline(cs, item, ',');) {
                try {
                    rgb.push_back(std::stof(item));
                } catch (const std::exception&) {
                    throw coif::Error::parameter("--streak", "'" + item + "' is not a number in '" + streak + "'");
                }
            }
            if (rgb.size() != 3) throw coif::Error::parameter("--streak", "needs three σa values after ':' in '" + streak + "'");
            const glm::vec3 sigma = colour(rgb, "--streak", root);
            std::stringstream ls(streak.substr(0, colon));
            for (std::string item; std::getline(ls, item, ',');) {
                int a = 0, b = 0;
                try {
                    const auto dash = item.find('-');
                    a = std::stoi(item.substr(0, dash));
                    b = dash == std::string::npos ? a : std::stoi(item.substr(dash + 1));
                } catch (const std::exception&) {
                    throw coif::Error::parameter("--streak", "'" + item + "' is not a cluster index or range in '" + streak + "'");
                }
                if (a < 0 || b < a || b >= clusters)
                    throw coif::Error::parameter("--streak", "clusters '" + item + "' outside 0.." + std::to_string(clusters - 1));
                for (int c = a; c <= b; ++c)
                    for (int i = 0; i < map.samples; ++i) map.at(c, i) = sigma;
            }
        }
        coif::write_absorption_map(po->out, map);
        std::fprintf(stderr, "wrote %s: %d clusters x %d samples of sigma_a\n", po->out.c_str(), map.clusters, map.samples);
    });
}

COIF_REGISTER_COMMAND(20, add_style);

}  // namespace
