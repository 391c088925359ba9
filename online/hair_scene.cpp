#include "online/hair_scene.h"

#include "db/default_database.h"
#include "models/core/error.h"

namespace coif::gl {

Camera SceneFraming::camera_for(Strands sampled) const {
    if (box) return view.around(box->first, box->second);
    const StrandStats st = strand_stats(keep_axes ? sampled : oriented_y_up(std::move(sampled)));
    return view.around(glm::vec3(st.bbox_min), glm::vec3(st.bbox_max));
}

void refuse_eye_inside(const Camera& camera, const ShellRenderer& r) {
    const glm::vec3 lo = r.bounds_min(), hi = r.bounds_max();
    if (glm::all(glm::greaterThan(camera.eye, lo)) && glm::all(glm::lessThan(camera.eye, hi)))
        throw Error::parameter("camera", "the eye lies inside the hair's bounding box");
}

RenderTarget camera_target(const Camera& camera, int samples) {
    return RenderTarget(camera.width, camera.height, GL_RGBA16F, samples);
}

namespace {

// `renderer` prepared from `style` and lit, `camera` framing it.
ShellView make_view(const HairStyle& style, const SatfIndex& satf, const std::vector<SrbfLight>& lights,
                    const AbsorptionMap* absorption, const SceneFraming& framing, int lighting_rows) {
    ShellView v;
    Strands sampled;
    v.renderer = std::make_unique<ShellRenderer>(style, satf, style_orientation(style), lighting_rows, &sampled);
    v.renderer->set_lights(lights);
    if (absorption) v.renderer->set_absorption(absorption);
    v.camera = framing.camera_for(std::move(sampled));
    refuse_eye_inside(v.camera, *v.renderer);
    return v;
}

}  // namespace

HairScene::HairScene(HairSceneDesc desc)
    : lights_label(std::move(desc.lights_label)),
      lights(std::move(desc.lights)),
      style(std::move(desc.style)),
      db(open_database_or_default(desc.database, desc.log)),
      satf(SatfIndex::open(db, SatfOptions{})),
      context(Context::headless()) {
    ShellView v = make_view(style, satf, lights, desc.absorption, desc.framing, desc.lighting_rows);
    renderer = std::move(v.renderer);
    camera = v.camera;
}

ShellView HairScene::view_of(const HairStyle& other, const SceneFraming& framing, int lighting_rows) const {
    return make_view(other, satf, lights, nullptr, framing, lighting_rows);
}

}  // namespace coif::gl
