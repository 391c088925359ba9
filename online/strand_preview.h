#pragma once
// The strand preview: every strand drawn as GL line segments with a simple tangent-based shading
// (Kajiya-Kay diffuse + specular under one directional light). It is NOT coif's hair renderer (the
// SATF shells lit by SRBF Marschner lighting); it exists so that strand files and fitted styles can
// be looked at, and every image it makes says so in its metadata. Only `coif view` draws it now, because it is
// cheap per frame; `coif render --strands` draws the lit strand renderer (online/strand_renderer.h), whose
// SRBF lighting costs seconds a frame on llvmpipe.
#include <glm/glm.hpp>

#include "models/core/camera.h"
#include "models/core/image.h"
#include "models/strands.h"
#include "online/gl.h"

namespace coif::gl {

struct StrandPreviewSettings {
    glm::vec3 hair_color{0.30f, 0.17f, 0.08f};    // linear RGB
    glm::vec3 light_direction{0.4f, 0.8f, 0.45f};  // towards the light, world space
    glm::vec3 background = kDefaultBackground;
    float specular_exponent = 60.0f;
    int samples = 4;                               // MSAA samples of the offscreen target
};

inline constexpr const char* kStrandPreviewLabel =
    "coif strand preview: strands drawn as GL lines with Kajiya-Kay shading (not the SATF/Marschner renderer)";

class StrandPreview {
public:
    explicit StrandPreview(const Strands& strands);  // uploads once; needs a current GL context
    void draw(const Camera& camera, const StrandPreviewSettings& settings) const;
    size_t segment_count() const { return index_count_ / 2; }

private:
    Program program_;
    VertexArray vao_;
    Buffer vertices_, indices_;
    size_t index_count_ = 0;
};

// Renders into an offscreen target of the camera's size and returns the linear RGBA image.
Image render_strand_preview(const Strands& strands, const Camera& camera, const StrandPreviewSettings& settings);

}  // namespace coif::gl
