#pragma once
// Painted absorption: the fibres' σa (per unit fibre radius, RGB, as shaders/lighting/marschner.glsl)
// per cluster and along each cluster from root to tip, for hair that is dyed, greying or streaked.
// The shell renderer reads it per lighting sample (single and multiple scattering both use it: the
// dual-scattering tables cover every σa, shaders/lighting/luts.glsl), so painting needs no
// precomputation.
//
// File: a linear float image (.exr, or .hdr), one row per cluster in the style's order (row 0 = the
// style's first cluster), `samples` columns from root (column 0) to tip, RGB = σa; values between
// columns are linear in t. Any image editor that keeps floats can paint it; `coif style
// paint-absorption` writes gradients and streaks.
#include <cstddef>
#include <filesystem>
#include <glm/glm.hpp>
#include <vector>

namespace coif {

inline constexpr float kMaxPaintedSigmaA = 1e4f;  // as shading::kMaxSigmaA

struct AbsorptionMap {
    int clusters = 0;
    int samples = 0;                  // along t, ≥ 1
    std::vector<glm::vec3> sigma_a;   // [cluster * samples + i]
    AbsorptionMap() = default;
    AbsorptionMap(int clusters, int samples, glm::vec3 fill);
    glm::vec3& at(int cluster, int i) { return sigma_a[static_cast<std::size_t>(cluster) * samples + i]; }
    const glm::vec3& at(int cluster, int i) const { return sigma_a[static_cast<std::size_t>(cluster) * samples + i]; }
    // Linear in t ∈ [0, 1] between the columns.
    glm::vec3 sample(int cluster, double t) const;
};

// Throws coif::Error naming the file: unreadable, not a float image, a row count other than
// `clusters`, or a value that is negative, above kMaxPaintedSigmaA or not finite (with its pixel).
AbsorptionMap read_absorption_map(const std::filesystem::path& path, std::size_t clusters);
// 32-bit float EXR, atomic.
void write_absorption_map(const std::filesystem::path& path, const AbsorptionMap& map);

}  // namespace coif
