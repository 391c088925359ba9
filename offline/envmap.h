#pragma once
// Equirectangular environment maps: loading, validation, solid-angle bookkeeping, downsampling.
//
// Orientation (the one mapping of coif, written once in shaders/envmap.glsl and used by the SRBF fit,
// the GL background and the reference renderer): world frame right-handed, y up, row 0 = zenith (+y),
// the centre column (u = 0.5) faces +x, the column at u = 0.25 faces −z, u = 0.75 faces +z, the left and
// right edges face −x. Pixel (col, row) of a W × H map is the direction envmap_direction(u, v) at its centre
// u = (col + 0.5)/W, v = (row + 0.5)/H; its solid angle is (2π/W)(cos(π row/H) − cos(π (row+1)/H)).
//
// Files read (through coif::read_image / OpenImageIO):
//   .hdr (Radiance RGBE), .exr (half/float), anything else OpenImageIO reads. Channels beyond RGB are
//   dropped; grey is expanded to RGB. Values are linear radiance in the file's own (arbitrary) units.
// What bad input gets (coif::Error naming the file, the place and what is wrong):
//   - missing, empty or undecodable file                               → error
//   - width ≠ 2 × height (not an equirectangular 2:1 map), or < 8 × 4 → error
//   - NaN or ±Inf in any RGB channel                                   → error (first pixel named, count given)
//   - negative values below −kNegativeTolerance × (mean luminance)      → error (first pixel named)
//   - small negatives above that (lossy EXR compression noise: DWAB leaves values down to −0.0033 in the
//     shared Blender maps, 2.4 % of the night map's mean)              → clamped to 0, counted, warning
//   - integer (8/16-bit, LDR) images                                    → accepted, decoded sRGB→linear, warning
//   - a map whose total energy is zero                                 → error
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "models/core/image.h"
#include "shaders/common.h"

namespace coif {

// Negative pixels with |value| ≤ kNegativeTolerance × (solid-angle mean luminance) are taken as
// compression noise and clamped to 0; anything more negative is an error. 5 % leaves a 2× margin over
// the worst DWAB noise in ../shared/data (night.exr: −0.0033 against a mean of 0.14).
inline constexpr double kNegativeTolerance = 0.05;

// Smallest map accepted (8 × 4): below that a pixel spans more than 45° and nothing can be fitted.
inline constexpr int kMinEnvMapWidth = 8;

// Rec. 709 / sRGB luminance of linear RGB, with the shaders' weights (shaders/lighting/common.glsl).
inline double luminance(const glm::dvec3& c) { return glm::dot(c, glm::dvec3(glsl::COIF_LUMINANCE)); }
inline float luminance(const glm::vec3& c) { return glsl::luminance(c); }

struct EnvMap {
    int width = 0;                     // = 2 × height
    int height = 0;
    std::vector<glm::vec3> radiance;   // width × height, row-major, row 0 = zenith; linear RGB

    EnvMap() = default;
    EnvMap(int width, int height);     // black map; throws coif::Error unless width = 2 × height ≥ 8

    glm::vec3& at(int col, int row) { return radiance[static_cast<size_t>(row) * width + col]; }
    const glm::vec3& at(int col, int row) const { return radiance[static_cast<size_t>(row) * width + col]; }

    // World direction of the centre of pixel (col, row) (unit vector; shaders/envmap.glsl).
    glm::vec3 direction(int col, int row) const;
    // Solid angle (sr) of any pixel of row `row`; the whole map sums to 4π.
    double pixel_solid_angle(int row) const;
};

struct EnvMapLoadInfo {
    std::uint64_t checksum = 0;        // coif::checksum of the file's bytes
    int file_width = 0, file_height = 0;
    bool floating_point = true;        // false: integer (LDR) file, accepted with a warning
    std::string format;                // OpenImageIO format name ("hdr", "openexr", "png", ...)
    std::size_t clamped_negatives = 0; // channel values in [−tolerance, 0) set to 0
    std::vector<std::string> warnings; // for the user; never fatal
};

// Reads and validates an equirectangular map (see the header comment for what bad input gets).
EnvMap load_envmap(const std::filesystem::path& path, EnvMapLoadInfo* info = nullptr);

// Validates an image already in memory as an environment map (same rules as load_envmap; `source`
// names it in errors). Negative noise is clamped and counted in *clamped when given.
EnvMap envmap_from_image(const Image& image, const std::filesystem::path& source, std::size_t* clamped = nullptr);

// The map as a 3-channel coif::Image (for write_image).
Image envmap_to_image(const EnvMap& map);

// Downsamples to width × width/2 by area-weighted averaging over solid angle (exact box filter in
// (φ, cos θ)), so ∫ L dω is preserved exactly. `width` must be even, ≥ kMinEnvMapWidth and ≤ map.width;
// width = map.width returns a copy.
EnvMap downsample_envmap(const EnvMap& map, int width);

// The map turned by `angle` radians about +y (right-handed: +x toward −z, as rotate_srbf_lights_y): a
// shift of every row by angle/2π of its width, linearly interpolated between columns (exact for multiples of
// one column; the row sums, and so the energy, are kept). Throws coif::Error for a non-finite angle.
EnvMap rotate_envmap_y(const EnvMap& map, float angle);

// ∫ L(ω) dω over the sphere (per channel, radiance × sr), by the pixel sum.
glm::dvec3 envmap_energy(const EnvMap& map);

// Solid-angle mean luminance, ∫ Y dω / 4π.
double envmap_mean_luminance(const EnvMap& map);

// Exposure (stops) that brings the map's solid-angle log-average luminance to middle grey 0.18
// (Reinhard's key), for tone-mapped previews: exposure = log2(0.18 / exp(Σ dω log(1e-4·Ȳ + Y) / 4π)).
float envmap_preview_exposure(const EnvMap& map);

}  // namespace coif
