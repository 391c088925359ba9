#include "offline/envmap.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "models/core/atomic_file.h"
#include "models/core/checksum.h"
#include "models/core/error.h"
#include "models/core/units.h"
#include "shaders/envmap.h"

namespace coif {
namespace fs = std::filesystem;

namespace {

std::string pixel_name(int col, int row) {
    return "pixel (col " + std::to_string(col) + ", row " + std::to_string(row) + ")";
}

void check_size(int width, int height, const fs::path& source) {
    if (width != 2 * height)
        throw Error(source, "size", std::to_string(width) + "x" + std::to_string(height) +
                                        " is not an equirectangular map (width must be 2 x height)");
    if (width < kMinEnvMapWidth)
        throw Error(source, "size", std::to_string(width) + "x" + std::to_string(height) + " is smaller than " +
                                        std::to_string(kMinEnvMapWidth) + "x" + std::to_string(kMinEnvMapWidth / 2));
}

}  // namespace

EnvMap::EnvMap(int w, int h) : width(w), height(h) {
    check_size(w, h, {});
    radiance.assign(static_cast<size_t>(w) * h, glm::vec3(0.0f));
}

glm::vec3 EnvMap::direction(int col, int row) const {
    return glsl::envmap_direction(glm::vec2((col + 0.5f) / width, (row + 0.5f) / height));
}

double EnvMap::pixel_solid_angle(int row) const {
    return glsl::envmap_pixel_solid_angle(float(row), float(width), float(height));
}

EnvMap envmap_from_image(const Image& image, const fs::path& source, std::size_t* clamped) {
    check_size(image.width, image.height, source);
    EnvMap map;
    map.width = image.width;
    map.height = image.height;
    map.radiance.resize(static_cast<size_t>(map.width) * map.height);

    // Non-finite values first: they would poison the mean used for the negative tolerance.
    std::size_t non_finite = 0;
    int first_col = -1, first_row = -1;
    for (int row = 0; row < map.height; ++row)
        for (int col = 0; col < map.width; ++col) {
            const float* p = image.at(col, row);
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(p[c])) {
                    if (non_finite++ == 0) first_col = col, first_row = row;
                }
            map.at(col, row) = glm::vec3(p[0], p[1], p[2]);
        }
    if (non_finite)
        throw Error(source, pixel_name(first_col, first_row),
                    "NaN or infinite value (" + std::to_string(non_finite) + " channel values in all)");

    const double mean = envmap_mean_luminance(map);
    const double tolerance = kNegativeTolerance * std::max(mean, 0.0);
    std::size_t n_clamped = 0;
    for (int row = 0; row < map.height; ++row)
        for (int col = 0; col < map.width; ++col) {
            glm::vec3& p = map.at(col, row);
            for (int c = 0; c < 3; ++c)
                if (p[c] < 0.0f) {
                    if (-p[c] > tolerance) {
                        std::ostringstream what;
                        what << "negative radiance " << p[c] << " in channel " << "RGB"[c]
                             << " (only noise down to -" << tolerance << ", " << kNegativeTolerance * 100
                             << " % of the mean luminance, is clamped to 0)";
                        throw Error(source, pixel_name(col, row), what.str());
                    }
                    p[c] = 0.0f;
                    ++n_clamped;
                }
        }
    if (!(envmap_mean_luminance(map) > 0.0)) throw Error(source, "pixels", "the map is black (no energy to fit)");
    if (clamped) *clamped = n_clamped;
    return map;
}

EnvMap load_envmap(const fs::path& path, EnvMapLoadInfo* info) {
    ImageInfo image_info;
    const Image image = read_image(path, &image_info);
    std::size_t clamped = 0;
    EnvMap map = envmap_from_image(image, path, &clamped);
    if (info) {
        info->checksum = checksum(read_file_bytes(path));
        info->file_width = image.width;
        info->file_height = image.height;
        info->floating_point = image_info.floating_point;
        info->format = image_info.format;
        info->clamped_negatives = clamped;
        info->warnings.clear();
        if (!image_info.floating_point)
            info->warnings.push_back(path.string() + ": " + std::to_string(image_info.bits_per_channel) +
                                     "-bit integer image: not an HDR map; values were decoded from sRGB to linear "
                                     "and clip at 1, so bright light sources are lost");
        if (clamped)
            info->warnings.push_back(path.string() + ": " + std::to_string(clamped) +
                                     " slightly negative channel values (compression noise) were set to 0");
    }
    return map;
}

Image envmap_to_image(const EnvMap& map) {
    Image image(map.width, map.height, 3);
    for (int row = 0; row < map.height; ++row)
        for (int col = 0; col < map.width; ++col) {
            float* p = image.at(col, row);
            const glm::vec3& c = map.at(col, row);
            p[0] = c.r, p[1] = c.g, p[2] = c.b;
        }
    return image;
}

namespace {

// Overlap weights of a box resampling from n source cells to m destination cells on [0, 1] under the
// measure d(x) (x = cell edge position in [0, 1]); measure(a, b) gives the measure of [a, b].
template <class Measure>
std::vector<std::vector<std::pair<int, double>>> box_weights(int n, int m, Measure measure) {
    std::vector<std::vector<std::pair<int, double>>> w(m);
    for (int d = 0; d < m; ++d) {
        const double d0 = double(d) / m, d1 = double(d + 1) / m;
        const int s_begin = std::max(0, int(std::floor(d0 * n)));
        const int s_end = std::min(n, int(std::ceil(d1 * n)));
        for (int s = s_begin; s < s_end; ++s) {
            const double lo = std::max(d0, double(s) / n), hi = std::min(d1, double(s + 1) / n);
            if (hi > lo) w[d].emplace_back(s, measure(lo, hi));
        }
    }
    return w;
}

}  // namespace

EnvMap rotate_envmap_y(const EnvMap& map, float angle) {
    if (!std::isfinite(angle)) throw Error::parameter("environment rotation", "the angle must be a finite number");
    EnvMap out = map;
    // Columns grow with azimuth towards −z from +x (centre column +x, quarter column −z), so turning the
    // environment +x → −z moves content to lower columns: out(c) = map(c + s), s = angle / 2π · width.
    const double s = double(angle) / (2.0 * kPi) * map.width;
    const double whole = std::floor(s);
    const int k = static_cast<int>(std::fmod(whole, double(map.width)));
    const float f = static_cast<float>(s - whole);
    for (int r = 0; r < map.height; ++r)
        for (int c = 0; c < map.width; ++c) {
            const int c0 = ((c + k) % map.width + map.width) % map.width, c1 = (c0 + 1) % map.width;
            out.at(c, r) = (1.0f - f) * map.at(c0, r) + f * map.at(c1, r);
        }
    return out;
}

EnvMap downsample_envmap(const EnvMap& map, int width) {
    if (width % 2 != 0 || width < kMinEnvMapWidth || width > map.width)
        throw Error::parameter("downsample width", std::to_string(width) + " must be even and within " +
                                                       std::to_string(kMinEnvMapWidth) + ".." +
                                                       std::to_string(map.width));
    if (width == map.width) return map;
    const int height = width / 2;
    // Columns: uniform in φ. Rows: measure dω ∝ d(−cos θ) with θ = π v.
    const auto cols = box_weights(map.width, width, [](double a, double b) { return b - a; });
    const auto rows = box_weights(map.height, height, [](double a, double b) {
        return 2.0 * std::sin(kPi * (a + b) / 2.0) * std::sin(kPi * (b - a) / 2.0);
    });
    EnvMap out(width, height);
    std::vector<glm::dvec3> row_acc(static_cast<size_t>(width));
    for (int r = 0; r < height; ++r) {
        std::fill(row_acc.begin(), row_acc.end(), glm::dvec3(0.0));
        double row_total = 0.0;
        for (const auto& [s, ws] : rows[r]) {
            row_total += ws;
            for (int c = 0; c < width; ++c) {
                glm::dvec3 sum(0.0);
                double total = 0.0;
                for (const auto& [sc, wc] : cols[c]) {
                    sum += wc * glm::dvec3(map.at(sc, s));
                    total += wc;
                }
                row_acc[c] += ws * sum / total;
            }
        }
        for (int c = 0; c < width; ++c) out.at(c, r) = glm::vec3(row_acc[c] / row_total);
    }
    return out;
}

glm::dvec3 envmap_energy(const EnvMap& map) {
    glm::dvec3 energy(0.0);
    for (int row = 0; row < map.height; ++row) {
        glm::dvec3 sum(0.0);
        for (int col = 0; col < map.width; ++col) sum += glm::dvec3(map.at(col, row));
        energy += map.pixel_solid_angle(row) * sum;
    }
    return energy;
}

double envmap_mean_luminance(const EnvMap& map) { return luminance(envmap_energy(map)) / (4.0 * kPi); }

float envmap_preview_exposure(const EnvMap& map) {
    const double floor = 1e-4 * std::max(envmap_mean_luminance(map), 1e-30);
    double sum = 0.0, total = 0.0;
    for (int row = 0; row < map.height; ++row) {
        const double d_omega = map.pixel_solid_angle(row);
        for (int col = 0; col < map.width; ++col) {
            sum += d_omega * std::log(floor + std::max(0.0f, luminance(map.at(col, row))));
            total += d_omega;
        }
    }
    return float(std::log2(0.18 / std::exp(sum / total)));
}

}  // namespace coif
