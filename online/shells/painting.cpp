#include "online/shells/painting.h"

#include <algorithm>
#include <cmath>

#include "online/shells/shell_pick.h"

namespace coif {

bool Painting::dab(const Camera& camera, const PreparedShells& shells, double x, double y, const Brush& brush, glm::vec3 base) {
    std::optional<AbsorptionMap> map = map_;
    if (!map) map = AbsorptionMap(static_cast<int>(shells.clusters()), kSamples, base);
    std::vector<float> weight(map->sigma_a.size(), 0.0f);
    const int r = static_cast<int>(std::ceil(brush.radius));
    const int step = std::max(1, r / 4);  // ~80 rays for a large brush: picking is brute force
    bool hit_any = false;
    for (int dy = -r; dy <= r; dy += step)
        for (int dx = -r; dx <= r; dx += step) {
            const double d = std::hypot(dx, dy);
            if (d > brush.radius) continue;
            glm::vec3 origin, direction;
            camera.ray(float(x + dx + 0.5), float(y + dy + 0.5), origin, direction);
            const std::optional<ShellHit> hit = pick_shells(shells, origin, direction);
            if (!hit) continue;
            hit_any = true;
            const int column = static_cast<int>(std::lround(hit->t * (map->samples - 1)));
            float& w = weight[static_cast<std::size_t>(hit->cluster) * map->samples + column];
            w = std::max(w, static_cast<float>(brush.strength * (1.0 - d / (brush.radius + 1.0))));
        }
    if (!hit_any) return false;
    for (std::size_t i = 0; i < weight.size(); ++i)
        if (weight[i] > 0.0f) map->sigma_a[i] = glm::mix(map->sigma_a[i], brush.sigma_a, weight[i]);
    map_ = std::move(map);
    return true;
}

}  // namespace coif
