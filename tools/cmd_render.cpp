// coif render — one image of the scene: the SATF shell renderer lit by SRBF Marschner lighting
// (online/shell_renderer.h), or, for --strands FILE and --preview-strands, the strands as GL lines lit by
// the same SRBF Marschner lighting (online/strand_renderer.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "models/absorption_map.h"
#include "models/animation.h"
#include "models/core/error.h"
#include "models/core/image.h"
#include "offline/srbf_lights.h"
#include "online/gl_context.h"
#include "online/scene/hair_scene.h"
#include "online/shell_renderer.h"
#include "online/strand_renderer.h"
#include "db/coverage.h"
#include "tools/animation_run.h"
#include "tools/cli.h"
#include "tools/scene_options.h"


namespace {

struct RenderOptions {
    coif::cli::SceneOptions scene;
    coif::cli::ShellOptions shell;
    std::string output = "coif.png";
    float exposure = 0.0f;
    bool preview = false;
    bool aovs = false;
    bool per_fragment = false;
    bool alpha = false;
    bool json = false;
    std::string animate;
};

// Held-out sectors of the database's generator that set the "beyond the held-out p95" distance of the
// coverage warning (db/coverage.h): 300 cost ~0.3 s per render and place the p95 within a few per cent.
constexpr std::size_t kCoverageHeldOut = 300;
// Warn when more than this share of the style's non-empty sectors lies beyond that distance: the default
// style has 3 %, Curly_100 at 16 clusters 48 % (at 64 clusters 99.8-100 %: look-ups of far denser sectors).
constexpr double kCoverageWarnShare = 0.25;

void add_render(CLI::App& root) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* render = root.add_subcommand(
        "render",
        "Render one image of a hair scene, headless (the embedded default scene when given no arguments)\n"
        "The SATF renderer (004 §6): every cluster's layered shells with re/alpha read from the HRIR database on the\n"
        "GPU, the within-cluster shadow of 004 eq. 12, back-to-front compositing, lit by the SRBF circular-Gaussian\n"
        "Marschner lighting (single + multiple scattering) of the environment's SRBF lights, with shadows between\n"
        "clusters. Rendering goes through EGL, so no window or display is needed. docs/renderer.md has the details.\n"
        "With no --db the default database (1000 sectors) is built once into ~/.cache/coif (about 2 minutes on 2 cores)\n"
        "and reused.\n"
        "--strands FILE (and --preview-strands, for the style's strands) draws strands as GL lines instead, each line\n"
        "lit by the same SRBF Marschner lighting, evaluated per strand point (--per-fragment: per fragment), no SATF, no\n"
        "shadows (--env, --params, --samples, --radius and --per-fragment apply):\n"
        "the renderer's lighting alone, to compare with `coif reference` (docs/quality.md).\n"
        "Output: .png (tone-mapped sRGB: exposure, clip, sRGB curve) or .exr (linear half float); written atomically.");
    o->scene.add_to(render);
    render->add_option("-o,--output", o->output, "Image to write (.png, .exr or .hdr)")->capture_default_str();
    render->add_flag("--json", o->json,
                     "Print a summary as JSON on stdout (output, size, timings; for the shells also the database coverage "
                     "of the style's sectors and any warnings)");
    o->shell.add_to(render);
    render->add_option("--exposure", o->exposure, "Exposure in stops for the PNG tone map")->capture_default_str();
    std::string lobe_aovs;
    for (const coif::shading::Lobe& lobe : coif::shading::kLobes) lobe_aovs += std::string("OUT.") + lobe.name + ", ";
    render->add_flag("--aovs", o->aovs,
                     "Also write the separate images " + lobe_aovs + "OUT.multiple (each scattering term alone, over "
                     "black: they add up to the image over black) and OUT.shadow (the unoccluded fraction of the light "
                     "times the within-cluster shadow, as coverage-weighted grey)");
    render->add_flag("--per-fragment", o->per_fragment,
                     "Strand lines: evaluate the lighting at every fragment, not at the strand points (exact, ~50x slower)");
    render->add_flag("--alpha", o->alpha,
                     "Strand lines: write straight-alpha RGBA (A = fibre coverage, RGB = the hair's radiance, no background), "
                     "as coif reference --alpha");
    render->add_option("--animate", o->animate,
                       "Animation spec (JSON: frames, fps, bones, pivot, keys of rotate_deg and translate; models/animation.h):\n"
                       "the style's clusters follow the --body's bones by their weights (coif style import --skinning) frame by\n"
                       "frame, the body skinned, the shadow grid made again; writes OUT_0000.png … and the contact sheet\n"
                       "OUT_sheet.png beside -o OUT.png")
        ->check(CLI::ExistingFile);
    render->add_flag("--preview-strands", o->preview,
                     "Draw the style's strands as lit GL lines (the strand renderer of --strands), not the SATF shells");
    coif::cli::examples(render, "  coif render -o hair.png\n"
                                "  coif render --db db4k.db --env ../shared/data/blender_studiolight_city.exr --azimuth 90 -o side.exr\n"
                                "  coif render --params red.json --width 1920 --height 1080 -o hd.png\n"
                                "  coif render --absorption dyed.exr -o dyed.png   # from coif style paint-absorption\n"
                                "  coif render --aovs -o hair.exr   # also hair.R.exr, hair.TT.exr, hair.TRT.exr, hair.multiple.exr, hair.shadow.exr\n"
                                "  coif render --strands ../shared/data/harolongo.data --env lights.json -o lines.png\n"
                                "  coif render --style mohawk.json --body ../shared/data/Ratboy_body.tfxmesh --animate head_turn.json -o turn.png");
    render->footer(render->get_footer() +
                   "\n\nParameters file (--params; also read by coif reference --params, which uses the fibre's keys):\n"
                   "a JSON object, every key optional; degrees for angles. alpha_R_deg / beta_R_deg alone keep 000's\n"
                   "links for TT and TRT; a TT/TRT key overrides its link. Keys, what they set and what they accept:\n" +
                   coif::params_help(coif::gl::shell_settings_table()));
    render->callback([o] {
        coif::check_image_name(o->output);  // before any work (the default database may take minutes to build)
        coif::cli::lock_output(o->output);
        coif::WriteOptions wo;
        wo.exposure = o->exposure;
        if (!o->animate.empty()) {
            if (o->preview || !o->scene.strands.empty() || o->aovs)
                throw coif::Error::parameter("option --animate", "animates the shells; --strands, --preview-strands and --aovs do not apply");
            std::vector<coif::Image> thumbs;
            int shrink_by = 1;
            const coif::AnimationSpec spec = coif::read_animation_spec(o->animate);
            wo.description = "coif render --animate " + o->animate + "; style " + o->scene.style;
            const coif::cli::AnimationResult r = coif::cli::run_animation(o->scene, o->shell, spec, [&](int f, const coif::Image& image) {
                if (f == 0) shrink_by = coif::cli::sheet_factor(spec.frames, image.width);
                const std::string path = coif::cli::animation_frame_path(o->output, f);
                coif::write_image(path, image, wo);
                thumbs.push_back(coif::cli::shrink(image, shrink_by));
            });
            const std::string sheet = coif::cli::animation_sheet_path(o->output);
            coif::write_image(sheet, coif::cli::contact_sheet(thumbs), wo);
            double total = 0, motion = 0;
            for (const auto& f : r.frames) total += f.total_ms, motion += f.skinning_ms + f.deformation_ms + f.shadow_grid_ms;
            const double n = static_cast<double>(r.frames.size());
            std::fprintf(stderr,
                         "animated %zu frames at %dx%d on %s: %.1f ms a frame (motion %.1f: skinning, deformation, shadow grid; "
                         "the rest the shadow, lighting and shell passes); a still frame %.1f ms; the roots' offsets from the "
                         "body along its normals %.2f … %.2f (at rest %.2f … %.2f) -> %s … %s, %s\n",
                         r.frames.size(), r.width, r.height, r.renderer.c_str(), total / n, motion / n, r.still.total_ms,
                         r.animated_root_offset.x, r.animated_root_offset.y, r.rest_root_offset.x, r.rest_root_offset.y,
                         coif::cli::animation_frame_path(o->output, 0).c_str(),
                         coif::cli::animation_frame_path(o->output, static_cast<int>(r.frames.size()) - 1).c_str(), sheet.c_str());
            if (o->json)
                coif::cli::print_json({{"frames", r.frames.size()},
                                       {"width", r.width},
                                       {"height", r.height},
                                       {"frame_milliseconds", total / n},
                                       {"motion_milliseconds", motion / n},
                                       {"still_milliseconds", r.still.total_ms},
                                       {"root_offset", {{"rest", {r.rest_root_offset.x, r.rest_root_offset.y}},
                                                        {"animated", {r.animated_root_offset.x, r.animated_root_offset.y}}}},
                                       {"sheet", sheet}});
            return;
        }
        if (o->preview || !o->scene.strands.empty()) {
            // Everything that can be refused is read before anything is rendered or written.
            coif::gl::StrandSettings settings;
            settings.samples = o->shell.samples;
            settings.fiber_radius = o->shell.radius;
            settings.per_fragment = o->per_fragment;
            settings.alpha = o->alpha;
            settings.background = coif::cli::background_color(o->shell.background);
            if (!o->shell.params.empty()) {
                settings.hair = coif::gl::read_shell_settings(o->shell.params).hair;
            }
            std::string lights_label, label;
            const std::vector<coif::SrbfLight> lights = coif::rotate_srbf_lights_y(
                coif::cli::load_render_lights(o->shell.env, &lights_label), coif::cli::lights_rotation(o->shell.rotate_lights_deg));
            const coif::Strands strands = o->scene.load_strands(&label);
            const coif::Camera camera = o->scene.camera_for(strands);
            auto context = coif::gl::Context::headless();
            coif::gl::StrandRenderer renderer(strands);
            renderer.set_lights(lights);
            const coif::Image image = renderer.render(camera, settings);
            wo.description = std::string(coif::gl::kStrandRendererLabel) +
                             (settings.per_fragment ? "; lighting per fragment" : "; lighting per segment end") + "; fibre radius " +
                             std::to_string(renderer.fiber_radius(settings)) + "; " + label + "; lights " + lights_label;
            coif::write_image(o->output, image, wo);
            if (o->json)
                coif::cli::print_json({{"output", o->output},
                                       {"renderer", coif::gl::kStrandRendererLabel},
                                       {"width", camera.width},
                                       {"height", camera.height},
                                       {"strands", strands.strand_count()},
                                       {"lights", lights.size()},
                                       {"gpu_milliseconds", renderer.timings().lighting_ms + renderer.timings().lines_ms}});
            std::fprintf(stderr,
                         "%s\nrendered %s (%zu strands, %zu segments, fibre radius %g) with %zu lights at %dx%d on %s in %.1f ms "
                         "GPU (lighting %.1f, lines %.1f) -> %s\n",
                         coif::gl::kStrandRendererLabel, label.c_str(), strands.strand_count(), renderer.segment_count(),
                         double(renderer.fiber_radius(settings)), lights.size(), camera.width, camera.height,
                         context->renderer().c_str(), renderer.timings().lighting_ms + renderer.timings().lines_ms,
                         renderer.timings().lighting_ms, renderer.timings().lines_ms, o->output.c_str());
            return;
        }
        // Everything that can be refused is read before anything is rendered or written.
        if (o->alpha) throw coif::Error::parameter("option --alpha", "only the strand lines (--strands, --preview-strands) write straight alpha");
        const auto t_inputs = std::chrono::steady_clock::now();
        coif::cli::SceneInputs inputs = o->shell.read_inputs(o->scene);
        const double inputs_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_inputs).count();
        const bool from_asset = inputs.cooked.has_value();
        coif::gl::ShellSettings settings = o->shell.settings(inputs);
        settings.timed = true;  // wall-clock per pass, each waited for (llvmpipe's timer queries misattribute)
        const std::optional<coif::AbsorptionMap> absorption = o->shell.absorption_map(inputs);
        const auto t_scene = std::chrono::steady_clock::now();
        coif::gl::HairScene scene(
            coif::cli::hair_scene_desc(o->scene, std::move(inputs), o->shell.db, o->shell.lighting_rows, absorption ? &*absorption : nullptr));
        const double scene_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_scene).count();
        coif::gl::ShellRenderer& renderer = *scene.renderer;
        const coif::Camera& camera = scene.camera;
        // Sectors the database does not cover (sparse styles): say so before drawing them.
        std::vector<std::string> warnings;
        nlohmann::json coverage_json = nullptr;
        if (scene.db && !scene.db->is_shard()) {
            coif::CoverageOptions copt;
            copt.held_out = kCoverageHeldOut;
            const coif::CoverageReport cov = coif::database_coverage(
                *scene.db, coif::style_sector_features(scene.style), coif::held_out_sector_features(scene.db->params(), copt.held_out), copt);
            coverage_json = {{"share_beyond_held_out_p95", cov.style_beyond_held_out_p95},
                             {"share_beyond_held_out_p95_nonempty", cov.style_beyond_held_out_p95_nonempty},
                             {"held_out_sectors", copt.held_out}};
            if (cov.style_beyond_held_out_p95_nonempty > kCoverageWarnShare) {
                char buf[512];
                std::snprintf(buf, sizeof buf,
                              "%.1f %% of the style's non-empty sectors lie beyond the database's held-out p95 distance: their "
                              "look-ups return records of unlike sectors (sparse hair drawn as denser, brighter blobs); "
                              "see `coif db coverage`",
                              100.0 * cov.style_beyond_held_out_p95_nonempty);
                warnings.emplace_back(buf);
                std::fprintf(stderr, "coif: warning: %s\n", buf);
            }
        }
        const auto t_render = std::chrono::steady_clock::now();
        const coif::Image image = renderer.render(camera, settings);
        const double render_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_render).count();
        wo.description = "coif render: SATF shells, SRBF Marschner lighting; style " + o->scene.style + "; database " +
                         scene.database_label + "; lights " + scene.lights_label;
        coif::write_image(o->output, image, wo);
        const auto& st = renderer.stats();
        // The own cluster's depth across its narrow diameter (medians; ShellRenderer::own_cluster_depth): the
        // reference's fibres there, and the shells' own-cluster optical depth 2 κ_shadow Σ ᾱ.
        const coif::gl::OwnClusterDepth own = renderer.own_cluster_depth();
        const double own_fibres = 2.0 * renderer.fiber_radius(settings) * own.length;
        const double own_depth = 2.0 * settings.kappa_shadow * own.alpha;
        const double lights_lit = renderer.mean_lights_lit();  // per lighting sample (ShellSettings::light_cull skips some)
        if (o->json)
            coif::cli::print_json({{"output", o->output},
                                   {"renderer", "SATF shells"},
                                   {"width", camera.width},
                                   {"height", camera.height},
                                   {"style", o->scene.style},
                                   {"database", scene.database_label},
                                   {"clusters", st.clusters},
                                   {"sectors", st.sectors},
                                   {"triangles", st.triangles},
                                   {"lights", scene.lights.size()},
                                   {"lights_lit_per_sample", lights_lit},
                                   {"render_milliseconds", render_ms},
                                   {"tiles", renderer.timings().tiles},
                                   {"lighting_step", renderer.timings().lighting_step},
                                   {"tangent_spread_deg", coif::degrees(double(renderer.tangent_spread(settings)))},
                                   {"fiber_radius", renderer.fiber_radius(settings)},
                                   {"own_cluster_across", {{"reference_fibres", own_fibres}, {"shells_depth", own_depth}}},
                                   {"coverage", coverage_json},
                                   {"load", {{"asset", from_asset},
                                             {"inputs_milliseconds", inputs_ms},
                                             {"scene_milliseconds", scene_ms},
                                             {"upload_milliseconds", 1e3 * st.upload_seconds},
                                             {"program_compile_milliseconds", 1e3 * coif::gl::program_compile_seconds()}}},
                                   {"warnings", warnings}});
        const coif::gl::ShellTimings& t = renderer.timings();
        std::fprintf(stderr,
                     "rendered %s (%zu clusters, %zu sectors, %zu triangles) with %zu lights at %dx%d on %s in %.1f ms "
                     "wall-clock (lighting %.1f, once for every frame of the image; shells %.1f, the last frame; upload %.2f s) -> %s\n",
                     o->scene.style.c_str(), st.clusters, st.sectors, st.triangles, scene.lights.size(), camera.width,
                     camera.height, scene.context->renderer().c_str(), render_ms, t.lighting_wall_ms, t.shells_wall_ms,
                     st.upload_seconds, o->output.c_str());
        std::fprintf(stderr,
                     "loading: %s and lights read in %.1f ms; scene %.1f ms (%s, GL context, upload %.1f ms); GL programs "
                     "compiled in %.1f ms\n",
                     from_asset ? "asset" : "style", inputs_ms, scene_ms,
                     from_asset ? "no database" : "database, look-ups, atlas, shadow grid", 1e3 * st.upload_seconds,
                     1e3 * coif::gl::program_compile_seconds());
        if (const int f = coif::gl::supersampling(settings); f > 1)
            std::fprintf(stderr, "antialiased: %d frames shifted within the pixel, averaged (--samples %d; 1 for one frame)\n",
                         f * f, settings.samples);
        std::fprintf(stderr, "re_norm %.4f, record atlas %dx%d; fibre tangents spread %.1f deg about the shells' (%s)\n", st.re_norm,
                     st.atlas_width, st.atlas_height,
                     coif::degrees(double(renderer.tangent_spread(settings))),
                     settings.tangent_spread >= 0 ? "--params tangent_spread_deg, as a ring" : "measured from the style's strands at every lighting sample");
        if (settings.shadows) {
            double direct = 0, fibres = 0;
            const std::vector<glm::vec2> sh = renderer.read_shadows();
            for (const glm::vec2& v : sh) {
                direct += v.x;
                fibres += v.y;
            }
            const double n = std::max<std::size_t>(1, sh.size());
            std::fprintf(stderr,
                         "shadows between clusters: grid %dx%dx%d of %.3g (%zu strands of radius %.3g), pass %.1f ms; over %zu "
                         "samples x lights: mean unoccluded fraction %.3f, mean fibres met %.2f\n",
                         st.grid_x, st.grid_y, st.grid_z, st.voxel, st.shadow_strands, double(renderer.fiber_radius(settings)),
                         renderer.timings().shadows_ms,
                         sh.size(), direct / n, fibres / n);
        }
        if (settings.own_cluster_shadow)
            std::fprintf(stderr,
                         "own cluster across its narrow diameter (medians): the reference's fibres %.1f, the shells' depth "
                         "2 kappa_shadow sum(alpha) %.1f\n",
                         own_fibres, own_depth);
        if (settings.lod_pixels > 0.0f) {
            const auto& at = renderer.timings().clusters_at_level;
            std::fprintf(stderr, "level of detail (edges within %g px): clusters at levels 0 / 1 / 2: %zu / %zu / %zu; %zu triangles drawn\n",
                         double(settings.lod_pixels), at[0], at[1], at[2], renderer.timings().triangles_drawn);
        }
        if (settings.light_cull > 0.0f)
            std::fprintf(stderr, "lights culled per lighting sample (light_cull %g): %.1f of %zu lit on average\n",
                         double(settings.light_cull), lights_lit, scene.lights.size());
        if (settings.compositing == coif::gl::Compositing::exact) {
            const coif::gl::FragmentListStats fl = renderer.fragment_list_stats();
            std::fprintf(stderr, "exact compositing: %d tile(s); %llu fragments (%llu dropped), %llu pixels over the resolve's %d, "
                                 "resolve %.1f ms wall-clock (last frame, its last tile)\n",
                         renderer.timings().tiles, static_cast<unsigned long long>(fl.fragments), static_cast<unsigned long long>(fl.dropped),
                         static_cast<unsigned long long>(fl.pixels_over_resolve_limit), coif::gl::kResolveFragments,
                         renderer.timings().resolve_wall_ms);
        }
        if (o->aovs) {  // after the figures above, which are the image's own
            const std::filesystem::path out(o->output);
            const auto write_aov = [&](const std::string& name, const coif::Image& image) {
                const std::filesystem::path path = out.parent_path() / (out.stem().string() + "." + name + out.extension().string());
                coif::WriteOptions aw = wo;
                aw.description = wo.description + "; AOV " + name;
                coif::write_image(path, image, aw);
                std::fprintf(stderr, "AOV %-8s -> %s\n", name.c_str(), path.c_str());
            };
            for (const coif::gl::ScatteringAov& a : coif::gl::scattering_aovs(settings))  // the scattering terms
                write_aov(a.name, coif::gl::render_aov(renderer, camera, a));
            coif::gl::ShellSettings shadow = settings;  // where light reaches
            shadow.background = glm::vec3(0.0f);
            shadow.debug = 4;
            write_aov("shadow", renderer.render(camera, shadow));
        }
    });
}

COIF_REGISTER_COMMAND(60, add_render);

}  // namespace
