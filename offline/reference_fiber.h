#pragma once
// The scattering function of one fibre as the reference renderer sees it: S(ωi, ωo) of 000 eq. 6
// (units 1/sr), so that the radiance leaving a fibre towards ωo is
//     L_o(ωo) = ∫ L_i(ωi) S(ωi, ωo) cos θi dωi                                   (000 eq. 2 without D)
// where θi is the longitudinal angle of ωi (cos θi = |ωi × u|). 000 eq. 2 multiplies by the fibre
// diameter D because it gives a curve's intensity (radiance integrated across the fibre's width); the
// reference renderer intersects fibres of real width, so a camera ray that hits a fibre sees the
// intensity divided by the width: the same integral without D, at every point across the fibre (the
// far-field model: no dependence on where across its width the fibre is hit).
//
// Directions are world-space unit vectors pointing AWAY from the fibre (ωi towards the light, ωo towards
// the eye). The hair frame (u tangent root→tip, v reference normal, w = u × v) is the lighting module's
// shading::FibreFrame; for eccentric fibres v is the axis that `a` scales (000 eq. 24).
//
// One source of truth: MarschnerFiber evaluates the lighting module's exact Marschner model (shaders/,
// issue 6), it does not re-implement it. IsotropicFiber is a test fibre (S = albedo / π², so that
// ∫ S cos θi dωi = albedo exactly: ∫ cos θi dωi = ∫∫ cos² θ dθ dφ = π²) for the white-furnace test of the
// path tracer itself.
#include <memory>

#include <glm/glm.hpp>

#include "shaders/lighting.h"

namespace coif {

using FiberFrame = shading::FibreFrame;

// A longitudinal lobe that the path tracer's direction sampling should follow: θi is drawn around
// 2α − θo (000 eq. 7: M_t(θh) = 2 g^u(θi; 2α_t − θo, 2β_t)); φ around φo + phi_offset with spread
// phi_sigma (radians; ≥ π means uniform in φ); weight = the share of samples (need not sum to 1).
struct FiberLobeHint {
    float alpha = 0, beta = 0.1f;
    float phi_offset = 0, phi_sigma = 10.0f;
    float weight = 1.0f;
};

class FiberBsdf {
public:
    virtual ~FiberBsdf() = default;
    // S(ωi, ωo), RGB, 1/sr.
    virtual glm::vec3 S(const FiberFrame& frame, const glm::vec3& wi, const glm::vec3& wo) const = 0;
    // Lobes to importance-sample (three at most); empty: uniform sampling only.
    virtual int lobe_hints(FiberLobeHint out[3]) const = 0;
};

class IsotropicFiber final : public FiberBsdf {
public:
    explicit IsotropicFiber(glm::vec3 albedo) : albedo_(albedo) {}
    glm::vec3 S(const FiberFrame&, const glm::vec3&, const glm::vec3&) const override;
    int lobe_hints(FiberLobeHint*) const override { return 0; }

private:
    glm::vec3 albedo_;
};

struct MarschnerTable;

// The exact Marschner model of the lighting module (R + TT + TRT, eccentricity, exact Fresnel, σa per
// unit radius) for one parameter set: S_t = M_t(θh) N_t(θd, φ) / cos² θd (000 eq. 6) with M_t the module's
// M_lobe and N_t its exact shading::reference::N_exact, sampled once on a grid at construction (a few
// seconds on 2 cores) and interpolated (see reference_fiber.cpp for the grid and why).
class MarschnerFiber final : public FiberBsdf {
public:
    explicit MarschnerFiber(const shading::HairParams& params);  // validates (coif::Error)
    glm::vec3 S(const FiberFrame& frame, const glm::vec3& wi, const glm::vec3& wo) const override;
    int lobe_hints(FiberLobeHint out[3]) const override;
    const shading::HairParams& params() const { return params_; }
    // The tabulated N_t (lobe 0 R, 1 TT, 2 TRT; eta_star only matters for eccentric TRT).
    glm::vec3 N(int lobe, float eta_star, float theta_d, float phi) const;

private:
    shading::HairParams params_;
    std::shared_ptr<const MarschnerTable> table_;
};

// ∫ L S cos θi dωi for a constant unit environment (the fibre's directional albedo towards ωo), by
// stratified quadrature over the sphere (n × 2n cells in (sin θi, φi), midpoint rule), for tests.
glm::vec3 fiber_albedo(const FiberBsdf& bsdf, const FiberFrame& frame, const glm::vec3& wo, int n = 256);

}  // namespace coif
