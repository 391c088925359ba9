#include "models/follow_strands.h"

#include <cmath>
#include <random>
#include <string>

#include "models/core/error.h"
#include "models/core/units.h"
#include "models/style_fit.h"

namespace coif {

void validate(const FollowOptions& o, const Strands& guides) {
    if (o.strands_per_guide < 1 || o.strands_per_guide > kMaxStrandsPerGuide)
        throw Error::parameter("strands per guide", "must be 1.." + std::to_string(kMaxStrandsPerGuide) + ", not " +
                                                        std::to_string(o.strands_per_guide));
    if (!std::isfinite(o.radius) || o.radius < 0) throw Error::parameter("follow radius", "must be finite and ≥ 0 (0: automatic)");
    if (!std::isfinite(o.tip_separation) || o.tip_separation < 0)
        throw Error::parameter("tip separation", "must be finite and ≥ 0");
    const auto n = static_cast<std::uint64_t>(o.strands_per_guide);
    if (guides.strand_count() * n > kMaxStrands || guides.points.size() * n > kMaxPoints)
        throw Error::parameter("strands per guide", std::to_string(n) + " strands per guide make " +
                                                        std::to_string(guides.strand_count() * n) + " strands and " +
                                                        std::to_string(guides.points.size() * n) + " points, more than coif reads");
}

Strands follow_strands(const Strands& guides, const FollowOptions& o, std::vector<std::uint32_t>* guide_of, double* radius_used) {
    validate(o, guides);
    std::vector<glm::dvec3> roots;
    roots.reserve(guides.strand_count());
    for (std::size_t s = 0; s < guides.strand_count(); ++s) roots.emplace_back(guides.points[guides.offsets[s]]);
    const double r = o.radius > 0 ? o.radius : median_root_spacing(roots);
    if (radius_used) *radius_used = r;
    const std::size_t N = static_cast<std::size_t>(o.strands_per_guide);
    Strands out;
    out.default_thickness = guides.default_thickness;
    out.default_transparency = guides.default_transparency;
    out.default_color = guides.default_color;
    out.info = guides.info;
    out.axes_stated = guides.axes_stated;
    out.points.reserve(guides.points.size() * N);
    out.offsets.reserve(guides.strand_count() * N + 1);
    out.offsets.push_back(0);
    if (guide_of) guide_of->clear();
    std::mt19937_64 rng(o.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto copy_attributes = [&](std::size_t from, std::size_t count) {
        if (!guides.thickness.empty()) out.thickness.insert(out.thickness.end(), guides.thickness.begin() + from, guides.thickness.begin() + from + count);
        if (!guides.transparency.empty())
            out.transparency.insert(out.transparency.end(), guides.transparency.begin() + from, guides.transparency.begin() + from + count);
        if (!guides.colors.empty()) out.colors.insert(out.colors.end(), guides.colors.begin() + from, guides.colors.begin() + from + count);
    };
    for (std::size_t s = 0; s < guides.strand_count(); ++s) {
        const std::size_t first = guides.offsets[s], n = guides.point_count(s);
        // The plane perpendicular to the first segment (a zero-length one: any plane; validate() refuses such strands).
        glm::dvec3 t = glm::dvec3(guides.points[first + 1]) - glm::dvec3(guides.points[first]);
        t = glm::length(t) > 0 ? glm::normalize(t) : glm::dvec3(0, 1, 0);
        const glm::dvec3 a = glm::normalize(glm::cross(t, std::abs(t.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
        const glm::dvec3 b = glm::cross(t, a);
        for (std::size_t j = 0; j < N; ++j) {
            glm::dvec3 offset(0.0);
            if (j > 0) {  // uniform in the disc: radius r √u, angle 2π v
                const double rho = r * std::sqrt(unit(rng)), phi = kTwoPi * unit(rng);
                offset = rho * (std::cos(phi) * a + std::sin(phi) * b);
            }
            for (std::size_t k = 0; k < n; ++k) {
                const double widen = 1.0 + o.tip_separation * static_cast<double>(k) / static_cast<double>(n);
                out.points.push_back(glm::vec3(glm::dvec3(guides.points[first + k]) + widen * offset));
            }
            out.offsets.push_back(static_cast<std::uint32_t>(out.points.size()));
            copy_attributes(first, n);
            if (guide_of) guide_of->push_back(static_cast<std::uint32_t>(s));
        }
    }
    return out;
}

}  // namespace coif
