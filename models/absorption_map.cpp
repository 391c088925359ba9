#include "models/absorption_map.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "models/core/error.h"
#include "models/core/image.h"

namespace coif {

AbsorptionMap::AbsorptionMap(int c, int s, glm::vec3 fill)
    : clusters(c), samples(s), sigma_a(static_cast<std::size_t>(c) * s, fill) {}

glm::vec3 AbsorptionMap::sample(int cluster, double t) const {
    const double x = std::clamp(t, 0.0, 1.0) * (samples - 1);
    const int i0 = std::min(static_cast<int>(x), samples - 1);
    const int i1 = std::min(i0 + 1, samples - 1);
    const float f = static_cast<float>(x - i0);
    const std::size_t row = static_cast<std::size_t>(cluster) * samples;
    return sigma_a[row + i0] * (1.0f - f) + sigma_a[row + i1] * f;
}

AbsorptionMap read_absorption_map(const std::filesystem::path& path, std::size_t clusters) {
    ImageInfo info;
    const Image image = read_image(path, &info);
    const std::string file = path.string();
    if (!info.floating_point)
        throw Error(file, "", "an absorption map holds σa values and must be a float image (.exr or .hdr), not " + info.format);
    if (static_cast<std::size_t>(image.height) != clusters)
        throw Error(file, "", "has " + std::to_string(image.height) + " rows but the style has " + std::to_string(clusters) +
                                  " clusters (one row per cluster, in the style's order)");
    if (image.channels < 3) throw Error(file, "", "needs RGB channels (σa per colour)");
    AbsorptionMap map(image.height, image.width, glm::vec3(0.0f));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float* p = image.at(x, y);
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(p[c]) || p[c] < 0.0f || p[c] > kMaxPaintedSigmaA)
                    throw Error(file, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")",
                                "σa must be finite and in [0, " + std::to_string(static_cast<int>(kMaxPaintedSigmaA)) + "]");
            map.at(y, x) = glm::vec3(p[0], p[1], p[2]);
        }
    return map;
}

void write_absorption_map(const std::filesystem::path& path, const AbsorptionMap& map) {
    if (map.clusters < 1 || map.samples < 1 || map.sigma_a.size() != static_cast<std::size_t>(map.clusters) * map.samples)
        throw Error(path.string(), "", "an absorption map needs at least one cluster and one sample");
    Image image(map.samples, map.clusters, 3);
    for (int y = 0; y < map.clusters; ++y)
        for (int x = 0; x < map.samples; ++x) {
            const glm::vec3 v = map.sigma_a[static_cast<std::size_t>(y) * map.samples + x];
            float* p = image.at(x, y);
            p[0] = v.x;
            p[1] = v.y;
            p[2] = v.z;
        }
    WriteOptions options;
    options.full_float = true;
    options.description = "coif absorption map: sigma_a per unit fibre radius; rows = clusters, columns = root to tip";
    write_image(path, image, options);
}

}  // namespace coif
