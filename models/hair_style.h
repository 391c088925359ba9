#pragma once
// A hairstyle: the four-level hierarchy of 004 §3.1 — hair volume → macro-clusters → clusters →
// density — and its JSON file format.
//
// Hierarchy. A cluster either carries its own geometry (a generalized cylinder, models/
// generalized_cylinder.h) and density, or is an instance of another cluster placed by a similarity
// transform; instances share the referenced cluster's geometry and density data (one object, not
// copies). A macro-cluster is a prototype (a cluster with geometry) with every cluster that resolves
// to it through instance references, the prototype included. The hair volume is all clusters.
//
// ── Style file, format "coif-style", version 1 (JSON; every field required unless marked) ──
//   {
//     "format": "coif-style", "version": 1,
//     "name": "…",                       optional, free text
//     "units": "…",                      optional, free text (coif scenes: centimetres, y up)
//     "source": { … },                   optional, free-form provenance (import writes file, licence,
//                                        axis rotation, fitting error)
//     "layout": {                        the generalized-disk sampling shared by all clusters
//       "core_radius": 0.2,              v of the transparent core, [0, 1)
//       "layers": 4,                     L shells, 1..256
//       "s_t": 8, "s_u": 8,              HSVs along t and around, 1..4096
//       "grid": [8, 4],                  density grid cells per sector along s and r, 1..256
//       "mesh": [4, 2],                  layer-mesh subdivisions per HSV along t and u, 1..64
//       "gaussian_width": 0.05           λ of a strand's Gaussian exp(−d²/λ²), world units, > 0
//     },
//     "clusters": [                      1..1,000,000 clusters
//       { "name": "c0",                  unique
//         "trajectory": [[x,y,z], …],    ≥ 2 control points of T (B-spline, models/bspline.h)
//         "a": [..], "b": [..],          ≥ 1 control points each, half-axes, > 0
//         "theta_deg": [..],             ≥ 1 control points, the ellipse's twist in degrees
//         "layers": 2,                   optional: this cluster's own L, 1..256 (default the layout's)
//         "density": one of
//            {"kind": "uniform", "value": 0.5}            ρ ≥ 0 in every sector
//            {"kind": "strands", "strand_weight": 1,      member strands' crossings of the s_t+1
//             "strands": [[first_plane, v, u_deg, v, u_deg, …], …]}   sector planes: a run starts at
//                                                         plane first_plane and continues on the next
//                                                         planes; each stored strand counts
//                                                         strand_weight times (a subsampled import)
//            {"kind": "grids", "sectors": [[ρ …], …]}     one grid per sector (sector_count of them,
//                                                         grid_s·grid_r values each, r-major)
//       },
//       { "name": "c1", "instance_of": "c0",             an instance: shares c0's geometry and density
//         "transform": {"scale": 1, "rotation": [w,x,y,z], "translation": [x,y,z]} }   (x ↦ s R x + c)
//     ]
//   }
//   Control-point counts are at most kMaxControlPoints; density runs at most s_t + 1 planes.
//
// What bad input gets: coif::Error naming the file and the JSON path ("JSON /clusters/3/a/1") with
// what is wrong — a missing field, a wrong type, NaN or infinite numbers (the non-standard literals
// NaN/Infinity are recognised and reported at their path too), negative or zero radii, an unknown
// format or version, an instance reference to an unknown cluster or a cycle of references, or counts
// whose density grids would need more than kMaxStyleBytes. Nothing is allocated from an unchecked
// count, and reading never writes anything.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "models/generalized_cylinder.h"
#include "models/generalized_disk.h"
#include "models/skinning.h"
#include "models/sector_density.h"
#include "models/similarity.h"

namespace coif {

inline constexpr int kStyleVersion = 1;
inline constexpr std::size_t kMaxClusters = 1'000'000;
inline constexpr std::size_t kMaxControlPoints = 4096;
// Density grids of all prototypes together (float per cell): 4 GiB, above any real style, below
// what a workstation can allocate.
inline constexpr std::uint64_t kMaxStyleBytes = 4ull << 30;

struct StrandRun {
    int first_plane = 0;
    std::vector<glm::dvec2> vu;  // (v, u in radians) on planes first_plane, first_plane + 1, …
};

struct DensitySource {
    enum class Kind { Uniform, Strands, Grids };
    Kind kind = Kind::Uniform;
    double value = 1.0;          // Uniform
    double strand_weight = 1.0;  // Strands
    std::vector<StrandRun> strands;
    std::vector<std::vector<float>> grids;  // Grids: one per sector
};

struct Cluster {
    std::string name;
    // An instance names another cluster and a transform from that cluster's coordinates.
    std::optional<std::size_t> instance_of;
    Similarity transform;
    // Shared data: a prototype owns these; instances point at their prototype's.
    std::shared_ptr<const GeneralizedCylinder> shape;
    std::shared_ptr<const DensitySource> density;
    // A prototype's own number of layered shells (JSON "layers"), or 0: the style layout's. Instances have their
    // prototype's.
    int layers = 0;
    // Resolved by HairStyle::resolve(): the prototype at the end of the instance chain, and the
    // composed placement (world = placement(prototype coordinates)); identity for a prototype.
    std::size_t prototype = 0;
    Similarity placement;
};

struct MacroCluster {
    std::size_t prototype = 0;
    std::vector<std::size_t> members;  // the prototype first, then its instances
};

// The value of a style's source "axes" when its coordinates are coif's y-up frame already (coif style import oriented
// the strands, or their format states its axes): the renderer then turns nothing (style_orientation).
inline constexpr const char* kStyleAxesYUp = "y-up";

struct HairStyle {
    std::string name;
    std::string units;
    nlohmann::json source = nlohmann::json::object();
    DiskLayout layout;
    std::vector<Cluster> clusters;
    // The clusters' bone weights (models/skinning.h), when the style was fitted to skinned strands (`coif style import
    // --skinning`). JSON: "skinning": {"bones": [name, …], "clusters": [[[bone, weight], … up to 4], … one per cluster]}.
    std::optional<StyleSkinning> skinning;

    // Follows instance references, fills prototype/placement/shape/density of every cluster. Throws
    // coif::Error (place "JSON /clusters/i/instance_of") on a cycle or a dangling reference.
    void resolve(const std::filesystem::path& file = {});
    std::vector<MacroCluster> macro_clusters() const;
    std::size_t prototype_count() const;
    // The layout of cluster c's shells and sectors: the style's, with its prototype's own layer count when it has one.
    DiskLayout layout_of(std::size_t c) const;
};

// Whether the style's source says it is in coif's y-up frame already (kStyleAxesYUp).
bool style_axes_stated(const HairStyle& style);
// The rotation `coif style import` applied to the strand file's coordinates (source "rotation_applied", row-major), or
// the identity: what takes things in the strand file's frame (a character's body) into the style's.
glm::mat3 style_source_rotation(const HairStyle& style);

HairStyle read_style(const std::filesystem::path& path);
HairStyle parse_style(std::string_view text, const std::filesystem::path& name);
HairStyle style_from_json(const nlohmann::json& doc, const std::filesystem::path& name);
nlohmann::ordered_json style_to_json(const HairStyle& style);
// Atomic; numbers rounded to `digits` significant digits where it keeps files small (control points,
// crossings); 0 keeps full precision.
void write_style(const std::filesystem::path& path, const HairStyle& style);
std::string style_text(const HairStyle& style);

// The density grid of every sector of a cluster with geometry `shape` and density `source`, indexed
// by layout.sector_index(i, j, k). Instances use their prototype's grids scaled by placement.scale.
std::vector<SectorDensity> cluster_sector_densities(const GeneralizedCylinder& shape, const DiskLayout& layout,
                                                    const DensitySource& source);
// Strand crossings of plane i in the sector's metric (s, r) coordinates: the mapping used above.
glm::dvec2 sector_coordinates(const SectorShape& sector, double v, double u);

struct StyleCounts {
    std::size_t clusters = 0, prototypes = 0, instances = 0, macro_clusters = 0, shared_macro_clusters = 0;
    std::size_t layers = 0, hsvs = 0, sectors = 0, stored_strands = 0;
    std::uint64_t geometry_bytes = 0, density_bytes = 0, mesh_bytes = 0;
};
StyleCounts style_counts(const HairStyle& style);

}  // namespace coif
