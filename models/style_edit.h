#pragma once
// Editing a cluster hairstyle: the edits of `coif style transform|mirror|duplicate|delete|set` and of the viewer's
// cluster authoring (issue 20), GL-free. Every edit leaves the style valid and resolved (HairStyle::resolve), moves
// nothing it was not asked to move, and keeps the rows that follow the clusters in step: the painted absorption map's
// (models/absorption_map.h, one row per cluster) and the bone weights' (HairStyle::skinning).
//
// Exactness. A cluster's envelope is its shape (models/generalized_cylinder.h) placed by its similarity. An instance
// moves by composing its transform. A prototype's shape is rewritten: its trajectory's and radii's control points go
// through the similarity, and its twist θ gains the constant angle by which the new rotation-minimizing frame differs
// from the turned old one (parallel transport commutes with rotations, so that angle is the same all along t), so the
// new envelope is the old one placed by the similarity to rounding; its instances keep their places (their transforms
// take the inverse). A mirror image is a new prototype: the reflection keeps rotation-minimizing frames but reverses
// their handedness, so θ becomes ψ − θ (ψ: where the reflected frame lies in the new one) and the angle around, u,
// becomes −u, which reverses each ring's sectors and their density grids along s. `models.StyleEdit.*` checks every
// edit's envelope against the similarity or reflection applied to the old one.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "models/absorption_map.h"
#include "models/hair_style.h"
#include "models/similarity.h"

namespace coif {

// Moves `clusters` (indices, each once) by `s` in the style's space. Throws coif::Error::parameter for an index out
// of range, a repeated one, or a similarity that is not finite with a positive scale.
void transform_clusters(HairStyle& style, std::span<const std::size_t> clusters, const Similarity& s);

// Copies of `clusters`, appended in their order and moved by `s`: as instances of the cluster copied (they share its
// geometry and density: the SATF's macro-clusters), or as new prototypes with their own. Names get "_copy" (then a
// number) until unique. Returns the new clusters' indices; `absorption`, if given, gets their rows copied.
std::vector<std::size_t> duplicate_clusters(HairStyle& style, std::span<const std::size_t> clusters, bool as_instances,
                                            const Similarity& s, AbsorptionMap* absorption = nullptr);

// Mirror images of `clusters` across the plane x[axis] = at (axis 0, 1, 2: x, y, z), appended as new prototypes named
// "_mirror" (the bone weights copied: a character's left and right bones are not known here). Returns their indices.
std::vector<std::size_t> mirror_clusters(HairStyle& style, std::span<const std::size_t> clusters, int axis, double at,
                                         AbsorptionMap* absorption = nullptr);

// The sphere that best fits the clusters' roots (least squares): the scalp as the style knows it. It is where the
// viewer plants a cluster added under the cursor, and the way a new cluster leaves its root. With fewer than four
// roots, or roots on one plane or line (no sphere through them), the centre is the roots' mean and the radius their
// largest distance from it.
struct RootSphere {
    glm::dvec3 centre{0.0};
    double radius = 0.0;
};
RootSphere root_sphere(const HairStyle& style);

// A cluster added from nothing (add_cluster): a new prototype rooted at `root` (style space) that leaves it along
// `direction` and bends toward `down`, as hair falls, draped over the scalp (root_sphere).
struct NewCluster {
    glm::dvec3 root{0.0};
    std::optional<glm::dvec3> direction;  // none: out of the scalp and down it (below)
    double length = 0.0;                  // the trajectory's control polygon's length before draping; 0: its neighbour's
    glm::dvec3 down{0.0, -1.0, 0.0};      // gravity in the style's space (the style's −y when it is y-up)
    std::string name = "added";           // made unique with a number
};
// Appends the new cluster and returns its index. Its trajectory has as many control points as its neighbour's (the
// cluster whose root is nearest `root`; at least 4), n − 1 segments of equal length: segment i along
// mix(d₀, down, i/(n−2)), so that the path leaves along d₀ and its last segment falls straight down. d₀ is
// `direction`, or by default the scalp's unit downhill tangent (down without its share along the scalp's normal): it
// leaves along the scalp (a path leaving 14° or 27° out of it stood off the fitted clusters). At the crown, where the downhill tangent is short or none, it leans toward −z (the
// back of a head whose face looks along +z, models/generalized_cylinder.h); so does a `direction` within 17° of up. Each point after the root that falls inside the scalp
// sphere (grown to the root when the root lies outside it) is put back onto it: the cluster drapes over the head. From the neighbour it takes what is not its path: its A, B and θ profiles (in world
// units), a copy of its density, its layer count, and its rows (bone weights, painted absorption), so that a cluster
// added among others looks and moves like them. Throws coif::Error::parameter for a root, direction or length that is
// not finite, a zero direction or down, a negative length, or an empty name.
std::size_t add_cluster(HairStyle& style, const NewCluster& cluster, AbsorptionMap* absorption = nullptr);

// The cluster that is `cluster`'s mirror image across x[axis] = at (the viewer's symmetry mode): a prototype of its own
// (not an instance, not `cluster`'s prototype) whose trajectory has as many control points, each within `tolerance`
// (style units) of `cluster`'s placed one reflected; the nearest such, or none.
std::optional<std::size_t> mirror_partner(const HairStyle& style, std::size_t cluster, int axis, double at, double tolerance);
// `partner`'s shape made the mirror image of `cluster`'s placed shape across x[axis] = at, as mirror_clusters makes it
// (its name, density and instances kept): the symmetric side of an edit of `cluster`. Throws coif::Error::parameter
// for a partner that is an instance, `cluster` itself or `cluster`'s prototype.
void mirror_onto(HairStyle& style, std::size_t cluster, std::size_t partner, int axis, double at);

// Removes `clusters`. An instance of a removed cluster keeps its place: it is re-pointed past it, and where a removed
// prototype leaves instances the first of them becomes the prototype (its shape rewritten in place, exactly as
// above). Throws coif::Error::parameter if nothing would remain.
void delete_clusters(HairStyle& style, std::span<const std::size_t> clusters, AbsorptionMap* absorption = nullptr);

// The cluster's trajectory control point `point` moved by `delta` in the style's space (an instance's: its
// prototype's, through its placement, so every instance of that prototype changes with it).
void move_control_point(HairStyle& style, std::size_t cluster, std::size_t point, const glm::dvec3& delta);

// A cluster's profile replaced: "a", "b" (half-axes, > 0, in the prototype's units) or "theta_deg" (degrees); an
// instance's edits its prototype's. Throws coif::Error::parameter for an unknown profile, no value, more than
// kMaxControlPoints, or values that are not finite (or not positive radii).
void set_profile(HairStyle& style, std::size_t cluster, const std::string& profile, std::span<const double> values);
// A cluster's own number of layered shells (an instance's: its prototype's), 1..kMaxLayers; the layout's count makes it
// follow the layout again. Its sectors are of its own layout from then on (HairStyle::layout_of); a density stored as
// member strands or uniform serves any count. Throws coif::Error::parameter outside the range, or for a density stored
// per sector (kind grids), which is of its layer count.
void set_layers(HairStyle& style, std::size_t cluster, int layers);

// The motion of `coif style transform` and the viewer's: turn by `rotate_deg` (about x, then y, then z), scale by
// `scale`, both about `pivot` (null: the centre of `clusters`' roots), then translate. Throws coif::Error::parameter
// for values that are not finite or a scale ≤ 0.
Similarity similarity_about(const HairStyle& style, std::span<const std::size_t> clusters, const glm::dvec3& translate,
                            const glm::dvec3& rotate_deg, double scale, const glm::dvec3* pivot = nullptr);
// The middle of all the clusters' roots along `axis`: the default mirror plane (the head's left-right plane for x).
double roots_middle(const HairStyle& style, int axis);

// The cluster named `name`, or coif::Error::parameter naming it and what the style holds.
std::size_t find_cluster(const HairStyle& style, const std::string& name);

}  // namespace coif
