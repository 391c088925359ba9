#pragma once
// Which cluster, and where along it, a ray meets first: the hair under the viewer's cursor (painting absorption,
// picking a cluster). GL-free: the ray is tested against every cluster's outermost layer mesh on the CPU (the
// shells drawn by the renderer, each cluster's prototype mesh placed by its instance), brute force, ~1 ms for the
// default style's 64 clusters.
#include <glm/glm.hpp>
#include <optional>

#include "online/shells/prepared_shells.h"

namespace coif {

struct ShellHit {
    int cluster = -1;    // the style's cluster index (an absorption map's row)
    float t = 0;         // along the cluster, 0 root … 1 tip (an absorption map's column: t · (samples − 1))
    float distance = 0;  // from the ray's origin, world units
};

// The nearest hit of the ray (world space; `direction` need not be unit) with the outer layers, or none.
std::optional<ShellHit> pick_shells(const PreparedShells& shells, glm::vec3 origin, glm::vec3 direction);

}  // namespace coif
