#pragma once
// A similarity transform x ↦ s R x + c (uniform scale s > 0, rotation R, translation c): how a
// macro-cluster places the instances of its prototype cluster (004 §3.1, "geometries of all the hair
// clusters can be trivially derived from each other via simple transformations").
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace coif {

struct Similarity {
    double scale = 1.0;
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // unit quaternion (w, x, y, z)
    glm::dvec3 translation{0.0};

    glm::dvec3 apply(const glm::dvec3& x) const { return scale * (rotation * x) + translation; }
    glm::dvec3 apply_direction(const glm::dvec3& d) const { return rotation * d; }  // unit vectors stay unit
    bool is_identity() const {
        return scale == 1.0 && rotation == glm::dquat(1.0, 0.0, 0.0, 0.0) && translation == glm::dvec3(0.0);
    }
    // x ↦ R⁻¹ (x − c) / s.
    Similarity inverse() const {
        Similarity r;
        r.scale = 1.0 / scale;
        r.rotation = glm::conjugate(rotation);
        r.translation = -(r.scale * (r.rotation * translation));
        return r;
    }
    // (this ∘ inner)(x) = this(inner(x)).
    Similarity after(const Similarity& inner) const {
        Similarity r;
        r.scale = scale * inner.scale;
        r.rotation = glm::normalize(rotation * inner.rotation);
        r.translation = apply(inner.translation);
        return r;
    }
};

}  // namespace coif
