#pragma once
// The precomputed tables of the SRBF lighting (layouts in shaders/lighting/luts.glsl), computed on the
// CPU in double precision and stored as float RGBA images that online/ uploads as GL_RGBA32F textures.
//   global (parameter-free, once per process): 𝒞_k (000 eq. 14), H_k^TT, H_k^TRT (eq. 19, 23), the
//   half-circle mass of circular Gaussians (eq. 28), the exact-Fresnel polynomial fit and the own cluster's
//   transmittance as harmonics (shaders/lighting/own_cluster.glsl);
//   per hair-parameter set: the dual-scattering 1D tables Ā_b, ∫Δ̄_b, ∫σ̄_b (000 §5, eq. 29-31).
#include <cstddef>
#include <span>
#include <vector>

#include "shaders/glsl_prelude.h"
#include "shaders/lut.h"

namespace coif::glsl {
struct HairParams;
struct LightingConfig;
}  // namespace coif::glsl

namespace coif::shading {

struct LightingTables {
    LutImage ck_lo, ck_hi, h_tt, h_trt, half_mass, fresnel_fit, own_cluster;
    double build_seconds = 0.0;  // wall time of build_lighting_tables()
    LutSet set() const;
};

LightingTables build_lighting_tables();

// Built on first use (thread-safe), then shared: read from the copy computed at build time and embedded in the
// library (shaders/tables/make_lighting_tables.cpp), which is build_lighting_tables()'s result bit for bit.
const LightingTables& global_lighting_tables();
// The tables as bytes (per table in the order ck_lo, ck_hi, h_tt, h_trt, half_mass, fresnel_fit, own_cluster: u32 width, u32
// height, width × height RGBA floats; little-endian), and back (throws coif::Error on a size that does not match).
std::vector<std::byte> lighting_tables_bytes(const LightingTables& tables);
LightingTables lighting_tables_from_bytes(std::span<const std::byte> bytes);

struct MultipleScatteringTables {
    LutImage ab, sat_delta, sat_sigma, af;
    double build_seconds = 0.0;
    LutSet set() const;
};

// The dual-scattering tables of one parameter set, over θd and σa (shaders/lighting/luts.glsl): they do
// not depend on the parameters' own σa. Needs the global tables bound or passed.
MultipleScatteringTables build_ms_tables(const glsl::HairParams& params, const glsl::LightingConfig& config);

// Exact references of table entries (double precision direct integration), for tests and checks.
double ck_direct(int k, double lambda_p, double dphi);            // 𝒞_k / ∫g^c
double h_direct(bool trt, int k, double eta, double theta_d);      // H_k^TT or H_k^TRT
double half_mass_direct(double lambda, double delta);
// The cosine harmonics o_0..o_8 of the own cluster's transmittance O(Δ) = exp(−τ s(ρ, Δ))
// (shaders/lighting/own_cluster.glsl): O = o_0 + Σ_m o_m cos mΔ.
std::array<double, 9> own_cluster_direct(double tau, double rho);

}  // namespace coif::shading
