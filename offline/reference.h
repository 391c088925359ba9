#pragma once
// The brute-force reference renderer (issue 10): the same strands as the real-time renderer, as thin
// round fibres ray traced with Embree, shaded with the lighting module's exact Marschner model
// (offline/reference_fiber.h), lit by an environment (a map, its fitted SRBF lights, or a constant),
// with ray-traced shadows through the fibres and multiple scattering by path tracing. Slow by design; the
// image it makes is what `coif compare` measures the real-time renderer against.
//
// Geometry. Every strand is a chain of Embree 3 RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE segments (cones with
// round joints) of constant radius, between exactly the points of the strand file. Why linear and not
// B-spline curves: the strand files are polylines and the GL renderer draws exactly those segments, so
// linear segments put the fibres where the real-time renderer puts them; B-splines would need control
// points recomputed from the polyline (they approximate, not interpolate) and move every fibre. Neighbour
// flags are set so that joints are closed without internal caps. The fibre radius is a scene-unit option;
// by default kAutoRadiusFraction of the strands' bounding-box diagonal (models/strands.h, auto_fiber_radius).
//
// Shading. A camera ray that hits a fibre sees L_o(ωo) = ∫ L_i(ωi) S(ωi, ωo) cos θi dωi (the far-field
// fibre of reference_fiber.h). L_i is the environment where the direction is unoccluded, and the light
// scattered by other fibres where it is not: a path tracer estimates it with next-event estimation of the
// environment (importance-sampled from the map itself, or from the SRBF lights) plus scattering-direction
// sampling (the fibre's longitudinal lobes), combined by multiple importance sampling (power heuristic).
// Paths stop after `max_depth` scattering events (1 = single scattering with shadows), with Russian
// roulette after `roulette_depth`. With `shadows` off the environment lights every fibre as if no other
// fibre were in the way (neither next-event nor scattering-direction samples are occluded; camera rays and
// scattered paths still meet fibres): with max_depth 1 that is the lighting alone, what the lit strand
// lines of online/strand_renderer.h compute, for `coif bench quality` to attribute error. The next ray of a path ignores the segment it leaves from and that
// segment's neighbours on the same strand (a far-field fibre scatters at its surface; without this the
// TT light would hit the fibre's own far side).
//
// Environment. Equirectangular maps use THE mapping of shaders/envmap.glsl (envmap_uv, envmap_direction,
// envmap_pixel_solid_angle), nearest pixel (piecewise constant, the function the SRBF fit approximates).
// Sampling picks a pixel with probability ∝ max(R,G,B) × solid angle and a direction uniform in solid
// angle inside it. SRBF lights are evaluated as Σ L_j G_j(ω) and sampled by picking a light ∝ its energy
// and a direction from its von Mises–Fisher shape (G_j = exp(κ(ω·ω_j − 1)), κ = 2/λ_j²).
//
// Pixels. Camera rays come from models/core/camera.h (the GL renderer's camera), jittered uniformly in
// the pixel (box filter). Output: RGB composited over a background colour (or the environment seen
// directly), or straight-alpha RGBA (`alpha`): A = fibre coverage, RGB = the mean radiance of the hair seen
// in the pixel. Deterministic for a seed: every pixel draws from its own random stream (seeded from the
// seed and the pixel index), whatever the thread count.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "models/core/camera.h"
#include "models/core/image.h"
#include "models/strands.h"
#include "offline/envmap.h"
#include "offline/reference_fiber.h"
#include "offline/srbf_lights.h"

namespace coif {

// Largest path depth accepted (scattering events).
inline constexpr int kMaxReferenceDepth = 1000;
inline constexpr int kMaxReferenceSpp = 1 << 20;

class ReferenceEnvironment {
public:
    static ReferenceEnvironment constant(const glm::vec3& radiance);
    static ReferenceEnvironment from_map(EnvMap map, std::string label);
    static ReferenceEnvironment from_srbf(std::vector<SrbfLight> lights, std::string label);

    glm::vec3 radiance(const glm::vec3& direction) const;
    // Draws a direction for next-event estimation; returns its radiance and sets the solid-angle pdf.
    glm::vec3 sample(float xi0, float xi1, float xi2, float xi3, glm::vec3& direction, float& pdf) const;
    float pdf(const glm::vec3& direction) const;
    const std::string& label() const { return label_; }

private:
    enum class Kind { constant, map, srbf } kind_ = Kind::constant;
    glm::vec3 constant_{1.0f};
    EnvMap map_;
    std::vector<float> row_cdf_;    // height + 1
    std::vector<float> col_cdf_;    // height × (width + 1)
    std::vector<float> pixel_prob_; // width × height
    std::vector<SrbfLight> lights_;
    std::vector<float> light_cdf_;  // lights + 1
    std::vector<float> light_prob_;
    std::string label_;
};

struct ReferenceSettings {
    int samples_per_pixel = 16;
    int max_depth = 10;                // scattering events per path; 1 = single scattering (with shadows)
    int roulette_depth = 3;            // Russian roulette from this depth on
    bool shadows = true;               // false: fibres do not block the environment (see the header)
    std::uint64_t seed = 1;
    int threads = 0;                   // 0: every hardware thread
    float fiber_radius = 0.0f;         // scene units; 0: auto_fiber_radius
    glm::vec3 background = kDefaultBackground;  // linear RGB
    bool background_env = false;       // show the environment where no fibre is hit
    bool alpha = false;                // straight-alpha RGBA instead of RGB over the background
    bool progress = true;
};

struct ReferenceStats {
    double build_seconds = 0;          // Embree scene
    double render_seconds = 0;         // pixels (threads included)
    std::uint64_t camera_rays = 0, rays = 0;
    int samples_per_pixel = 0;
    float fiber_radius = 0;
    std::size_t segments = 0;
    double coverage = 0;               // mean fibre coverage over the image
};

// An Embree scene of fibres plus the path tracer. Thread-safe for concurrent const calls.
class ReferenceRenderer {
public:
    // Keeps `environment` and `bsdf` by reference: they must outlive the renderer, so temporaries are refused.
    ReferenceRenderer(const Strands& strands, const ReferenceEnvironment& environment, const FiberBsdf& bsdf,
                      const ReferenceSettings& settings);
    ReferenceRenderer(const Strands&, ReferenceEnvironment&&, const FiberBsdf&, const ReferenceSettings&) = delete;
    ReferenceRenderer(const Strands&, const ReferenceEnvironment&, FiberBsdf&&, const ReferenceSettings&) = delete;
    ~ReferenceRenderer();
    ReferenceRenderer(const ReferenceRenderer&) = delete;
    ReferenceRenderer& operator=(const ReferenceRenderer&) = delete;

    Image render(const Camera& camera, ReferenceStats* stats = nullptr) const;

    // Mean over `paths` paths along one ray: RGB radiance of the first fibre hit (0 if none), A = share
    // of paths that hit a fibre. For tests of an isolated fibre.
    glm::vec4 trace(const glm::vec3& origin, const glm::vec3& direction, int paths, std::uint64_t seed) const;

    // The first fibre along a ray, and whether a ray from it toward the unit direction `light` leaves the hair (the
    // fibre's own neighbouring segments skipped, as the tracer's shadow rays skip them). For measuring the direct light
    // that reaches the fibres a camera sees (coif bench shadows --light).
    struct LitHit {
        bool found = false;
        glm::vec3 position{0.0f};
        bool lit = false;
    };
    LitHit first_fibre_lit(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& light) const;

    float fiber_radius() const { return radius_; }
    std::size_t segment_count() const { return segment_strand_.size(); }
    double build_seconds() const { return build_seconds_; }

    struct Impl;

private:
    const ReferenceEnvironment& env_;
    const FiberBsdf& bsdf_;
    ReferenceSettings settings_;
    float radius_ = 0;
    std::vector<std::uint32_t> segment_strand_;
    std::vector<glm::vec3> segment_tangent_;
    double build_seconds_ = 0;
    std::unique_ptr<Impl> impl_;
};

// Validates settings (throws coif::Error naming the option): spp and depth in range, radius finite ≥ 0,
// background finite.
void validate(const ReferenceSettings& settings);

}  // namespace coif
