#pragma once
// The exact reference of the SRBF lighting (issue 6): the Marschner model of 000 §4.1 with the exact
// Fresnel term, integrated by brute force (dense quadrature in double precision), for checking every
// approximation of shaders/lighting/*.glsl. Slow by design; never used for rendering.
//
// Definitions the reference fixes (the approximations are measured against exactly these):
//  - N_t = Σ_h ½ |dφ/dh|⁻¹ A_t(h) (000 eq. 9), exact Fresnel, σa' and η' of Table 1. Integrals of N_t
//    against smooth kernels are done in h (γ = asin h), where the TRT caustic's 1/sqrt singularity
//    disappears: ∫ K(φ) N_t(φ) dφ = ½ ∫ A_t(h) K(φ(p,h)) dh.
//  - The TRT glints are smoothed by surface roughness of bandwidth w_c: N_TRT ⊛ ĝ^c(·; w_c), with
//    ĝ^c the circular Gaussian normalised to unit integral. This keeps TRT's energy (000's b1 is
//    energy-preserving too) and tends to the geometric-optics model as w_c → 0.
//  - Eccentricity: TRT uses η*(φh) of 000 eq. 24 with φh = (φi + φo)/2 inside the φi integral.
//  - The SRBF factorisation G_j = g^c(θi;θj,λj) g^c(φi;φj,λ') (000 Appendix) is exact; no Gaussian
//    stands in for a circular one.
//  - Dual scattering follows srbf_multiple.glsl's definitions (Zinke 2008 in θh) with the ā, ᾱ, β̄
//    terms of 000 eq. 32-33 integrated without the separation of eq. 33 and without fitted N_t.
#include <vector>

#include <glm/glm.hpp>

#include "shaders/lighting.h"

namespace coif::shading::reference {

// Exact N_t(θd, φ) at one azimuth (R, TT: sum over roots; TRT: roughened by w_c). `eta` overrides
// params.eta (for η*). RGB.
glm::dvec3 N_exact(int lobe, const HairParams& params, double eta, double theta_d, double phi);

// Exact N_TRT without roughening (infinite at the caustics), for plots.
glm::dvec3 N_TRT_unsmoothed(const HairParams& params, double eta, double theta_d, double phi);

// Exact inner integral 𝓝_t(λ', Δ, θd) = ∫ g^c(x; 0, λ') N_t(Δ - x) dx of a circular fibre of index `eta`.
glm::dvec3 inner_exact(int lobe, const HairParams& params, double eta, double theta_d, double lambda_p, double dphi);

// ∫_{-π}^{π} N_t(θd, φ) dφ exactly (in h).
glm::dvec3 energy_exact(int lobe, const HairParams& params, double eta, double theta_d);

// Brute-force 𝓜_t(ωj, λj) = ∫ G_j S_t cos θi dωi (000 eq. 2 without T̃, eq. 11) and Σ_t.
glm::dvec3 single_lobe(int lobe, const HairParams& params, double theta_o, double phi_o, double theta_j, double phi_j,
                       double lambda_j);
glm::dvec3 single(const HairParams& params, double theta_o, double phi_o, double theta_j, double phi_j, double lambda_j);

// Zinke's dual-scattering terms on a θd grid, by dense integration of the exact model.
struct ZinkeTable {
    std::vector<double> theta_d;                       // uniform on [-π/2, π/2]
    std::vector<glm::dvec3> a_f, a_b, alpha_f, alpha_b, beta_f2, beta_b2;
    std::vector<glm::dvec3> A_b, Delta_b, sigma_b;
    // Linear interpolation of one of the last three at θd.
    glm::dvec3 A_b_at(double x) const;
    glm::dvec3 Delta_b_at(double x) const;
    glm::dvec3 sigma_b_at(double x) const;
};
ZinkeTable zinke_table(const HairParams& params, int points = 129);

// Brute-force 𝓜^G = Σ_t ∫ ψ_f S_t cos θi dωi and 𝓜^L = ∫ ψ_f S_back cos θi dωi (srbf_multiple.glsl's
// definitions; exact N_t, exact per-θi Zinke terms from `table`).
glm::dvec3 ms_global(const HairParams& params, double theta_o, double phi_o, double theta_j, double phi_j,
                     double lambda_j, double sigma_f2);
glm::dvec3 ms_local(const HairParams& params, const ZinkeTable& table, double theta_o, double phi_o, double theta_j,
                    double phi_j, double lambda_j, double sigma_f2);

}  // namespace coif::shading::reference
