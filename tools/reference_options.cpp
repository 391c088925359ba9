#include "tools/reference_options.h"

#include <cmath>
#include <sstream>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "offline/envmap.h"
#include "offline/srbf_lights.h"
#include "tools/scene_options.h"
#include "tools/subprocess.h"

namespace coif::cli {
namespace {

glm::vec3 rgb(const std::vector<float>& v, const std::string& option) {
    if (v.size() != 3) throw Error::parameter("option " + option, "needs three numbers R G B");
    const glm::vec3 c(v[0], v[1], v[2]);
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(c[i])) throw Error::parameter("option " + option, "must be finite numbers");
    return c;
}

}  // namespace

void ReferenceCliOptions::add_to(CLI::App* app) {
    app->add_option("--env", env, "Equirectangular environment map (.exr, .hdr) lighting the hair, importance-sampled from its pixels");
    app->add_option("--lights", lights, "SRBF lights file (from `coif env fit`) lighting the hair instead of a map: Σ L_j G_j(ω)");
    app->add_option("--env-constant", env_constant, "Constant environment radiance R G B (the default lighting is 1 1 1)")->expected(3);
    add_rotate_lights_option(app, rotate_lights_deg);
    hair.add_to(app);
    app->add_option("--spp", settings.samples_per_pixel, "Samples (camera paths) per pixel")->check(CLI::Range(1, kMaxReferenceSpp));
    app->add_option("--max-depth", settings.max_depth,
                    "Most scattering events per path: 1 = single scattering with ray-traced shadows; more = multiple "
                    "scattering between fibres")
        ->check(CLI::Range(1, kMaxReferenceDepth));
    app->add_flag("!--no-shadows", settings.shadows,
                  "Light every fibre as if no other fibre blocked the environment (camera rays still stop at the first "
                  "fibre): with --max-depth 1, the lighting alone");
    app->add_option("--seed", settings.seed, "Random seed; the same seed gives the same image on any thread count");
    app->add_option("--threads", settings.threads, "Worker threads (0 = every hardware thread)")->check(CLI::Range(0, coif::kMaxThreads));
    app->add_option("--radius", settings.fiber_radius,
                    "Fibre radius in scene units (0 = the --params key fiber_radius if given, else auto: 1e-3 of the strands' "
                    "bounding-box diagonal, ~0.8 px at the default framing)");
    add_background_option(app, background);
    app->add_flag("--background-env", background_env, "Show the environment where no fibre is hit");
    app->add_flag("--alpha", settings.alpha, "Write straight-alpha RGBA: A = fibre coverage, RGB = hair colour alone (no background)");
}

shading::HairParams ReferenceCliOptions::hair_params() const { return hair.settings().hair.fibre; }

ReferenceEnvironment ReferenceCliOptions::environment() const {
    const int given = int(!env.empty()) + int(!lights.empty()) + int(!env_constant.empty());
    if (given > 1) throw Error::parameter("options --env, --lights, --env-constant", "give at most one light source");
    const float turn = lights_rotation(rotate_lights_deg);
    if (!env.empty()) return ReferenceEnvironment::from_map(rotate_envmap_y(load_envmap(env), turn), env);
    if (!lights.empty()) return ReferenceEnvironment::from_srbf(rotate_srbf_lights_y(read_srbf_lights(lights).lights, turn), lights);
    return ReferenceEnvironment::constant(env_constant.empty() ? glm::vec3(1.0f) : rgb(env_constant, "--env-constant"));
}

ReferenceSettings ReferenceCliOptions::reference_settings() const {
    ReferenceSettings s = settings;
    // --radius, else the parameters file's fiber_radius (the radius the shells' shadows count), else auto.
    if (s.fiber_radius == 0) s.fiber_radius = hair.settings().fiber_radius;
    s.background = background_color(background);
    s.background_env = background_env;
    validate(s);
    return s;
}

std::string ReferenceCliOptions::lighting_args() const {
    std::ostringstream o;
    if (!env.empty()) o << " --env " << shell_quote(env);
    if (!lights.empty()) o << " --lights " << shell_quote(lights);
    if (env_constant.size() == 3) o << " --env-constant " << env_constant[0] << ' ' << env_constant[1] << ' ' << env_constant[2];
    return o.str();
}

}  // namespace coif::cli
