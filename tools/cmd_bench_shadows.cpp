// coif bench shadows — the shadow grid's count of fibres against the fibres themselves. The shell renderer's shadows
// between clusters take a light's unoccluded fraction as exp(−n), n the fibres a ray is expected to meet in the grid of
// the strands' length by direction (online/shells/shadow_grid.h; shaders/gl/shell_shadow.comp marches it): Poisson
// fibres, independent of each other. Along every camera ray through the hair this prints that exp(−n) beside the share
// of the pixel's rays that pass between the fibres, traced by `coif reference` (Embree cylinders of the same radius),
// by bins of n. Fibres gathered into clusters, and parallel neighbours that hide one another, leave more gaps than
// Poisson fibres of the same count: docs/quality.md, "The shadow grid against the fibres' gaps".
#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/core/error.h"
#include "models/core/random.h"
#include "models/core/image.h"
#include "offline/reference.h"
#include "offline/reference_fiber.h"
#include "online/shells/shadow_grid.h"
#include "shaders/lighting.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct BenchShadowsOptions {
    coif::cli::SceneOptions scene;
    int spp = 64;
    float radius = 0.0f;
    std::uint64_t seed = 1;
    std::vector<float> light;  // empty: along the camera rays; else the direction toward a light
    int grid = coif::kShadowGridSize;  // voxels along the hair's longest axis
    std::string image;                 // with --light: the per-pixel figures (write_image)
    bool json = false;
};

// Bins of the grid's n (fibres met along the camera ray): [edge_k, edge_k+1).
constexpr std::array<double, 8> kEdges{0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 1e30};

struct Bin {
    int pixels = 0;
    double fibres = 0, poisson = 0, gaps = 0;  // sums of n, exp(−n) and the traced gap share
};

void add_bench_shadows(CLI::App& root) {
    CLI::App* bench = coif::cli::noun(root, "bench", "Benchmarks that print figures (JSON with --json, else a table)");
    auto o = std::make_shared<BenchShadowsOptions>();
    CLI::App* cmd = bench->add_subcommand(
        "shadows",
        "The shadow grid's fibre count against the fibres: along every camera ray through the hair, the unoccluded\n"
        "fraction exp(-n) that the shell renderer's shadows take for the grid's n fibres met (Poisson fibres), beside\n"
        "the share of the pixel's rays that pass between the traced fibres (coif reference's coverage, --spp rays a\n"
        "pixel, the same fibre radius), by bins of n. The effective share of n, -ln(gaps) / n, is 1 for Poisson fibres\n"
        "and below 1 where fibres gather into clusters. Same scene and camera options as coif reference.");
    o->scene.add_to(cmd);
    cmd->add_option("--spp", o->spp, "Rays traced per pixel for the gaps")->check(CLI::Range(1, 65536));
    cmd->add_option("--radius", o->radius, "Fibre radius in scene units (0 = auto, as coif reference: 1e-3 of the strands' bounding-box diagonal)")
        ->check(CLI::Range(0.0f, 1e6f));
    cmd->add_option("--seed", o->seed, "Random seed of the traced rays");
    cmd->add_option("--light", o->light,
                    "X Y Z: toward a light instead. At the first fibre of each of a pixel's rays (what the camera sees),\n"
                    "exp(-n) of the grid's count along the light's direction from that fibre beside whether a traced ray\n"
                    "from it toward the light leaves the hair, by bins of n")
        ->expected(3);
    cmd->add_option("--grid", o->grid,
                    "Voxels along the hair's longest axis: " + std::to_string(coif::kShadowGridSize) +
                        " is the shadow pass's grid (the default), " + std::to_string(coif::kKeyLightGridSize) +
                        " the key lights' (online/shells/shadow_grid.h)")
        ->check(CLI::Range(8, 512));
    cmd->add_option("--image", o->image,
                    "With --light: write the figures per pixel (.exr; written atomically), each the mean over the pixel's rays,\n"
                    "a ray that meets no fibre counting 0: R the grid's exp(-n) from the fibre it meets, G whether the traced\n"
                    "ray from there reaches the light, B the share of rays that meet a fibre (the coverage), A 1. So R / B and\n"
                    "G / B are the pixel's means over the fibres it shows, and sums of R, G and B over a region weigh its fibres");
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif bench shadows --width 360 --height 240\n"
                             "  coif bench shadows --strands ../shared/data/harolongo.data --json\n"
                             "  coif bench shadows --light -1 0 0 --width 180 --height 120 --spp 16\n"
                             "  coif bench shadows --light 0 1 -1 --grid 128 --image keep.exr   # the key lights' grid, per pixel");
    cmd->callback([o] {
        if (!std::isfinite(o->radius)) throw coif::Error::parameter("option --radius", "must be a finite number of scene units");
        if (!o->image.empty() && o->light.empty())
            throw coif::Error::parameter("option --image", "writes the figures toward a light: give --light X Y Z too");
        if (!o->image.empty()) coif::cli::lock_output(o->image);
        std::string label;
        const coif::Strands strands = o->scene.load_strands(&label);
        const coif::Camera camera = o->scene.camera_for(strands);
        const float r = o->radius > 0 ? o->radius : coif::auto_fiber_radius(strands);
        // The grid as the renderer builds it from the strands it draws (ShellRenderer: voxelize_strands, not turned).
        const coif::DensityGrid grid = coif::voxelize_strands(strands, glm::mat3(1.0f), o->grid);
        coif::ReferenceSettings s;
        s.samples_per_pixel = o->spp;
        s.max_depth = 1;
        s.shadows = false;
        s.alpha = true;  // A = the share of the pixel's rays that meet a fibre
        s.fiber_radius = r;
        s.seed = o->seed;
        s.progress = !o->json;
        const coif::MarschnerFiber bsdf(coif::shading::default_hair_params());
        const coif::ReferenceEnvironment sky = coif::ReferenceEnvironment::constant(glm::vec3(1.0f));  // the tracer keeps a reference
        const coif::ReferenceRenderer tracer(strands, sky, bsdf, s);
        const bool toward_light = !o->light.empty();
        coif::Image coverage, per_pixel;  // per_pixel: --image's figures
        if (!toward_light) coverage = tracer.render(camera);

        const glm::vec3 centre = grid.origin + 0.5f * grid.extent();
        const float reach = glm::length(camera.eye - centre) + glm::length(grid.extent());
        std::array<Bin, kEdges.size() - 1> bins{};
        Bin all;
        // One measurement into its bin of n and into `all`: n the grid's fibres met, `gap` the traced share let through.
        const auto add = [&](double n, double gap) {
            std::size_t k = 0;
            while (n >= kEdges[k + 1]) ++k;
            for (Bin* b : {&bins[k], &all}) {
                ++b->pixels;
                b->fibres += n;
                b->poisson += std::exp(-n);
                b->gaps += gap;
            }
        };
        glm::vec3 light(0.0f);
        if (toward_light) {
            light = glm::vec3(o->light[0], o->light[1], o->light[2]);
            if (!std::isfinite(glm::dot(light, light)) || glm::length(light) < 1e-6f)
                throw coif::Error::parameter("option --light", "must be a finite, non-zero direction X Y Z");
            light = glm::normalize(light);
            // Every fibre point the camera sees counts once (a "pixel" of the table is one such point): the grid's
            // count toward the light from it, and whether the traced ray from it toward the light leaves the hair.
            if (!o->image.empty()) per_pixel = coif::Image(camera.width, camera.height, 4, 1.0f);
            for (int y = 0; y < camera.height; ++y)
                for (int x = 0; x < camera.width; ++x) {
                    coif::Pcg32 rng(o->seed, static_cast<std::uint64_t>(y) * camera.width + x);
                    double grid_sum = 0, lit_sum = 0, hits = 0;
                    for (int k = 0; k < o->spp; ++k) {
                        glm::vec3 origin, dir;
                        camera.ray(x + rng.uniform(), y + rng.uniform(), origin, dir);
                        const auto hit = tracer.first_fibre_lit(origin, dir, light);
                        if (!hit.found) continue;
                        const double n = 2.0 * r * grid.integrate(hit.position, light, reach, 0.5f * grid.voxel);
                        add(n, hit.lit ? 1.0 : 0.0);
                        grid_sum += std::exp(-n);
                        lit_sum += hit.lit ? 1.0 : 0.0;
                        hits += 1.0;
                    }
                    if (!per_pixel.empty()) {
                        float* px = per_pixel.at(x, y);
                        px[0] = static_cast<float>(grid_sum / o->spp);
                        px[1] = static_cast<float>(lit_sum / o->spp);
                        px[2] = static_cast<float>(hits / o->spp);
                    }
                }
        } else {
            for (int y = 0; y < camera.height; ++y)
                for (int x = 0; x < camera.width; ++x) {
                    glm::vec3 origin, dir;
                    camera.ray(x + 0.5f, y + 0.5f, origin, dir);
                    const double n = 2.0 * r * grid.integrate(origin, glm::normalize(dir), reach, 0.5f * grid.voxel);
                    const double hit = coverage.at(x, y)[3];
                    if (n < 0.01 && hit < 0.01) continue;  // no hair in either
                    add(n, 1.0 - hit);
                }
        }
        if (all.pixels == 0) throw coif::Error::parameter("camera", "no pixel sees the hair");
        if (!per_pixel.empty()) coif::write_image(o->image, per_pixel);
        const auto share = [](const Bin& b) {
            const double gaps = b.gaps / b.pixels, fibres = b.fibres / b.pixels;
            return gaps > 0 && fibres > 0 ? -std::log(gaps) / fibres : 0.0;
        };
        nlohmann::json rows = nlohmann::json::array();
        for (std::size_t k = 0; k < bins.size(); ++k) {
            const Bin& b = bins[k];
            if (b.pixels == 0) continue;
            rows.push_back({{"fibres_from", kEdges[k]},
                            {"fibres_to", k + 2 < kEdges.size() ? nlohmann::json(kEdges[k + 1]) : nlohmann::json(nullptr)},
                            {toward_light ? "points" : "pixels", b.pixels},
                            {"mean_fibres", b.fibres / b.pixels},
                            {"grid_unoccluded", b.poisson / b.pixels},
                            {"traced_gaps", b.gaps / b.pixels},
                            {"effective_share", share(b)}});
        }
        if (o->json) {
            coif::cli::print_json({{"strands", label},
                                   {"width", camera.width},
                                   {"height", camera.height},
                                   {"spp", o->spp},
                                   {"fiber_radius", r},
                                   {"grid", {grid.dims.x, grid.dims.y, grid.dims.z}},
                                   {"voxel", grid.voxel},
                                   {"light", toward_light ? nlohmann::json{light.x, light.y, light.z} : nlohmann::json(nullptr)},
                                   {toward_light ? "points" : "pixels", all.pixels},
                                   {"grid_unoccluded", all.poisson / all.pixels},
                                   {"traced_gaps", all.gaps / all.pixels},
                                   {"bins", rows}});
            return;
        }
        std::printf("coif bench shadows: %s, %dx%d, %d rays a pixel, fibre radius %g, grid %dx%dx%d of %g\n", label.c_str(),
                    camera.width, camera.height, o->spp, double(r), grid.dims.x, grid.dims.y, grid.dims.z, double(grid.voxel));
        if (toward_light)
            std::printf("  toward the light (%.3f, %.3f, %.3f) from the fibres the camera sees: each row counts fibre points,\n"
                        "  'gaps (traced)' is the share of them whose ray to the light leaves the hair\n",
                        double(light.x), double(light.y), double(light.z));
        std::printf("  fibres met (grid)   %s   mean n   exp(-n) (grid)   gaps (traced)   -ln(gaps)/n\n", toward_light ? "points" : "pixels");
        for (std::size_t k = 0; k < bins.size(); ++k) {
            const Bin& b = bins[k];
            if (b.pixels == 0) continue;
            char to[16] = "";
            if (k + 2 < kEdges.size()) std::snprintf(to, sizeof to, "%.1f", kEdges[k + 1]);
            std::printf("  %5.1f .. %-8s  %7d   %6.2f   %14.3f   %13.3f   %11.3f\n", kEdges[k], to, b.pixels, b.fibres / b.pixels,
                        b.poisson / b.pixels, b.gaps / b.pixels, share(b));
        }
        std::printf("  all hair %s     %7d   %6.2f   %14.3f   %13.3f   %11.3f\n", toward_light ? "points" : "pixels", all.pixels,
                    all.fibres / all.pixels, all.poisson / all.pixels, all.gaps / all.pixels, share(all));
    });
}

COIF_REGISTER_COMMAND(98, add_bench_shadows);

}  // namespace
