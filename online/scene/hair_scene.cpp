#include "online/scene/hair_scene.h"

#include <tuple>

#include "db/default_database.h"
#include "models/core/error.h"
#include "online/scene/cook.h"

namespace coif::gl {

std::pair<glm::vec3, glm::vec3> SceneFraming::box_for(Strands sampled) const {
    if (box) return *box;
    const StrandStats st = strand_stats(keep_axes ? sampled : oriented_y_up(std::move(sampled)));
    return {glm::vec3(st.bbox_min), glm::vec3(st.bbox_max)};
}

Camera SceneFraming::camera_for(Strands sampled) const {
    const auto [lo, hi] = box_for(std::move(sampled));
    return view.around(lo, hi);
}

void refuse_eye_inside(const Camera& camera, const ShellRenderer& r) { refuse_eye_inside(camera, r.bounds_min(), r.bounds_max()); }

void refuse_eye_inside(const Camera& camera, glm::vec3 lo, glm::vec3 hi) {
    if (glm::all(glm::greaterThan(camera.eye, lo)) && glm::all(glm::lessThan(camera.eye, hi)))
        throw Error::parameter("camera", "the eye lies inside the hair's bounding box");
}

RenderTarget camera_target(const Camera& camera, int samples) {
    return RenderTarget(camera.width, camera.height, GL_RGBA16F, samples);
}

namespace {

// `cooked` uploaded to a renderer and lit, `camera` framing it: `framing.box`, else with keep_axes the sampled strands
// in the style's axes, else the box the cooking recorded (the strands turned y-up, as camera_for frames them).
ShellView make_view(CookedShells cooked, const Strands* sampled, const std::vector<SrbfLight>& lights,
                    const AbsorptionMap* absorption, const SceneFraming& framing) {
    ShellView v;
    if (framing.box) std::tie(v.frame_min, v.frame_max) = *framing.box;
    else if (framing.keep_axes) {
        if (!sampled) throw Error::parameter("keep axes", "an asset is framed as it was baked; keeping the axes needs the style");
        std::tie(v.frame_min, v.frame_max) = framing.box_for(*sampled);
    } else std::tie(v.frame_min, v.frame_max) = std::pair(cooked.frame_min, cooked.frame_max);
    v.camera = framing.view.around(v.frame_min, v.frame_max);
    v.renderer = std::make_unique<ShellRenderer>(std::move(cooked));
    v.renderer->set_lights(lights);
    if (absorption) v.renderer->set_absorption(absorption);
    refuse_eye_inside(v.camera, *v.renderer);
    return v;
}

ShellView cook_view(const HairStyle& style, const SatfIndex& satf, const std::vector<SrbfLight>& lights,
                    const AbsorptionMap* absorption, const SceneFraming& framing, int lighting_rows, CookCache* cache = nullptr) {
    Strands sampled;
    CookedShells cooked = cook_shells(style, satf, style_orientation(style), lighting_rows, &sampled, cache);
    return make_view(std::move(cooked), &sampled, lights, absorption, framing);
}

}  // namespace

HairScene::HairScene(HairSceneDesc desc)
    : lights_label(std::move(desc.lights_label)), lights(std::move(desc.lights)), style(std::move(desc.style)) {
    ShellView v;
    // A body is turned as the style's strands were on import and are when drawn; an asset holds that turn.
    const glm::mat3 body_turn = desc.cooked ? desc.cooked->body_orientation : coif::body_orientation(style);
    if (desc.cooked) {
        database_label = desc.cooked->database;
        if (desc.headless) context = Context::headless();
        v = make_view(std::move(*desc.cooked), nullptr, lights, desc.absorption, desc.framing);
    } else {
        db.emplace(open_database_or_default(desc.database, desc.log));
        satf.emplace(SatfIndex::open(*db, SatfOptions{}));
        database_label = db->path().string();
        if (desc.headless) context = Context::headless();
        v = cook_view(style, *satf, lights, desc.absorption, desc.framing, desc.lighting_rows, desc.cook_cache);
    }
    renderer = std::move(v.renderer);
    if (desc.body) {
        renderer->set_body(&*desc.body, body_turn);
        if (!desc.framing.box) {  // frame the character: the hair's box and the body's
            const auto [lo, hi] = desc.body->bounds(body_turn);
            v.frame_min = glm::min(v.frame_min, lo);
            v.frame_max = glm::max(v.frame_max, hi);
            v.camera = desc.framing.view.around(v.frame_min, v.frame_max);
            refuse_eye_inside(v.camera, *renderer);
        }
    }
    camera = v.camera;
    frame_min = v.frame_min;
    frame_max = v.frame_max;
}

ShellView HairScene::view_of(const HairStyle& other, const SceneFraming& framing, int lighting_rows, CookCache* cache) const {
    if (!satf) throw Error::parameter("style", "a scene drawn from an asset has no database to cook another style with");
    return cook_view(other, *satf, lights, nullptr, framing, lighting_rows, cache);
}

CookedShells HairScene::cook(const HairStyle& other, int lighting_rows, CookCache* cache) const {
    if (!satf) throw Error::parameter("style", "a scene drawn from an asset has no database to cook another style with");
    return cook_shells(other, *satf, style_orientation(other), lighting_rows, nullptr, cache);
}

}  // namespace coif::gl
