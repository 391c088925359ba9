#pragma once
// SRBF lights: an environment map as L(ω) ≈ Σ_j L_j G(ω; ω_j, λ_j), with
// G(ω; ω_j, λ_j) = exp(2(ω·ω_j − 1)/λ_j²)  (000 eq. 1 and Table 1; shaders/envmap.glsl srbf_G).
//   L_j     RGB, linear radiance in the source map's units (the map's value at ω_j if no other light overlaps)
//   ω_j     unit world direction (y up; the map's orientation is that of shaders/envmap.glsl)
//   λ_j     bandwidth, radians-like (G ≈ exp(−γ²/λ_j²) at angle γ from ω_j); NOT a standard deviation
// The energy of light j is L_j · πλ_j²(1 − e^{−4/λ_j²}) (srbf_integral).
//
// Lights file (JSON, written by `coif env fit`, read by the renderer and `coif env inspect`):
//   {
//     "format": "coif-srbf-lights", "version": 1,
//     "convention": "<text: G, frame, orientation>",            (informative, not read)
//     "source": {"file": "city.exr", "checksum": "<16 hex: XXH3-64 of the file bytes>",
//                "width": 1024, "height": 512},
//     "fit": {"lights": 40, "seed": 1, "fit_width": 128, "supersampling": 3, "lambda_min": 0.0245, "lambda_max": 4,
//             "max_iterations": 100, "iterations": 37, "termination": "CONVERGENCE", "seconds": 2.1,
//             "relative_l2_error": 0.21, "relative_l2_error_fit_grid": 0.12,
//             "energy_error": 0.003, "energy_error_rgb": [..3]},
//     "lights": [{"L": [r, g, b], "omega": [x, y, z], "lambda": 0.31}, ...]
//   }
// Reading validates: format and version; 1 ≤ count ≤ kMaxSrbfLights; every number finite; L ≥ 0;
// |ω| within 1e-3 of 1 (then renormalised); λ in [kSrbfLambdaMinAllowed, kSrbfLambdaMaxAllowed];
// checksum 16 hex digits. Anything else is a coif::Error naming the JSON pointer. "fit" is optional
// (hand-written light sets need not have one); "source" is optional likewise.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shaders/srbf_light.h"

namespace coif {

// Largest light set accepted anywhere (fit and file): 000 renders with 30–60 lights; 1024 leaves room
// for studies while rejecting absurd counts that would take hours to fit.
inline constexpr int kMaxSrbfLights = 1024;
// Bandwidths accepted in a lights file. The lower end is 000 §5's smallest tabulated λ' (0.001); above
// ~10 an SRBF is constant to 4 % over the sphere (e^{−4/100}), so larger values mean nothing more.
inline constexpr double kSrbfLambdaMinAllowed = 0.001;
inline constexpr double kSrbfLambdaMaxAllowed = 10.0;

// What a light set was fitted from and how (recorded in the lights file).
struct SrbfSource {
    std::string file;                  // file name as given to the fit
    std::uint64_t checksum = 0;        // coif::checksum of the source file's bytes
    int width = 0, height = 0;         // source map size
    double rotation_y_deg = 0;         // the map was turned by this about +y before the fit (coif env fit --rotate)
};

struct SrbfFitRecord {
    int lights = 0;
    std::uint64_t seed = 0;
    int fit_width = 0;
    int supersampling = 0;
    double lambda_min = 0, lambda_max = 0;
    int max_iterations = 0;
    int iterations = 0;
    std::string termination;
    double seconds = 0;
    double relative_l2_error = 0;           // solid-angle weighted, on the full-resolution map
    double relative_l2_error_fit_grid = 0;  // the same on the downsampled map the fit saw
    double energy_error = 0;                // (E_fit − E_map)/E_map of luminance energy ∫Y dω
    glm::dvec3 energy_error_rgb{0.0};       // the same per channel
};

struct SrbfLightSet {
    std::vector<SrbfLight> lights;
    std::optional<SrbfSource> source;
    std::optional<SrbfFitRecord> fit;
};

// Σ_j L_j G(ω; ω_j, λ_j) for a unit direction ω.
glm::vec3 evaluate_srbf_lights(std::span<const SrbfLight> lights, const glm::vec3& omega);

// Σ_j L_j ∫G_j: the total energy (RGB, radiance × sr).
glm::dvec3 srbf_lights_energy(std::span<const SrbfLight> lights);

// Rotating the environment at run time = rotating the light centres (the map is never resampled).
// `rotation` must be a rotation matrix (orthonormal, det +1); L_j and λ_j are unchanged.
std::vector<SrbfLight> rotate_srbf_lights(std::span<const SrbfLight> lights, const glm::mat3& rotation);
// The usual case: turn the environment by `angle` radians about +y (right-handed: +x toward −z).
std::vector<SrbfLight> rotate_srbf_lights_y(std::span<const SrbfLight> lights, float angle);
// A turn given in degrees (`--rotate-lights`, the viewer's slider) as the radians rotate_srbf_lights_y takes: the
// same number gives the same lights everywhere. Throws coif::Error::parameter(place) for a non-finite value.
float srbf_rotation_radians(double degrees, const std::string& place = "light rotation");

// JSON text of a light set (see the header comment), and the file forms (write is atomic).
std::string srbf_lights_to_json(const SrbfLightSet& set);
// The "fit" object of a lights file (settings and measured errors of a fit), for files and --json output.
nlohmann::ordered_json srbf_fit_record_json(const SrbfFitRecord& fit);
SrbfLightSet srbf_lights_from_json(std::string_view text, const std::filesystem::path& source);
void write_srbf_lights(const std::filesystem::path& path, const SrbfLightSet& set);
SrbfLightSet read_srbf_lights(const std::filesystem::path& path);

}  // namespace coif
