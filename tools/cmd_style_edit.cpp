// `coif style transform | mirror | duplicate | add | delete | set`: the viewer's cluster edits without a window
// (models/style_edit.h), each reading a style and writing the edited one, with the painted absorption map's rows
// following the clusters when one is given.
#include <cstdio>
#include <memory>
#include <optional>

#include "models/absorption_map.h"
#include "models/core/error.h"
#include "models/hair_style.h"
#include "models/style_edit.h"
#include "online/shells/prepared_shells.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace fs = std::filesystem;

namespace {

// What every edit reads and writes.
struct EditIo {
    std::string style, out, absorption, absorption_out;
    std::vector<std::string> clusters;
};

void add_io(CLI::App* app, EditIo& io, bool selection) {
    app->add_option("style", io.style, "Style file (JSON), or @default")->required();
    app->add_option("-o,--output", io.out, "The edited style to write (JSON, atomically)")->required();
    if (selection)
        app->add_option("--clusters", io.clusters, "The clusters to edit, by name (coif style inspect lists them), or 'all'")
            ->required()->expected(1, 1 << 20);
    app->add_option("--absorption", io.absorption,
                    "A painted absorption map of the style (coif style paint-absorption, the viewer's brush): its rows follow the\n"
                    "clusters (copied with a copy, removed with a cluster) into --absorption-out")
        ->check(CLI::ExistingFile);
    app->add_option("--absorption-out", io.absorption_out, "Where the edited absorption map goes (.exr, atomically)");
}

struct Loaded {
    coif::HairStyle style;
    std::optional<coif::AbsorptionMap> absorption;
    std::vector<std::size_t> selection;
};

Loaded load(const EditIo& io) {
    if (io.absorption.empty() != io.absorption_out.empty())
        throw coif::Error::parameter("--absorption", "--absorption and --absorption-out go together");
    if (!io.absorption_out.empty() && fs::path(io.absorption_out).extension() != ".exr")
        throw coif::Error(io.absorption_out, "", "the absorption map must be a .exr file");
    coif::cli::lock_output(io.out);
    if (!io.absorption_out.empty()) coif::cli::lock_output(io.absorption_out);
    Loaded l{coif::cli::load_style(io.style), std::nullopt, {}};
    if (!io.absorption.empty()) l.absorption = coif::read_absorption_map(io.absorption, l.style.clusters.size());
    if (io.clusters.size() == 1 && io.clusters[0] == "all")
        for (std::size_t c = 0; c < l.style.clusters.size(); ++c) l.selection.push_back(c);
    else
        for (const std::string& name : io.clusters) l.selection.push_back(coif::find_cluster(l.style, name));
    return l;
}

// Both files, the style last (so that a failure leaves no edited style without its map).
void save(const EditIo& io, const Loaded& l, const std::string& what) {
    if (l.absorption) coif::write_absorption_map(io.absorption_out, *l.absorption);
    coif::write_style(io.out, l.style);
    std::fprintf(stderr, "%s; wrote %s (%zu clusters)%s\n", what.c_str(), io.out.c_str(), l.style.clusters.size(),
                 l.absorption ? (" and " + io.absorption_out).c_str() : "");
}

// --translate, --rotate-deg (x, then y, then z, about --about or the selection's roots' centre) and --scale.
struct Motion {
    std::vector<double> translate{0, 0, 0}, rotate_deg{0, 0, 0}, about;
    double scale = 1.0;
};

void add_motion(CLI::App* app, Motion& m) {
    app->add_option("--translate", m.translate, "Move by X Y Z (the style's units)")->expected(3);
    app->add_option("--rotate-deg", m.rotate_deg, "Turn by X Y Z degrees about x, then y, then z")->expected(3);
    app->add_option("--scale", m.scale, "Scale by S (> 0)")->capture_default_str()->check(CLI::PositiveNumber);
    app->add_option("--about", m.about, "The point the turn and the scale keep (default: the centre of the clusters' roots)")->expected(3);
}

coif::Similarity similarity(const Motion& m, const coif::HairStyle& style, const std::vector<std::size_t>& selection) {
    const glm::dvec3 pivot = m.about.size() == 3 ? glm::dvec3(m.about[0], m.about[1], m.about[2]) : glm::dvec3(0.0);
    return coif::similarity_about(style, selection, {m.translate[0], m.translate[1], m.translate[2]},
                                  {m.rotate_deg[0], m.rotate_deg[1], m.rotate_deg[2]}, m.scale, m.about.size() == 3 ? &pivot : nullptr);
}

void add_style_edits(CLI::App& root) {
    CLI::App* style = coif::cli::noun(root, "style", "");
    const std::string rows = "\nWith --absorption MAP --absorption-out OUT the painted map's rows follow the clusters.";

    auto to = std::make_shared<EditIo>();
    auto tm = std::make_shared<Motion>();
    CLI::App* transform = style->add_subcommand(
        "transform",
        "Move clusters: turn, scale and translate them, exactly (models/style_edit.h). An instance's transform takes\n"
        "the motion; a prototype's shape is rewritten and its instances keep their places." + rows);
    add_io(transform, *to, true);
    add_motion(transform, *tm);
    coif::cli::examples(transform, "  coif style transform @default --clusters c3 c4 --rotate-deg 0 15 0 -o turned.json\n"
                                   "  coif style transform h64.json --clusters all --translate 0 2 0 --scale 1.1 -o bigger.json");
    transform->callback([to, tm] {
        Loaded l = load(*to);
        coif::transform_clusters(l.style, l.selection, similarity(*tm, l.style, l.selection));
        save(*to, l, "moved " + std::to_string(l.selection.size()) + " clusters");
    });

    auto mo = std::make_shared<EditIo>();
    auto axis = std::make_shared<std::string>("x");
    auto at = std::make_shared<std::optional<double>>();
    CLI::App* mirror = style->add_subcommand(
        "mirror",
        "Add the mirror images of clusters across a plane (x = AT by default: the head's left-right plane), as new\n"
        "clusters named NAME_mirror, each a prototype of its own with its density reversed around." + rows);
    add_io(mirror, *mo, true);
    mirror->add_option("--axis", *axis, "The plane's normal: x, y or z")->capture_default_str()->check(CLI::IsMember({"x", "y", "z"}));
    mirror->add_option("--at", *at, "Where the plane crosses the axis (default: the middle of the roots of every cluster)");
    coif::cli::examples(mirror, "  coif style mirror h64.json --clusters c7 c8 -o both_sides.json");
    mirror->callback([mo, axis, at] {
        Loaded l = load(*mo);
        const int a = (*axis)[0] - 'x';
        const double plane = *at ? **at : coif::roots_middle(l.style, a);
        const auto made = coif::mirror_clusters(l.style, l.selection, a, plane, l.absorption ? &*l.absorption : nullptr);
        char what[96];
        std::snprintf(what, sizeof what, "mirrored %zu clusters across %s = %.6g", made.size(), axis->c_str(), plane);
        save(*mo, l, what);
    });

    auto dO = std::make_shared<EditIo>();
    auto dm = std::make_shared<Motion>();
    auto as_copy = std::make_shared<bool>(false);
    CLI::App* duplicate = style->add_subcommand(
        "duplicate",
        "Add copies of clusters, moved by the motion options (as transform's), named NAME_copy: instances of the\n"
        "copied clusters (they share geometry and density, the SATF's macro-clusters), or with --as-copy prototypes\n"
        "with their own." + rows);
    add_io(duplicate, *dO, true);
    add_motion(duplicate, *dm);
    duplicate->add_flag("--as-copy", *as_copy, "Copy the geometry and density instead of sharing them");
    coif::cli::examples(duplicate, "  coif style duplicate @default --clusters c3 --translate 0 0 1.5 -o more.json");
    duplicate->callback([dO, dm, as_copy] {
        Loaded l = load(*dO);
        const auto made = coif::duplicate_clusters(l.style, l.selection, !*as_copy, similarity(*dm, l.style, l.selection),
                                                   l.absorption ? &*l.absorption : nullptr);
        save(*dO, l, "added " + std::to_string(made.size()) + (*as_copy ? " copies" : " instances"));
    });

    struct AddOptions {
        EditIo io;
        std::vector<double> root, direction;
        double length = 0.0;
        std::string name = "added";
    };
    auto ao = std::make_shared<AddOptions>();
    CLI::App* add = style->add_subcommand(
        "add",
        "Add a cluster from nothing: a new prototype rooted at --root that leaves it along --direction (default: away\n"
        "from the centre of the sphere that fits the clusters' roots, the scalp) and bends down as hair falls. Its\n"
        "profiles, density, layer count and rows are its nearest neighbour's (the cluster whose root is nearest), so it\n"
        "looks and moves like the clusters around it; shape it further with `coif style set`." + rows);
    add_io(add, ao->io, false);
    add->add_option("--root", ao->root, "Where it grows from, X Y Z (the style's units)")->required()->expected(3);
    add->add_option("--direction", ao->direction, "The way it leaves the root, X Y Z (any length)")->expected(3);
    add->add_option("--length", ao->length, "Its trajectory's length (default: its neighbour's)")->check(CLI::PositiveNumber);
    add->add_option("--name", ao->name, "Its name, made unique with a number")->capture_default_str();
    coif::cli::examples(add, "  coif style add @default --root 0 18 -6 -o more.json\n"
                             "  coif style add @default --root 5 14 0 --direction 1 0 0 --length 12 --name fringe -o more.json");
    add->callback([ao] {
        if (ao->name.empty()) throw coif::Error::parameter("--name", "must not be empty");
        Loaded l = load(ao->io);
        coif::NewCluster n;
        n.root = {ao->root[0], ao->root[1], ao->root[2]};
        if (ao->direction.size() == 3) n.direction = glm::dvec3(ao->direction[0], ao->direction[1], ao->direction[2]);
        n.length = ao->length;
        n.name = ao->name;
        // The style's down: the shells' −y turned back into the style's space.
        n.down = glm::transpose(glm::dmat3(coif::style_orientation(l.style))) * glm::dvec3(0.0, -1.0, 0.0);
        const std::size_t made = coif::add_cluster(l.style, n, l.absorption ? &*l.absorption : nullptr);
        save(ao->io, l, "added " + l.style.clusters[made].name);
    });

    auto xo = std::make_shared<EditIo>();
    CLI::App* remove = style->add_subcommand(
        "delete",
        "Remove clusters. Instances of a removed cluster keep their places: the first instance of a removed prototype\n"
        "takes its geometry." + rows);
    add_io(remove, *xo, true);
    coif::cli::examples(remove, "  coif style delete h64.json --clusters c12 c13 -o fewer.json");
    remove->callback([xo] {
        Loaded l = load(*xo);
        const std::size_t n = l.selection.size();
        coif::delete_clusters(l.style, l.selection, l.absorption ? &*l.absorption : nullptr);
        save(*xo, l, "removed " + std::to_string(n) + " clusters");
    });

    struct SetOptions {
        EditIo io;
        std::string cluster;
        std::vector<double> a, b, theta;
        std::optional<std::size_t> point;
        std::vector<double> move;
        std::optional<int> layers;
    };
    auto so = std::make_shared<SetOptions>();
    CLI::App* set = style->add_subcommand(
        "set",
        "Edit one cluster's shape: its half-axis profiles A and B and its twist θ (control points from root to tip),\n"
        "its own number of layered shells, or move one control point of its trajectory. An instance's edit goes to its\n"
        "prototype, so every instance of that prototype changes with it.");
    add_io(set, so->io, false);
    set->add_option("--cluster", so->cluster, "The cluster, by name")->required();
    set->add_option("--a", so->a, "Half-axis A's control points (> 0, the style's units)");
    set->add_option("--b", so->b, "Half-axis B's control points (> 0)");
    set->add_option("--theta-deg", so->theta, "The twist θ's control points, degrees");
    set->add_option("--point", so->point, "A trajectory control point's index (0: the root)");
    set->add_option("--move", so->move, "Move that point by X Y Z (the style's units)")->expected(3);
    set->add_option("--layers", so->layers, "Its own number of layered shells (the layout's: follow the layout again)")
        ->check(CLI::Range(1, coif::kMaxLayers));
    coif::cli::examples(set, "  coif style set @default --cluster c3 --a 1.2 1.0 0.8 -o wider.json\n"
                             "  coif style set @default --cluster c3 --point 2 --move 0 0 1 -o bent.json\n"
                             "  coif style set @default --cluster c3 --layers 2 -o thin.json");
    set->callback([so] {
        if (so->point.has_value() != (so->move.size() == 3))
            throw coif::Error::parameter("--point", "--point and --move go together");
        if (so->a.empty() && so->b.empty() && so->theta.empty() && !so->point && !so->layers)
            throw coif::Error::parameter("set", "nothing to set: give --a, --b, --theta-deg, --layers or --point with --move");
        Loaded l = load(so->io);
        const std::size_t c = coif::find_cluster(l.style, so->cluster);
        if (!so->a.empty()) coif::set_profile(l.style, c, "a", so->a);
        if (!so->b.empty()) coif::set_profile(l.style, c, "b", so->b);
        if (!so->theta.empty()) coif::set_profile(l.style, c, "theta_deg", so->theta);
        if (so->point) coif::move_control_point(l.style, c, *so->point, {so->move[0], so->move[1], so->move[2]});
        if (so->layers) coif::set_layers(l.style, c, *so->layers);
        save(so->io, l, "edited " + so->cluster);
    });
}

COIF_REGISTER_COMMAND(21, add_style_edits);

}  // namespace
