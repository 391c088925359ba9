// Editing a cluster hairstyle (models/style_edit.h): each edit moves the envelopes it is asked to move exactly as the
// similarity or the reflection moves them, and nothing else, and the rows that follow the clusters follow.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <numbers>

#include "models/core/error.h"
#include "models/style_edit.h"

namespace coif {
namespace {

// A curved, twisted prototype with a density grid per sector, an instance of it turned and moved, and a second
// prototype with strand density.
HairStyle style() {
    std::string grids;
    const int sectors = (2 + 1) * 2 * 4;  // (s_t + 1) · layers · s_u
    for (int s = 0; s < sectors; ++s) grids += std::string(s ? ", " : "") + "[" + std::to_string(s) + ", 1, 2, 3, 4, 5]";
    return parse_style(R"({"format": "coif-style", "version": 1,
      "layout": {"core_radius": 0.2, "layers": 2, "s_t": 2, "s_u": 4, "grid": [3, 2], "mesh": [2, 2], "gaussian_width": 0.05},
      "clusters": [
        {"name": "curl", "trajectory": [[0, 0, 0], [1, -3, 0.5], [0.5, -6, 2], [2, -9, 1]], "a": [1.0, 1.4], "b": [0.6, 0.5],
         "theta_deg": [10, 70], "density": {"kind": "grids", "sectors": [)" + grids + R"(]}},
        {"name": "twin", "instance_of": "curl", "transform": {"scale": 0.8, "rotation": [0.9238795, 0, 0.3826834, 0], "translation": [4, 1, 0]}},
        {"name": "plain", "trajectory": [[-3, 0, 0], [-3, -5, 1]], "a": [1.0], "b": [0.7], "theta_deg": [0],
         "density": {"kind": "strands", "strand_weight": 1, "strands": [[0, 0.5, 30, 0.6, 40, 0.7, 50]]}}]})",
                       "<edit>");
}

glm::dvec3 at(const HairStyle& s, std::size_t c, double t, double v, double u) {
    return s.clusters[c].placement.apply(s.clusters[c].shape->point(t, v, u));
}

// The largest distance between cluster c of `a` moved by `f` and cluster d of `b` with u ↦ g(u), over a grid of (t, v, u).
template <class F, class G>
double worst(const HairStyle& a, std::size_t c, const HairStyle& b, std::size_t d, F f, G g) {
    double w = 0;
    for (double t = 0; t <= 1.0; t += 0.125)
        for (double v : {0.3, 1.0})
            for (double u = 0; u < 2 * std::numbers::pi; u += 0.4) w = std::max(w, glm::distance(f(at(a, c, t, v, u)), at(b, d, t, v, g(u))));
    return w;
}
const auto same_u = [](double u) { return u; };
const auto unmoved = [](glm::dvec3 x) { return x; };

Similarity turn() {
    Similarity s;
    s.scale = 1.3;
    s.rotation = glm::angleAxis(0.7, glm::normalize(glm::dvec3(0.3, 1.0, -0.4)));
    s.translation = {2, -1, 3};
    return s;
}

// Rounding only: the shapes' tables are fourth-order accurate in double precision (sizes ~10).
constexpr double kExact = 1e-6;

TEST(StyleEdit, AClustersOwnLayerCountIsItsPrototypesAndTravelsWithItsEdits) {
    HairStyle s = style();
    // "plain" (strand density) takes 3 layered shells; its sectors are of its own layout; the file keeps the count.
    set_layers(s, 2, 3);
    EXPECT_EQ(s.layout_of(2).layers, 3);
    EXPECT_EQ(s.layout_of(0).layers, 2);
    EXPECT_EQ(s.layout_of(1).layers, 2);  // an instance has its prototype's
    EXPECT_EQ(style_counts(s).sectors, 3u * 4u * (2u + 2u + 3u));
    const HairStyle back = parse_style(style_text(s), "<again>");
    EXPECT_EQ(back.layout_of(2).layers, 3);
    EXPECT_EQ(style_text(back), style_text(s));
    // A copy, a mirror image and an instance left behind by a delete keep their prototype's count.
    const std::vector<std::size_t> plain{2};
    EXPECT_EQ(s.layout_of(duplicate_clusters(s, plain, false, Similarity{})[0]).layers, 3);
    EXPECT_EQ(s.layout_of(mirror_clusters(s, plain, 0, 0.0)[0]).layers, 3);
    HairStyle d = style();
    EXPECT_THROW(set_layers(d, 1, 3), Error);  // the instance's edit is its prototype's: "curl" has grids
    EXPECT_EQ(d.layout_of(0).layers, 2);
    // The layout's count: it follows the layout again (not written).
    set_layers(s, 2, 2);
    EXPECT_EQ(s.clusters[2].layers, 0);
    // Refused: out of range; a density stored per sector (its grids are of its count).
    EXPECT_THROW(set_layers(s, 2, 0), Error);
    EXPECT_THROW(set_layers(s, 2, kMaxLayers + 1), Error);
    try {
        set_layers(s, 0, 3);
        ADD_FAILURE() << "a grid density's layer count changed";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("one grid per sector"), std::string::npos) << e.what();
    }
    // In the file: an instance may not have a count of its own, and the count is 1..kMaxLayers.
    const auto with = [](std::size_t cluster, int layers) {
        nlohmann::json j = nlohmann::json::parse(style_text(style()));
        j["clusters"][cluster]["layers"] = layers;
        return parse_style(j.dump(), "<edited>");
    };
    EXPECT_THROW(with(1, 3), Error);
    EXPECT_THROW(with(2, 0), Error);
    EXPECT_THROW(with(2, kMaxLayers + 1), Error);
    EXPECT_EQ(with(2, 5).layout_of(2).layers, 5);
}

TEST(StyleEdit, TransformMovesAPrototypeOrAnInstanceByTheSimilarityAndNothingElse) {
    const HairStyle before = style();
    const Similarity s = turn();
    const auto moved = [&](glm::dvec3 x) { return s.apply(x); };
    HairStyle a = before;
    const std::size_t curl = 0;
    transform_clusters(a, std::span(&curl, 1), s);
    EXPECT_LT(worst(before, 0, a, 0, moved, same_u), kExact);
    EXPECT_LT(worst(before, 1, a, 1, unmoved, same_u), kExact);  // its instance stays
    EXPECT_LT(worst(before, 2, a, 2, unmoved, same_u), kExact);
    HairStyle b = before;
    const std::size_t both[] = {0, 1};
    transform_clusters(b, both, s);
    EXPECT_LT(worst(before, 0, b, 0, moved, same_u), kExact);
    EXPECT_LT(worst(before, 1, b, 1, moved, same_u), kExact);
    HairStyle c = before;
    const std::size_t twin = 1;
    transform_clusters(c, std::span(&twin, 1), s);
    EXPECT_LT(worst(before, 1, c, 1, moved, same_u), kExact);
    EXPECT_LT(worst(before, 0, c, 0, unmoved, same_u), kExact);
    // The edited style is a valid file.
    EXPECT_NO_THROW(parse_style(style_to_json(b).dump(), "<edited>"));
    Similarity bad;
    bad.scale = -1;
    EXPECT_THROW(transform_clusters(c, std::span(&twin, 1), bad), Error);
    const std::size_t twice[] = {1, 1};
    EXPECT_THROW(transform_clusters(c, twice, s), Error);
}

TEST(StyleEdit, MirrorMakesTheReflectedEnvelopeWithItsDensityReversedAround) {
    const HairStyle before = style();
    AbsorptionMap paint(3, 4, glm::vec3(1.0f));
    paint.at(1, 2) = glm::vec3(7.0f);
    HairStyle m = before;
    const std::size_t which[] = {0, 1, 2};
    const std::vector<std::size_t> made = mirror_clusters(m, which, 0, 0.5, &paint);
    ASSERT_EQ(made, (std::vector<std::size_t>{3, 4, 5}));
    const auto reflect = [](glm::dvec3 x) { return glm::dvec3(1.0 - x.x, x.y, x.z); };
    const auto reverse = [](double u) { return 2 * std::numbers::pi - u; };
    for (std::size_t k = 0; k < 3; ++k) EXPECT_LT(worst(before, k, m, made[k], reflect, reverse), kExact) << k;
    EXPECT_EQ(m.clusters[3].name, "curl_mirror");
    EXPECT_FALSE(m.clusters[4].instance_of);  // a reflection is no similarity: a prototype of its own
    // Ring (i, j)'s sectors in reverse order, each grid reversed along s: sector 0's grid [0, 1, 2 | 3, 4, 5] is the
    // mirror's sector 3's [2, 1, 0 | 5, 4, 3].
    const DiskLayout& L = m.layout;
    const std::vector<float>& g = m.clusters[3].density->grids[L.sector_index(0, 0, L.s_u - 1)];
    EXPECT_EQ(g, (std::vector<float>{2, 1, 0, 5, 4, 3}));
    EXPECT_NEAR(m.clusters[5].density->strands[0].vu[0].y, 2 * std::numbers::pi - 30 * std::numbers::pi / 180, 1e-9);
    // The painted rows follow.
    ASSERT_EQ(paint.clusters, 6);
    EXPECT_EQ(paint.at(4, 2), glm::vec3(7.0f));
    EXPECT_NO_THROW(parse_style(style_to_json(m).dump(), "<mirrored>"));
}

TEST(StyleEdit, AMirrorPartnerIsFoundAndTakesTheEditedClustersMirrorImage) {
    // The viewer's symmetry mode: each cluster and its mirror find each other; an edit of one, followed by mirror_onto,
    // leaves the other the exact mirror image of the edited one (the envelope at kExact, as mirror_clusters makes it).
    HairStyle m = style();
    const std::size_t which[] = {0, 1, 2};
    const std::vector<std::size_t> made = mirror_clusters(m, which, 0, 0.5);  // curl_mirror 3, twin_mirror 4, plain_mirror 5
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(mirror_partner(m, k, 0, 0.5, 1e-6), made[k]) << k;
        // A mirror is a prototype; its partner can be an instance (twin) only as the edited side, never as the partner.
        EXPECT_EQ(mirror_partner(m, made[k], 0, 0.5, 1e-6), k == 1 ? std::optional<std::size_t>{} : std::optional(k)) << k;
    }
    EXPECT_EQ(mirror_partner(m, 0, 0, 0.9, 1e-3), std::nullopt);  // another plane: no partner within the tolerance
    // Edit curl (control point 2 moved), then make its partner the mirror of the edited curl.
    move_control_point(m, 0, 2, glm::dvec3(0.4, -0.3, 0.2));
    mirror_onto(m, 0, made[0], 0, 0.5);
    const auto reflect = [](glm::dvec3 x) { return glm::dvec3(1.0 - x.x, x.y, x.z); };
    const auto reverse = [](double u) { return 2 * std::numbers::pi - u; };
    EXPECT_LT(worst(m, 0, m, made[0], reflect, reverse), kExact);
    EXPECT_EQ(mirror_partner(m, 0, 0, 0.5, 1e-6), made[0]);  // still each other's
    // Refused: the cluster itself, its own prototype (twin is curl's instance), and an instance as the partner.
    EXPECT_THROW(mirror_onto(m, 0, 0, 0, 0.5), Error);
    EXPECT_THROW(mirror_onto(m, 1, 0, 0, 0.5), Error);
    EXPECT_THROW(mirror_onto(m, 3, 1, 0, 0.5), Error);
}

TEST(StyleEdit, DuplicatesAreMovedCopiesAsInstancesOrPrototypes) {
    const HairStyle before = style();
    const Similarity s = turn();
    const auto moved = [&](glm::dvec3 x) { return s.apply(x); };
    for (const bool instances : {true, false}) {
        HairStyle d = before;
        AbsorptionMap paint(3, 2, glm::vec3(1.0f));
        paint.at(1, 1) = glm::vec3(3.0f);
        const std::size_t which[] = {1, 2};
        const std::vector<std::size_t> made = duplicate_clusters(d, which, instances, s, &paint);
        ASSERT_EQ(made.size(), 2u);
        EXPECT_LT(worst(before, 1, d, made[0], moved, same_u), kExact) << instances;
        EXPECT_LT(worst(before, 2, d, made[1], moved, same_u), kExact) << instances;
        EXPECT_LT(worst(before, 1, d, 1, unmoved, same_u), kExact);
        EXPECT_EQ(d.clusters[made[0]].name, "twin_copy");
        EXPECT_EQ(d.clusters[made[0]].instance_of.has_value(), instances);
        EXPECT_EQ(paint.at(static_cast<int>(made[0]), 1), glm::vec3(3.0f));
        EXPECT_NO_THROW(parse_style(style_to_json(d).dump(), "<duplicated>"));
    }
}

// Roots on a known sphere: centre (1, 2, 3), radius 5, at polar angles up to 80° from +y; each cluster hangs down.
// Cluster "small" is an instance at half size of the first, placed so its root is on the sphere too.
HairStyle scalp_style() {
    nlohmann::json doc = {{"format", "coif-style"}, {"version", 1},
                          {"layout", {{"core_radius", 0.2}, {"layers", 2}, {"s_t", 2}, {"s_u", 4}, {"grid", {3, 2}}, {"mesh", {2, 2}}, {"gaussian_width", 0.05}}}};
    nlohmann::json clusters = nlohmann::json::array();
    const glm::dvec3 centre(1, 2, 3);
    int k = 0;
    for (const double polar : {0.3, 0.8, 1.4})
        for (const double around : {0.0, 2.1, 4.2}) {
            const glm::dvec3 r = centre + 5.0 * glm::dvec3(std::sin(polar) * std::cos(around), std::cos(polar), std::sin(polar) * std::sin(around));
            std::string name = "c";  // (not "c" + …: GCC 12's -Wrestrict false positive)
            name += std::to_string(k++);
            clusters.push_back({{"name", name},
                                {"trajectory", {{r.x, r.y, r.z}, {r.x, r.y - 4, r.z}, {r.x, r.y - 8, r.z + 1}}},
                                {"a", {0.8, 0.6}}, {"b", {0.5}}, {"theta_deg", {20}},
                                {"density", {{"kind", "strands"}, {"strand_weight", 2}, {"strands", {{0, 0.5, 30, 0.6, 40}}}}}});
        }
    // c0's root r0 placed at centre + 5 (0, 0, −1) by scale ½: x ↦ ½ x + t.
    const glm::dvec3 r0 = centre + 5.0 * glm::dvec3(std::sin(0.3), std::cos(0.3), 0.0), want = centre + glm::dvec3(0, 0, -5);
    const glm::dvec3 t = want - 0.5 * r0;
    clusters.push_back({{"name", "small"}, {"instance_of", "c0"},
                        {"transform", {{"scale", 0.5}, {"rotation", {1, 0, 0, 0}}, {"translation", {t.x, t.y, t.z}}}}});
    doc["clusters"] = clusters;
    return style_from_json(doc, "<scalp>");
}

TEST(StyleEdit, AClusterAddedFromNothingDrapesOverTheScalpAndTakesItsNeighboursLook) {
    HairStyle s = scalp_style();
    const RootSphere scalp = root_sphere(s);
    EXPECT_LT(glm::distance(scalp.centre, glm::dvec3(1, 2, 3)), 1e-9);  // exact roots: the fit is exact to rounding
    EXPECT_NEAR(scalp.radius, 5.0, 1e-9);
    // Beside "small" (the instance at half size, root at the sphere's −z): its look at its size, its rows.
    AbsorptionMap paint(static_cast<int>(s.clusters.size()), 3, glm::vec3(1.0f));
    paint.at(9, 2) = glm::vec3(7.0f);
    NewCluster n;
    n.root = glm::dvec3(1, 2, 3) + 5.0 * glm::normalize(glm::dvec3(0.3, 0.5, -1.0));
    const std::size_t c = add_cluster(s, n, &paint);
    ASSERT_EQ(c, 10u);
    const Cluster& added = s.clusters[c];
    EXPECT_EQ(added.name, "added");
    EXPECT_FALSE(added.instance_of.has_value());
    EXPECT_EQ(paint.clusters, 11);
    EXPECT_EQ(paint.at(10, 2), glm::vec3(7.0f));
    EXPECT_NEAR(added.shape->a(0.0), 0.4, 1e-12);  // c0's A(0) = 0.8 at "small"'s scale ½
    EXPECT_NEAR(added.shape->b(1.0), 0.25, 1e-12);
    ASSERT_EQ(added.density->strands.size(), 1u);
    EXPECT_EQ(added.density->strand_weight, 2.0);
    const std::vector<glm::dvec3>& p = added.shape->trajectory().control();
    ASSERT_EQ(p.size(), 4u);  // the neighbour's 3 control points, at least 4
    EXPECT_EQ(p[0], n.root);
    // It leaves along the scalp (tangent, downhill), never goes inside it, and its last segment falls straight down.
    const glm::dvec3 normal = glm::normalize(n.root - glm::dvec3(1, 2, 3));
    EXPECT_NEAR(glm::dot(glm::normalize(p[1] - p[0]), normal), 0.0, 0.02);  // the next point put back onto the sphere
    EXPECT_LT((p[1] - p[0]).y, 0.0);
    for (const glm::dvec3& x : p) EXPECT_GE(glm::distance(x, glm::dvec3(1, 2, 3)), 5.0 - 1e-9);
    const glm::dvec3 last = glm::normalize(p[3] - p[2]);
    EXPECT_LT(glm::distance(last, glm::dvec3(0, -1, 0)), 1e-12);
    EXPECT_NO_THROW(parse_style(style_to_json(s).dump(), "<added>"));

    // At the crown it leans toward −z; a second one there is named apart.
    NewCluster crown;
    crown.root = glm::dvec3(1, 7, 3);
    const std::size_t k = add_cluster(s, crown);
    EXPECT_EQ(s.clusters[k].name, "added2");
    const glm::dvec3 first = s.clusters[k].shape->trajectory().control()[1] - crown.root;
    EXPECT_LT(first.z, -0.9 * glm::length(first));
    for (const glm::dvec3& x : s.clusters[k].shape->trajectory().control())  // where it bends down it would go inside
        EXPECT_GE(glm::distance(x, glm::dvec3(1, 2, 3)), 5.0 - 1e-9);
    // A given direction on the equator straight down: the path is that line, of the given length.
    NewCluster hang;
    hang.root = glm::dvec3(6, 2, 3);
    hang.direction = glm::dvec3(0, -2, 0);
    hang.length = 9.0;
    const auto& q = s.clusters[add_cluster(s, hang)].shape->trajectory().control();
    EXPECT_LT(glm::distance(q.back(), glm::dvec3(6, -7, 3)), 1e-12);

    // Refused, the style unchanged: a root or a direction not finite, a zero direction or down, a negative length, no
    // name, a map with other rows.
    const std::string before = style_text(s);
    const auto refused = [&](NewCluster bad, AbsorptionMap* map = nullptr) { EXPECT_THROW((void)add_cluster(s, bad, map), Error); };
    NewCluster bad = n;
    bad.root.x = std::nan("");
    refused(bad);
    bad = n, bad.direction = glm::dvec3(0.0);
    refused(bad);
    bad = n, bad.direction = glm::dvec3(1.0, INFINITY, 0.0);
    refused(bad);
    bad = n, bad.down = glm::dvec3(0.0);
    refused(bad);
    bad = n, bad.length = -1.0;
    refused(bad);
    bad = n, bad.name.clear();
    refused(bad);
    refused(n, &paint);  // 11 rows for 13 clusters
    EXPECT_EQ(style_text(s), before);

    // Fewer than four roots: no sphere; the roots' mean and their largest distance from it.
    HairStyle two = scalp_style();
    two.clusters.resize(2);
    two.resolve();
    const RootSphere few = root_sphere(two);
    const glm::dvec3 r0 = two.clusters[0].shape->position(0.0), r1 = two.clusters[1].shape->position(0.0);
    EXPECT_LT(glm::distance(few.centre, 0.5 * (r0 + r1)), 1e-12);
    EXPECT_NEAR(few.radius, 0.5 * glm::distance(r0, r1), 1e-12);
}

TEST(StyleEdit, DeletingKeepsEveryOtherClusterWhereItWas) {
    const HairStyle before = style();
    HairStyle d = before;
    AbsorptionMap paint(3, 2, glm::vec3(1.0f));
    paint.at(2, 0) = glm::vec3(5.0f);
    const std::size_t curl = 0;
    delete_clusters(d, std::span(&curl, 1), &paint);  // the prototype of "twin": twin takes its shape, in place
    ASSERT_EQ(d.clusters.size(), 2u);
    EXPECT_EQ(d.clusters[0].name, "twin");
    EXPECT_FALSE(d.clusters[0].instance_of);
    EXPECT_LT(worst(before, 1, d, 0, unmoved, same_u), kExact);
    EXPECT_LT(worst(before, 2, d, 1, unmoved, same_u), kExact);
    EXPECT_EQ(paint.clusters, 2);
    EXPECT_EQ(paint.at(1, 0), glm::vec3(5.0f));
    EXPECT_NO_THROW(parse_style(style_to_json(d).dump(), "<deleted>"));
    const std::size_t all[] = {0, 1};
    EXPECT_THROW(delete_clusters(d, all), Error);
}

TEST(StyleEdit, ControlPointsAndProfilesEditThePrototype) {
    HairStyle e = style();
    const glm::dvec3 root = at(e, 1, 0, 0, 0);
    // The instance's root control point moved by (0, 0, 1) in the style's space: the instance's root moves so.
    move_control_point(e, 1, 0, {0, 0, 1});
    EXPECT_LT(glm::distance(at(e, 1, 0, 0, 0), root + glm::dvec3(0, 0, 1)), 1e-9);
    const double b[] = {0.9, 0.8, 0.7};
    set_profile(e, 0, "b", b);
    EXPECT_NEAR(e.clusters[1].shape->b(1.0), 0.7, 1e-12);  // shared by the instance
    const double nan[] = {std::nan("")};
    EXPECT_THROW(set_profile(e, 0, "a", nan), Error);
    EXPECT_THROW(set_profile(e, 0, "c", b), Error);
    EXPECT_THROW(move_control_point(e, 0, 9, {0, 0, 1}), Error);
    EXPECT_EQ(find_cluster(e, "plain"), 2u);
    EXPECT_THROW((void)find_cluster(e, "none"), Error);
}

}  // namespace
}  // namespace coif
