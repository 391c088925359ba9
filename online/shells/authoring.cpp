#include "online/shells/authoring.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "models/style_edit.h"
#include "online/shells/shell_pick.h"

namespace coif {
namespace {

// The length of a cluster's placed control polygon: the scale of kSymmetryTolerance.
double control_length(const Cluster& cl) {
    const auto& control = cl.shape->trajectory().control();
    double length = 0;
    for (std::size_t i = 1; i < control.size(); ++i)
        length += glm::distance(cl.placement.apply(control[i]), cl.placement.apply(control[i - 1]));
    return length;
}

}  // namespace

Authoring::Authoring(std::optional<HairStyle> style, std::optional<AbsorptionMap> map) : painting_(std::move(map)) {
    if (style) style_ = std::make_shared<const HairStyle>(std::move(*style));
}

Authoring::Snapshot Authoring::current() const {
    return {style_, painting_.map() ? std::optional<AbsorptionMap>(*painting_.map()) : std::nullopt};
}

void Authoring::restore(Snapshot s) {
    if (s.style != style_) ++style_version_;
    style_ = std::move(s.style);
    painting_.replace(std::move(s.map));
    std::erase_if(selection_, [&](std::size_t c) { return !style_ || c >= style_->clusters.size(); });
}

void Authoring::select(const std::vector<std::string>& names) {
    if (!style_ && !names.empty()) throw Error::parameter("select", "a baked asset is view-only: open its style to edit it");
    std::vector<std::size_t> s;
    for (const std::string& n : names) s.push_back(find_cluster(*style_, n));
    selection_ = std::move(s);
}

bool Authoring::pick(const Camera& camera, const PreparedShells& shells, double x, double y, bool add) {
    glm::vec3 origin, direction;
    camera.ray(static_cast<float>(x), static_cast<float>(y), origin, direction);
    const std::optional<ShellHit> hit = pick_shells(shells, origin, direction);
    if (!add) selection_.clear();
    if (!hit || hit->cluster < 0) return false;
    const std::size_t c = static_cast<std::size_t>(hit->cluster);
    const auto it = std::find(selection_.begin(), selection_.end(), c);
    if (it == selection_.end()) selection_.push_back(c);
    else if (add) selection_.erase(it);
    return true;
}

std::optional<std::size_t> Authoring::symmetric_partner(std::size_t c) const {
    if (!symmetry_ || !style_ || c >= style_->clusters.size()) return std::nullopt;
    return mirror_partner(*style_, c, 0, roots_middle(*style_, 0), kSymmetryTolerance * control_length(style_->clusters[c]));
}

std::vector<std::pair<std::size_t, std::size_t>> Authoring::partners(const std::vector<std::size_t>& cs) const {
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (const std::size_t c : cs)
        if (const std::optional<std::size_t> p = symmetric_partner(c);
            p && std::find(cs.begin(), cs.end(), *p) == cs.end() &&
            std::none_of(pairs.begin(), pairs.end(), [&](const auto& q) { return q.second == *p; }))
            pairs.emplace_back(c, *p);
    return pairs;
}

void Authoring::remove(const std::vector<std::size_t>& cs) {
    std::vector<std::size_t> gone = cs;
    for (const auto& [c, p] : partners(cs)) gone.push_back(p);
    edit([&](HairStyle& s, AbsorptionMap* map) {
        delete_clusters(s, gone, map);
        return std::vector<std::size_t>{};
    });
    selection_.clear();
}

void Authoring::duplicate(const std::vector<std::size_t>& cs, bool as_instances, const glm::dvec3& translate) {
    const std::vector<std::pair<std::size_t, std::size_t>> pairs = partners(cs);
    const double at = style_ ? roots_middle(*style_, 0) : 0.0;  // the plane the partners mirror each other across
    edit([&](HairStyle& s, AbsorptionMap* map) {
        std::vector<std::size_t> made =
            duplicate_clusters(s, cs, as_instances, similarity_about(s, cs, translate, glm::dvec3(0.0), 1.0), map);
        std::vector<std::size_t> paired;  // the copies of the clusters with partners, whose mirror images are made too
        for (const auto& [c, p] : pairs)
            paired.push_back(made[static_cast<std::size_t>(std::find(cs.begin(), cs.end(), c) - cs.begin())]);
        if (!paired.empty()) {
            const std::vector<std::size_t> mirrored = mirror_clusters(s, paired, 0, at, map);
            made.insert(made.end(), mirrored.begin(), mirrored.end());
        }
        return made;
    });
}

void Authoring::add(const Camera& camera, const glm::mat3& orientation, double x, double y) {
    if (!style_) throw Error::parameter("add", "a baked asset is view-only: open its style to edit it");
    glm::vec3 o, d;
    camera.ray(static_cast<float>(x), static_cast<float>(y), o, d);
    const glm::dmat3 to_style = glm::transpose(glm::dmat3(orientation));
    const glm::dvec3 origin = to_style * glm::dvec3(o), dir = glm::normalize(to_style * glm::dvec3(d));
    const RootSphere sphere = root_sphere(*style_);
    // Nearest the eye of |origin + s dir − centre| = radius; a miss: the sphere's point nearest the ray.
    const glm::dvec3 to_centre = sphere.centre - origin;
    const double along = glm::dot(to_centre, dir), gap2 = glm::dot(to_centre, to_centre) - along * along;
    const double r2 = sphere.radius * sphere.radius;
    glm::dvec3 root;
    if (gap2 <= r2 && along - std::sqrt(r2 - gap2) > 0.0) {
        root = origin + (along - std::sqrt(r2 - gap2)) * dir;
    } else {
        const glm::dvec3 nearest = origin + std::max(along, 0.0) * dir - sphere.centre;
        const double n = glm::length(nearest);
        root = sphere.centre + (n > 0.0 ? sphere.radius / n * nearest : glm::dvec3(0.0, sphere.radius, 0.0));
    }
    NewCluster c;
    c.root = root;
    c.down = to_style * glm::dvec3(0.0, -1.0, 0.0);
    const bool symmetric = symmetry_;
    const double at = roots_middle(*style_, 0);
    edit([&](HairStyle& s, AbsorptionMap* map) {
        std::vector<std::size_t> made{add_cluster(s, c, map)};
        if (!symmetric) return made;
        const Cluster& added = s.clusters[made[0]];  // a prototype: its control points are where it is
        double off = 0;  // how far its own mirror image lies from it
        for (const glm::dvec3& x : added.shape->trajectory().control()) off = std::max(off, 2.0 * std::abs(x.x - at));
        if (off > kSymmetryTolerance * control_length(added)) made.push_back(mirror_clusters(s, made, 0, at, map)[0]);
        return made;
    });
}

void Authoring::edit_clusters(const std::vector<std::size_t>& cs, const std::function<void(HairStyle&)>& f) {
    const std::vector<std::pair<std::size_t, std::size_t>> pairs = partners(cs);  // (edited, its partner), before the edit
    const double at = style_ ? roots_middle(*style_, 0) : 0.0;
    edit([&](HairStyle& s, AbsorptionMap*) {
        f(s);
        for (const auto& [c, p] : pairs) mirror_onto(s, c, p, 0, at);
        return cs;
    });
}

void Authoring::edit(const Edit& f) {
    if (!style_) throw Error::parameter("edit", "a baked asset is view-only: open its style to edit it");
    HairStyle style = *style_;
    std::optional<AbsorptionMap> map = painting_.map() ? std::optional<AbsorptionMap>(*painting_.map()) : std::nullopt;
    std::vector<std::size_t> selected = f(style, map ? &*map : nullptr);  // throws: nothing changed
    // What its file holds (models/hair_style.h rounds control points): what is drawn is what is saved.
    style = parse_style(style_text(style), style.name);
    push_step();
    restore({std::make_shared<const HairStyle>(std::move(style)), std::move(map)});
    if (!selected.empty()) selection_ = std::move(selected);
}

void Authoring::drag_point(const Camera& camera, const glm::mat3& orientation, int point, glm::dvec2 from, glm::dvec2 to, int axis) {
    if (!style_) throw Error::parameter("drag", "a baked asset is view-only: open its style to edit it");
    if (selection_.size() != 1) throw Error::parameter("drag", "select one cluster to drag its control points");
    const std::size_t c = selection_[0];
    const Cluster& cl = style_->clusters[c];
    const auto& control = style_->clusters[cl.prototype].shape->trajectory().control();
    if (point < 0 || static_cast<std::size_t>(point) >= control.size())
        throw Error::parameter("drag", "control point " + std::to_string(point) + " of " + cl.name + "'s " +
                                           std::to_string(control.size()));
    // The point in the shells' space, and the plane facing the camera through it.
    const glm::vec3 q = orientation * glm::vec3(cl.placement.apply(control[static_cast<std::size_t>(point)]));
    const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
    const auto on_plane = [&](glm::dvec2 px) {
        glm::vec3 o, d;
        camera.ray(static_cast<float>(px.x), static_cast<float>(px.y), o, d);
        const float along = glm::dot(d, forward);
        if (std::abs(along) < 1e-6f) throw Error::parameter("drag", "the cursor's ray runs along the view plane");
        return o + d * (glm::dot(q - o, forward) / along);
    };
    glm::vec3 delta = on_plane(to) - on_plane(from);
    if (axis >= 0 && axis <= 2) {
        glm::vec3 e(0.0f);
        e[axis] = 1.0f;
        delta = glm::dot(delta, e) * e;
    }
    const glm::dvec3 in_style = glm::dvec3(glm::transpose(orientation) * delta);  // a rotation: its inverse
    edit_cluster(c, [&](HairStyle& s) { move_control_point(s, c, static_cast<std::size_t>(point), in_style); });
}

void Authoring::push_step() {
    undo_.push_back(current());
    redo_.clear();
}

void Authoring::begin_stroke() { push_step(); }

void Authoring::clear_paint() {
    push_step();
    painting_.replace(std::nullopt);
}

bool Authoring::step(std::vector<Snapshot>& from, std::vector<Snapshot>& to) {
    if (from.empty()) return false;
    to.push_back(current());
    restore(std::move(from.back()));
    from.pop_back();
    return true;
}

bool Authoring::undo() { return step(undo_, redo_); }
bool Authoring::redo() { return step(redo_, undo_); }

}  // namespace coif
