#pragma once
// The lit strand renderer: every strand drawn as GL line segments shaded with the SRBF circular-Gaussian
// Marschner lighting of shaders/lighting/ (the same GLSL as the shell renderer's lighting pass and the CPU
// evaluator shading::LightingEvaluator; shaders/gl/strand_lighting.glsl): single scattering of every SRBF
// light (srbf_single_lobes) plus, when `multiple`, the multiple-scattering term of an unoccluded fibre
// (srbf_shadowed_multiple with T̃ = 1, n = 0: d_b 𝓜^L). No shadows, no SATF: it is the real-time
// renderer's lighting alone, so that `coif bench quality` can attribute error to the lighting separately
// from SATF, shadows and compositing (docs/quality.md). `coif render --strands FILE` draws with it.
//
// Where the lighting is evaluated. By default a compute pass evaluates it at both ends of every segment
// (shaders/gl/strand_lighting.comp) and the lines interpolate it (Gouraud); `per_fragment` evaluates it
// in the fragment shader instead, exactly at every fragment. Per fragment costs ~50× more on llvmpipe
// (thin lines waste most of its 4×4-pixel shading blocks, and a line has far more fragments than points:
// harolongo at 720×480 with 40 lights took 15 min), for a difference that docs/quality.md measures.
//
// Shading frame. Tangent u = the segment's direction, constant along it as in the reference's fibre frame
// (offline/reference.cpp; each segment has its own two vertices). For a round fibre the lighting depends
// on φo − φi only (shaders/lighting.h; the reference's frame differs only by a rotation about u), so v =
// the view direction projected orthogonal to u (φo = 0) and w = u × v. Eccentric fibres (ecc_a ≠ 1) are
// shaded with this view-aligned frame too, which is not the reference's horizontal one.
//
// What a pixel sees. The fragment's radiance is L_o = Σ_j L_j (𝓜_j + ∫G_j d_b 𝓜^L_j) — 000 eq. 2 without the
// fibre diameter D, as the reference renders a fibre of real width (offline/reference_fiber.h). Lines are
// rasterized 1 px wide, so a fibre of radius r covers 2r/p of a pixel across (p = the pixel's footprint
// at the fragment's view depth z: p = 2 z tan(fov/2) / height); the fragment's alpha is that coverage,
// min(1, 2r/p), composited premultiplied "over" the background, segments drawn back to front (their
// midpoints' distance to the eye). Fibres wider than a pixel are under-covered (alpha clamps at 1 on a
// 1-px line); at coif's default framing the reference's auto radius is 0.4–0.8 px.
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "models/core/camera.h"
#include "models/core/image.h"
#include "models/strands.h"
#include "online/gl.h"
#include "online/lighting_uniforms.h"
#include "shaders/hair_parameters.h"
#include "shaders/srbf_light.h"

namespace coif::gl {

struct StrandSettings {
    shading::HairParameters hair;  // multiple: the unoccluded fibre's d_b 𝓜^L (off: single scattering only); d_f unused (no shadows)
    float fiber_radius = 0.0f;     // world units; 0: the reference's auto radius (models/strands.h auto_fiber_radius)
    glm::vec3 background = kDefaultBackground;  // linear RGB behind the hair
    int samples = 4;               // MSAA samples of the offscreen target
    bool sort_segments = true;     // back-to-front order of segments (off: file order)
    bool per_fragment = false;     // evaluate the lighting per fragment, not per strand point (see above)
    bool alpha = false;            // render(): straight-alpha RGBA, A = coverage, RGB = the hair's radiance (no
                                   // background), as the reference's `alpha` (offline/reference.h)
};

struct StrandTimings {  // GPU time of the last draw, milliseconds (GL_TIME_ELAPSED queries)
    double lighting_ms = 0, lines_ms = 0;  // lighting_ms: the per-point pass (0 per fragment)
};

inline constexpr const char* kStrandRendererLabel =
    "coif strand renderer: strands as GL lines lit by the SRBF Marschner lighting (no SATF, no shadows), coverage 2r/pixel";

class StrandRenderer {
public:
    explicit StrandRenderer(const Strands& strands);  // uploads once; needs a current GL 4.5 context
    void set_lights(std::span<const SrbfLight> lights);  // validated (coif::Error)
    // Draws into the bound framebuffer (viewport set, cleared to the background first, or to 0 with `alpha`:
    // premultiplied RGB and coverage A).
    void draw(const Camera& camera, const StrandSettings& settings);
    // Renders into an offscreen target of the camera's size and returns the linear RGBA image.
    Image render(const Camera& camera, const StrandSettings& settings);

    std::size_t segment_count() const { return midpoints_.size(); }
    const StrandTimings& timings() const { return timings_; }
    float auto_fiber_radius() const { return auto_radius_; }
    // The fibre radius `settings` asks for (its own, or the auto radius).
    float fiber_radius(const StrandSettings& settings) const;

private:
    void set_shading_uniforms(const Program& program, const Camera& camera, const StrandSettings& settings);

    Program lighting_, lines_, lines_per_fragment_;  // the last built on first use
    VertexArray vao_;
    Buffer vertices_, indices_, lights_, radiance_;
    Query query_lighting_, query_lines_;
    StrandTimings timings_;
    std::size_t vertex_count_ = 0;
    LightingTextures tables_;
    std::vector<glm::vec3> midpoints_;
    std::vector<std::uint32_t> order_, index_scratch_;
    int light_count_ = 0;
    float auto_radius_ = 0;
};

}  // namespace coif::gl
