#pragma once
// The viewer's cluster authoring, GL-free (issue 20): the style being edited, the clusters selected, the painted
// absorption map, and one undo history for both the paint strokes and the cluster edits (models/style_edit.h). Each
// edit or stroke is one step; undo and redo restore the style and the map exactly as they were (snapshots: a style's
// clusters share their shapes and densities, so a snapshot costs the cluster list). The viewer (online/window/)
// cooks the shells again when style_version() changes.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/core/camera.h"
#include "models/hair_style.h"
#include "online/shells/painting.h"
#include "online/shells/prepared_shells.h"

namespace coif {

class Authoring {
public:
    // `style`: the style drawn (none: a baked asset, view-only: every edit is refused); `map`: painted σa to start from.
    Authoring(std::optional<HairStyle> style, std::optional<AbsorptionMap> map);

    const HairStyle* style() const { return style_.get(); }
    std::uint64_t style_version() const { return style_version_; }  // changes with every edit, undo or redo of the style
    Painting& painting() { return painting_; }
    const AbsorptionMap* map() const { return painting_.map(); }

    const std::vector<std::size_t>& selection() const { return selection_; }
    // By name (coif::Error::parameter naming an unknown one), or the cluster under image pixel (x, y) of `camera`
    // (shells: as drawn; nothing there: none). Returns whether a cluster was picked.
    // With `add`, the picked cluster joins the selection (or leaves it, when it was in it).
    void select(const std::vector<std::string>& names);
    bool pick(const Camera& camera, const PreparedShells& shells, double x, double y, bool add = false);

    // An edit of the style (and of the map's rows), one undo step: `f` gets copies of the style and of the map, and
    // the edited style is then made what its file holds (write_style's rounding), so that the viewer draws what it
    // saves. The
    // selection becomes `f`'s return (empty: kept where still valid). Throws coif::Error::parameter when the drawing is
    // view-only, or what `f` throws (then nothing changed).
    using Edit = std::function<std::vector<std::size_t>(HairStyle&, AbsorptionMap*)>;
    void edit(const Edit& f);
    // An edit of clusters `cs`' shapes or places (a control point, a profile, a transform), one undo step. In symmetry
    // mode, each cluster that was one's mirror image across the head's plane before the edit (x = the middle of the
    // roots, the plane the viewer's mirror uses; models/style_edit.h mirror_partner, within kSymmetryTolerance of its
    // length), and is not itself in `cs`, is made the mirror image of the edited one, in the same step. The selection
    // becomes `cs`.
    void edit_clusters(const std::vector<std::size_t>& cs, const std::function<void(HairStyle&)>& f);
    void edit_cluster(std::size_t c, const std::function<void(HairStyle&)>& f) { edit_clusters({c}, f); }
    // Clusters `cs` removed, one undo step; in symmetry mode each one's mirror partner too. The selection becomes none.
    void remove(const std::vector<std::size_t>& cs);
    // Copies of clusters `cs` moved by `translate` (about their roots' centre), as instances or as new prototypes, one
    // undo step (models/style_edit.h duplicate_clusters); in symmetry mode each copy of a cluster with a mirror partner
    // gets its mirror image beside the partner, so that the style stays symmetric. The copies become the selection.
    void duplicate(const std::vector<std::size_t>& cs, bool as_instances, const glm::dvec3& translate);
    // A cluster added from nothing (models/style_edit.h add_cluster), one undo step: rooted where the ray through image
    // pixel (x, y) of `camera` meets the sphere that fits the roots (root_sphere; the scalp: the hit nearest the eye,
    // or, for a ray that passes by, the sphere's point nearest the ray), leaving it outward and falling along the
    // shells' −y. `orientation` turns the style into the shells' space. In symmetry mode its mirror image across the
    // head's plane is added too, unless it is its own (a cluster on the plane). The new clusters become the selection.
    void add(const Camera& camera, const glm::mat3& orientation, double x, double y);
    void set_symmetry(bool on) { symmetry_ = on; }
    bool symmetry() const { return symmetry_; }
    // The partner a symmetric edit of `c` would change now (none without symmetry mode or without one).
    std::optional<std::size_t> symmetric_partner(std::size_t c) const;
    static constexpr double kSymmetryTolerance = 0.02;  // of the cluster's control polygon's length
    // The selected cluster's trajectory control point `point` dragged from image pixel `from` to `to` of `camera`: in
    // the plane facing the camera through the point (axis −1), or along the shells' axis 0, 1, 2 only. `orientation`
    // turns the style into the shells' space (style_orientation). One undo step; throws unless one cluster is selected.
    void drag_point(const Camera& camera, const glm::mat3& orientation, int point, glm::dvec2 from, glm::dvec2 to, int axis);
    // A paint stroke starts: one undo step (its dabs: painting().dab).
    void begin_stroke();
    // No paint: the parameters' σa again, as a stroke (undoable).
    void clear_paint();
    bool undo();  // false when there is nothing to undo
    bool redo();

private:
    struct Snapshot {
        std::shared_ptr<const HairStyle> style;
        std::optional<AbsorptionMap> map;
    };
    Snapshot current() const;
    // Each of `cs` with its mirror partner (symmetric_partner) when the partner is not in `cs`, each partner once.
    std::vector<std::pair<std::size_t, std::size_t>> partners(const std::vector<std::size_t>& cs) const;
    void restore(Snapshot s);
    void push_step();  // what is now, as the step undo goes back to; the redo steps dropped
    bool step(std::vector<Snapshot>& from, std::vector<Snapshot>& to);  // undo (from undo_ to redo_) or redo
    std::shared_ptr<const HairStyle> style_;
    std::uint64_t style_version_ = 0;
    Painting painting_;
    std::vector<std::size_t> selection_;
    std::vector<Snapshot> undo_, redo_;
    bool symmetry_ = false;
};

}  // namespace coif
