#include "models/style_edit.h"

#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

#include "models/core/error.h"
#include "models/core/units.h"

namespace coif {
namespace {

// A cluster's root in the style's space: its axis at t = 0, placed.
glm::dvec3 placed_root(const Cluster& c) { return c.placement.apply(c.shape->position(0.0)); }

void check_clusters(const HairStyle& style, std::span<const std::size_t> clusters) {
    std::set<std::size_t> seen;
    for (const std::size_t c : clusters) {
        if (c >= style.clusters.size())
            throw Error::parameter("cluster", std::to_string(c) + " is out of range (the style has " + std::to_string(style.clusters.size()) + ")");
        if (!seen.insert(c).second) throw Error::parameter("cluster", style.clusters[c].name + " is named twice");
    }
}

void check_similarity(const Similarity& s) {
    const bool finite = std::isfinite(s.scale) && std::isfinite(s.rotation.w) && std::isfinite(s.rotation.x) &&
                        std::isfinite(s.rotation.y) && std::isfinite(s.rotation.z) && std::isfinite(s.translation.x) &&
                        std::isfinite(s.translation.y) && std::isfinite(s.translation.z);
    if (!finite || !(s.scale > 0.0) || std::abs(glm::length(s.rotation) - 1.0) > 1e-6)
        throw Error::parameter("transform", "must be finite, with a positive scale and a unit rotation");
}

std::shared_ptr<const GeneralizedCylinder> make_shape(Spline3 trajectory, Spline1 a, Spline1 b, Spline1 theta) {
    try {
        return std::make_shared<const GeneralizedCylinder>(std::move(trajectory), std::move(a), std::move(b), std::move(theta));
    } catch (const std::invalid_argument& e) {
        throw Error::parameter("cluster shape", e.what());
    }
}

Spline1 scaled(const Spline1& s, double k) {
    std::vector<double> c = s.control();
    for (double& x : c) x *= k;
    return Spline1(std::move(c));
}

// The angle of `d` (in the normal plane) measured from f.normal toward f.binormal.
double angle_in(const Frame& f, const glm::dvec3& d) { return std::atan2(glm::dot(d, f.binormal), glm::dot(d, f.normal)); }

// g placed by p, as a shape of its own (see the header: θ gains the frames' constant angle).
std::shared_ptr<const GeneralizedCylinder> placed_shape(const GeneralizedCylinder& g, const Similarity& p) {
    std::vector<glm::dvec3> points = g.trajectory().control();
    for (glm::dvec3& x : points) x = p.apply(x);
    const auto moved = make_shape(Spline3(points), scaled(g.a_spline(), p.scale), scaled(g.b_spline(), p.scale), g.theta_spline());
    const double phi = angle_in(moved->frame(0.0), p.apply_direction(g.frame(0.0).normal));
    std::vector<double> theta = g.theta_spline().control();
    for (double& x : theta) x += phi;
    return make_shape(Spline3(std::move(points)), scaled(g.a_spline(), p.scale), scaled(g.b_spline(), p.scale), Spline1(std::move(theta)));
}

// g reflected across x[axis] = at: θ ↦ ψ − θ, and u ↦ −u (the density's business).
std::shared_ptr<const GeneralizedCylinder> mirrored_shape(const GeneralizedCylinder& g, int axis, double at) {
    const auto reflect = [&](glm::dvec3 x) {
        x[axis] = 2.0 * at - x[axis];
        return x;
    };
    std::vector<glm::dvec3> points = g.trajectory().control();
    for (glm::dvec3& x : points) x = reflect(x);
    const auto reflected = make_shape(Spline3(points), g.a_spline(), g.b_spline(), g.theta_spline());
    glm::dvec3 n = g.frame(0.0).normal;
    n[axis] = -n[axis];
    const double psi = angle_in(reflected->frame(0.0), n);
    std::vector<double> theta = g.theta_spline().control();
    for (double& x : theta) x = psi - x;
    return make_shape(Spline3(std::move(points)), g.a_spline(), g.b_spline(), Spline1(std::move(theta)));
}

// A density with the angle around reversed (u ↦ −u): each ring's sectors in reverse order, each grid flipped along s.
std::shared_ptr<const DensitySource> mirrored_density(const DensitySource& d, const DiskLayout& L) {
    auto out = std::make_shared<DensitySource>(d);
    for (StrandRun& run : out->strands)
        for (glm::dvec2& vu : run.vu) vu.y = vu.y > 0.0 ? kTwoPi - vu.y : 0.0;
    if (d.kind == DensitySource::Kind::Grids)
        for (int i = 0; i <= L.s_t; ++i)
            for (int j = 0; j < L.layers; ++j)
                for (int k = 0; k < L.s_u; ++k) {
                    const std::vector<float>& from = d.grids[L.sector_index(i, j, L.s_u - 1 - k)];
                    std::vector<float>& to = out->grids[L.sector_index(i, j, k)];
                    for (int r = 0; r < L.grid_r; ++r)
                        for (int s = 0; s < L.grid_s; ++s)
                            to[static_cast<std::size_t>(r * L.grid_s + s)] = from[static_cast<std::size_t>(r * L.grid_s + (L.grid_s - 1 - s))];
                }
    return out;
}

std::string unique_name(const HairStyle& style, const std::string& base) {
    const auto taken = [&](const std::string& n) {
        return std::any_of(style.clusters.begin(), style.clusters.end(), [&](const Cluster& c) { return c.name == n; });
    };
    if (!taken(base)) return base;
    for (int i = 2;; ++i)
        if (!taken(base + std::to_string(i))) return base + std::to_string(i);
}

// The rows that follow the clusters (bone weights, painted absorption) for a new last cluster: `from`'s.
void append_rows(HairStyle& style, std::size_t from, AbsorptionMap* absorption) {
    if (style.skinning) style.skinning->clusters.push_back(style.skinning->clusters.at(from));
    if (absorption) {
        const std::size_t row = static_cast<std::size_t>(absorption->samples);
        const auto first = absorption->sigma_a.begin() + static_cast<std::ptrdiff_t>(from * row);
        const std::vector<glm::vec3> copy(first, first + static_cast<std::ptrdiff_t>(row));
        absorption->sigma_a.insert(absorption->sigma_a.end(), copy.begin(), copy.end());
        ++absorption->clusters;
    }
}

// A new prototype from `shape` and `density`, with `from`'s rows.
std::size_t append_prototype(HairStyle& style, std::size_t from, const std::string& name, std::shared_ptr<const GeneralizedCylinder> shape,
                             std::shared_ptr<const DensitySource> density, AbsorptionMap* absorption) {
    Cluster c;
    c.name = unique_name(style, name);
    c.shape = std::move(shape);
    c.density = std::move(density);
    c.layers = style.clusters[style.clusters[from].prototype].layers;
    style.clusters.push_back(std::move(c));
    append_rows(style, from, absorption);
    return style.clusters.size() - 1;
}

void check_rows(const HairStyle& style, const AbsorptionMap* absorption) {
    if (absorption && static_cast<std::size_t>(absorption->clusters) != style.clusters.size())
        throw Error::parameter("absorption", "the map has " + std::to_string(absorption->clusters) + " rows for " +
                                                 std::to_string(style.clusters.size()) + " clusters");
}

// The prototype a cluster's geometry edits go to.
std::size_t edited_prototype(const HairStyle& style, std::size_t cluster) {
    check_clusters(style, std::span(&cluster, 1));
    return style.clusters[cluster].prototype;
}

}  // namespace

Similarity similarity_about(const HairStyle& style, std::span<const std::size_t> clusters, const glm::dvec3& translate,
                            const glm::dvec3& rotate_deg, double scale, const glm::dvec3* pivot) {
    check_clusters(style, clusters);
    glm::dvec3 p(0.0);
    if (pivot) p = *pivot;
    else {
        for (const std::size_t c : clusters) p += placed_root(style.clusters[c]);
        if (!clusters.empty()) p /= static_cast<double>(clusters.size());
    }
    Similarity s;
    s.scale = scale;
    s.rotation = glm::angleAxis(radians(rotate_deg.z), glm::dvec3(0, 0, 1)) * glm::angleAxis(radians(rotate_deg.y), glm::dvec3(0, 1, 0)) *
                 glm::angleAxis(radians(rotate_deg.x), glm::dvec3(1, 0, 0));
    s.translation = p - scale * (s.rotation * p) + translate;
    check_similarity(s);
    return s;
}

double roots_middle(const HairStyle& style, int axis) {
    if (axis < 0 || axis > 2) throw Error::parameter("axis", "must be x, y or z");
    double lo = 1e300, hi = -1e300;
    for (const Cluster& c : style.clusters) {
        const double x = placed_root(c)[axis];
        lo = std::min(lo, x), hi = std::max(hi, x);
    }
    return style.clusters.empty() ? 0.0 : 0.5 * (lo + hi);
}

std::size_t find_cluster(const HairStyle& style, const std::string& name) {
    for (std::size_t c = 0; c < style.clusters.size(); ++c)
        if (style.clusters[c].name == name) return c;
    std::string some;
    for (std::size_t c = 0; c < style.clusters.size() && c < 4; ++c) some += (c ? ", " : "") + style.clusters[c].name;
    throw Error::parameter("cluster", "no cluster is named \"" + name + "\" (the style's " + std::to_string(style.clusters.size()) +
                                          " clusters: " + some + (style.clusters.size() > 4 ? ", …" : "") + ")");
}

void transform_clusters(HairStyle& style, std::span<const std::size_t> clusters, const Similarity& s) {
    check_clusters(style, clusters);
    check_similarity(s);
    const Similarity inv = s.inverse();
    for (const std::size_t c : clusters) {  // prototypes: the shape rewritten, their direct instances kept in place
        if (style.clusters[c].instance_of) continue;
        style.clusters[c].shape = placed_shape(*style.clusters[c].shape, s);
        for (Cluster& k : style.clusters)
            if (k.instance_of == c) k.transform = k.transform.after(inv);
    }
    for (const std::size_t c : clusters)
        if (style.clusters[c].instance_of) style.clusters[c].transform = s.after(style.clusters[c].transform);
    style.resolve();
}

std::vector<std::size_t> duplicate_clusters(HairStyle& style, std::span<const std::size_t> clusters, bool as_instances,
                                            const Similarity& s, AbsorptionMap* absorption) {
    check_clusters(style, clusters);
    check_similarity(s);
    check_rows(style, absorption);
    std::vector<std::size_t> out;
    for (const std::size_t c : clusters) {
        const Cluster& from = style.clusters[c];
        if (as_instances) {
            Cluster d;
            d.name = unique_name(style, from.name + "_copy");
            d.instance_of = c;
            d.transform = s;  // its placement: s ∘ the copied cluster's
            style.clusters.push_back(std::move(d));
            append_rows(style, c, absorption);
            out.push_back(style.clusters.size() - 1);
        } else {
            auto shape = placed_shape(*from.shape, s.after(from.placement));
            auto density = std::make_shared<const DensitySource>(*from.density);
            out.push_back(append_prototype(style, c, from.name + "_copy", std::move(shape), std::move(density), absorption));
        }
    }
    style.resolve();
    return out;
}

std::vector<std::size_t> mirror_clusters(HairStyle& style, std::span<const std::size_t> clusters, int axis, double at,
                                         AbsorptionMap* absorption) {
    check_clusters(style, clusters);
    check_rows(style, absorption);
    if (axis < 0 || axis > 2) throw Error::parameter("mirror axis", "must be x, y or z");
    if (!std::isfinite(at)) throw Error::parameter("mirror plane", "must be finite");
    std::vector<std::size_t> out;
    for (const std::size_t c : clusters) {
        const Cluster& from = style.clusters[c];
        const auto placed = from.placement.is_identity() ? from.shape : placed_shape(*from.shape, from.placement);
        out.push_back(append_prototype(style, c, from.name + "_mirror", mirrored_shape(*placed, axis, at),
                                       mirrored_density(*from.density, style.layout_of(c)), absorption));
    }
    style.resolve();
    return out;
}

RootSphere root_sphere(const HairStyle& style) {
    std::vector<glm::dvec3> roots;
    for (const Cluster& c : style.clusters) roots.push_back(placed_root(c));
    RootSphere s;
    if (roots.empty()) return s;
    for (const glm::dvec3& x : roots) s.centre += x / double(roots.size());
    for (const glm::dvec3& x : roots) s.radius = std::max(s.radius, glm::distance(x, s.centre));
    if (roots.size() < 4 || !(s.radius > 0.0)) return s;
    // |x|² = 2 c·x + (r² − |c|²), linear in (c, r² − |c|²): the normal equations, in coordinates about the mean and
    // in units of the spread so that the 4×4 system is well scaled.
    glm::dmat4 ata(0.0);
    glm::dvec4 atb(0.0);
    for (const glm::dvec3& x : roots) {
        const glm::dvec3 y = (x - s.centre) / s.radius;
        const glm::dvec4 row(2.0 * y, 1.0);
        ata += glm::outerProduct(row, row);
        atb += row * glm::dot(y, y);
    }
    if (!(std::abs(glm::determinant(ata)) > 1e-9 * std::pow(double(roots.size()), 4.0))) return s;  // one plane: no sphere
    const glm::dvec4 z = glm::inverse(ata) * atb;
    const double r2 = z.w + glm::dot(glm::dvec3(z), glm::dvec3(z));
    if (!(r2 > 0.0)) return s;
    return {s.centre + s.radius * glm::dvec3(z), s.radius * std::sqrt(r2)};
}

std::size_t add_cluster(HairStyle& style, const NewCluster& n, AbsorptionMap* absorption) {
    check_rows(style, absorption);
    const auto finite = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (!finite(n.root)) throw Error::parameter("root", "must be finite");
    if (!finite(n.down) || glm::length(n.down) == 0.0) throw Error::parameter("down", "must be finite and not zero");
    if (n.direction && (!finite(*n.direction) || glm::length(*n.direction) == 0.0))
        throw Error::parameter("direction", "must be finite and not zero");
    if (!std::isfinite(n.length) || n.length < 0.0) throw Error::parameter("length", "must be finite and ≥ 0 (0: its neighbour's)");
    if (n.name.empty()) throw Error::parameter("name", "must not be empty");
    if (style.clusters.empty()) throw Error::parameter("add", "the style has no cluster to take a profile from");
    std::size_t near = 0;  // the cluster whose root is nearest
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < style.clusters.size(); ++c)
        if (const double d = glm::distance(placed_root(style.clusters[c]), n.root); d < nearest) near = c, nearest = d;
    const Cluster& from = style.clusters[near];
    const double scale = from.placement.scale;
    const glm::dvec3 down = glm::normalize(n.down);
    const RootSphere scalp = root_sphere(style);
    // −z across `normal` (or +x where −z is along it): where a crown's cluster leans.
    const auto back_across = [](const glm::dvec3& normal) {
        glm::dvec3 b = glm::dvec3(0.0, 0.0, -1.0) - glm::dot(glm::dvec3(0.0, 0.0, -1.0), normal) * normal;
        if (glm::length(b) < 0.5) b = glm::dvec3(1.0, 0.0, 0.0) - glm::dot(glm::dvec3(1.0, 0.0, 0.0), normal) * normal;
        return glm::normalize(b);
    };
    glm::dvec3 dir;
    if (n.direction) {
        dir = glm::normalize(*n.direction);
        if (glm::dot(dir, down) < 0.0 && glm::length(glm::cross(dir, down)) < 0.3) dir = glm::normalize(dir + 0.5 * back_across(down));
    } else {
        const glm::dvec3 out = n.root - scalp.centre;
        const glm::dvec3 normal = glm::length(out) > 0.0 ? glm::normalize(out) : -down;  // a root at the centre: up
        glm::dvec3 downhill = down - glm::dot(down, normal) * normal;  // 0 at the crown, 1 on the equator
        downhill += std::max(0.0, 0.3 - glm::length(downhill)) * back_across(normal);
        dir = glm::normalize(downhill);
    }
    const std::size_t count = std::max<std::size_t>(4, style.clusters[from.prototype].shape->trajectory().control().size());
    const double length = n.length > 0.0 ? n.length : scale * from.shape->length();
    const double floor = std::max(scalp.radius, glm::distance(n.root, scalp.centre));
    std::vector<glm::dvec3> points{n.root};
    for (std::size_t i = 0; i + 1 < count; ++i) {
        glm::dvec3 p = points.back() + length / double(count - 1) * glm::normalize(glm::mix(dir, down, double(i) / double(count - 2)));
        const glm::dvec3 off = p - scalp.centre;
        if (glm::length(off) < floor && glm::length(off) > 0.0) p = scalp.centre + floor * glm::normalize(off);
        points.push_back(p);
    }
    const GeneralizedCylinder& g = *from.shape;
    auto shape = make_shape(Spline3(std::move(points)), scaled(g.a_spline(), scale), scaled(g.b_spline(), scale), g.theta_spline());
    auto density = std::make_shared<const DensitySource>(*from.density);
    const std::size_t made = append_prototype(style, near, n.name, std::move(shape), std::move(density), absorption);
    style.resolve();
    return made;
}

std::optional<std::size_t> mirror_partner(const HairStyle& style, std::size_t cluster, int axis, double at, double tolerance) {
    check_clusters(style, std::span(&cluster, 1));
    if (axis < 0 || axis > 2) throw Error::parameter("mirror axis", "must be x, y or z");
    const Cluster& from = style.clusters[cluster];
    std::vector<glm::dvec3> reflected = from.shape->trajectory().control();
    for (glm::dvec3& x : reflected) {
        x = from.placement.apply(x);
        x[axis] = 2.0 * at - x[axis];
    }
    std::optional<std::size_t> best;
    double best_worst = tolerance;
    for (std::size_t k = 0; k < style.clusters.size(); ++k) {
        const Cluster& c = style.clusters[k];
        if (k == cluster || k == from.prototype || c.instance_of) continue;
        const auto& control = c.shape->trajectory().control();
        if (control.size() != reflected.size()) continue;
        double worst = 0;
        for (std::size_t i = 0; i < control.size(); ++i) worst = std::max(worst, glm::distance(control[i], reflected[i]));
        if (worst <= best_worst) best = k, best_worst = worst;
    }
    return best;
}

void mirror_onto(HairStyle& style, std::size_t cluster, std::size_t partner, int axis, double at) {
    check_clusters(style, std::span(&cluster, 1));
    check_clusters(style, std::span(&partner, 1));
    if (axis < 0 || axis > 2) throw Error::parameter("mirror axis", "must be x, y or z");
    if (!std::isfinite(at)) throw Error::parameter("mirror plane", "must be finite");
    const Cluster& from = style.clusters[cluster];
    if (partner == cluster || partner == from.prototype || style.clusters[partner].instance_of)
        throw Error::parameter("mirror", style.clusters[partner].name + " cannot take " + from.name +
                                             "'s mirror image (it is the cluster itself, its prototype, or an instance)");
    const auto placed = from.placement.is_identity() ? from.shape : placed_shape(*from.shape, from.placement);
    style.clusters[partner].shape = mirrored_shape(*placed, axis, at);
    style.resolve();
}

void delete_clusters(HairStyle& style, std::span<const std::size_t> clusters, AbsorptionMap* absorption) {
    check_clusters(style, clusters);
    check_rows(style, absorption);
    const std::size_t n = style.clusters.size();
    std::vector<bool> gone(n, false);
    for (const std::size_t c : clusters) gone[c] = true;
    if (clusters.size() == n) throw Error::parameter("delete", "it would leave the style with no cluster");
    // Every kept cluster that names a removed one is re-pointed past it, in place.
    for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t k = 0; k < n; ++k) {
            Cluster& cl = style.clusters[k];
            if (gone[k] || !cl.instance_of || !gone[*cl.instance_of]) continue;
            const std::size_t d = *cl.instance_of;
            const Cluster& dead = style.clusters[d];
            if (dead.instance_of) {  // past a removed instance: its transform composed into ours
                cl.transform = cl.transform.after(dead.transform);
                cl.instance_of = dead.instance_of;
            } else {  // a removed prototype: this instance takes its shape, placed where it was, and its other instances
                const Similarity was = cl.transform;
                cl.shape = placed_shape(*dead.shape, was);
                cl.density = dead.density;
                cl.layers = dead.layers;
                cl.instance_of.reset();
                cl.transform = {};
                const Similarity inv = was.inverse();
                for (std::size_t m = 0; m < n; ++m)
                    if (m != k && !gone[m] && style.clusters[m].instance_of == d) {
                        style.clusters[m].instance_of = k;
                        style.clusters[m].transform = style.clusters[m].transform.after(inv);
                    }
            }
            changed = true;
        }
    }
    std::vector<std::size_t> index(n, 0);
    std::vector<Cluster> kept;
    std::vector<BoneInfluence> kept_bones;
    std::vector<glm::vec3> kept_rows;
    for (std::size_t c = 0; c < n; ++c) {
        if (gone[c]) continue;
        index[c] = kept.size();
        kept.push_back(std::move(style.clusters[c]));
        if (style.skinning) kept_bones.push_back(style.skinning->clusters.at(c));
        if (absorption)
            for (int i = 0; i < absorption->samples; ++i) kept_rows.push_back(absorption->at(static_cast<int>(c), i));
    }
    for (Cluster& c : kept)
        if (c.instance_of) c.instance_of = index[*c.instance_of];
    style.clusters = std::move(kept);
    if (style.skinning) style.skinning->clusters = std::move(kept_bones);
    if (absorption) {
        absorption->sigma_a = std::move(kept_rows);
        absorption->clusters = static_cast<int>(style.clusters.size());
    }
    style.resolve();
}

void move_control_point(HairStyle& style, std::size_t cluster, std::size_t point, const glm::dvec3& delta) {
    const std::size_t p = edited_prototype(style, cluster);
    const GeneralizedCylinder& g = *style.clusters[p].shape;
    if (point >= g.trajectory().size())
        throw Error::parameter("control point", std::to_string(point) + " is out of range (the trajectory has " +
                                                    std::to_string(g.trajectory().size()) + ")");
    if (!std::isfinite(delta.x) || !std::isfinite(delta.y) || !std::isfinite(delta.z))
        throw Error::parameter("control point", "the move must be finite");
    const Similarity& place = style.clusters[cluster].placement;  // the prototype's coordinates → the cluster's
    std::vector<glm::dvec3> points = g.trajectory().control();
    points[point] += glm::conjugate(place.rotation) * delta / place.scale;
    style.clusters[p].shape = make_shape(Spline3(std::move(points)), g.a_spline(), g.b_spline(), g.theta_spline());
    style.resolve();
}

void set_profile(HairStyle& style, std::size_t cluster, const std::string& profile, std::span<const double> values) {
    const std::size_t p = edited_prototype(style, cluster);
    if (values.empty() || values.size() > kMaxControlPoints)
        throw Error::parameter(profile, "needs 1.." + std::to_string(kMaxControlPoints) + " control points");
    const bool radius = profile == "a" || profile == "b";
    if (!radius && profile != "theta_deg") throw Error::parameter("profile", "\"" + profile + "\" is none of a, b, theta_deg");
    std::vector<double> c(values.begin(), values.end());
    for (double& x : c) {
        if (!std::isfinite(x) || (radius && !(x > 0.0))) throw Error::parameter(profile, radius ? "half-axes must be finite and > 0" : "must be finite");
        if (!radius) x = radians(x);
    }
    const GeneralizedCylinder& g = *style.clusters[p].shape;
    style.clusters[p].shape = make_shape(g.trajectory(), profile == "a" ? Spline1(c) : g.a_spline(), profile == "b" ? Spline1(c) : g.b_spline(),
                                         profile == "theta_deg" ? Spline1(c) : g.theta_spline());
    style.resolve();
}

void set_layers(HairStyle& style, std::size_t cluster, int layers) {
    const std::size_t p = edited_prototype(style, cluster);
    if (layers < 1 || layers > kMaxLayers) throw Error::parameter("layers", "must be 1.." + std::to_string(kMaxLayers));
    if (style.clusters[p].density->kind == DensitySource::Kind::Grids && layers != style.layout_of(p).layers)
        throw Error::parameter("layers", style.clusters[p].name +
                                             "'s density is stored as one grid per sector of its layers; it keeps its layer count");
    style.clusters[p].layers = layers == style.layout.layers ? 0 : layers;
    style.resolve();
}

}  // namespace coif
