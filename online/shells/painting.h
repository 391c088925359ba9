#pragma once
// Painting absorption onto the shells: the painted map (models/absorption_map.h, what `coif render --absorption`
// reads), a brush that moves the map's columns under a disc of pixels toward its σa (the hair under each pixel
// picked by online/shells/shell_pick.h). GL-free; the viewer (online/window/) draws with map(). The strokes' undo and
// redo are the authoring's history (online/shells/authoring.h), which holds cluster edits too.
#include <glm/glm.hpp>
#include <optional>

#include "models/absorption_map.h"
#include "models/core/camera.h"
#include "online/shells/prepared_shells.h"

namespace coif {

struct Brush {
    double radius = 12;                     // pixels
    double strength = 0.5;                  // 0 … 1: how far σa moves toward the brush's at the disc's centre
    glm::vec3 sigma_a{4.0f, 5.0f, 6.0f};    // per unit fibre radius (near-black)
};

class Painting {
public:
    // Columns along each cluster of a map the first stroke starts (coif style paint-absorption's default).
    static constexpr int kSamples = 32;

    explicit Painting(std::optional<AbsorptionMap> start = std::nullopt) : map_(std::move(start)) {}

    // The painted map, or null before any paint (σa then comes from the parameters).
    const AbsorptionMap* map() const { return map_ ? &*map_ : nullptr; }

    // One dab centred on image pixel (x, y) (top-left origin) of `camera`'s image: each hair point under the disc is
    // moved toward brush.sigma_a by strength × (1 − r/(radius + 1)) at the column nearest its t. The first dab makes
    // the map, `base` everywhere (the parameters' σa). False when the disc met no hair.
    bool dab(const Camera& camera, const PreparedShells& shells, double x, double y, const Brush& brush, glm::vec3 base);
    // The map set as it is (null: no paint; the authoring's history restores maps this way).
    void replace(std::optional<AbsorptionMap> map) { map_ = std::move(map); }

private:
    std::optional<AbsorptionMap> map_;
};

}  // namespace coif
