#pragma once
// The shell renderer's scene preparation (online/shell_renderer.h), GL-free: everything about a hairstyle that
// the GPU passes read, computed once per style on the CPU and testable without a GL context. Stage 1 needs the
// HRIR database and lives with the cooking (online/scene/cook.h); these types and stage 2 do not, so that the
// runtime, which draws cooked assets (online/shells/hair_asset.h), links no database.
//
//   prototypes  each prototype cluster's layer meshes (models/generalized_disk.h layer_mesh) in one vertex and
//               index array, and per sector its density features → FLANN look-up (db/satf.h match_all, DESIGN.md
//               decision 2), kept as the kMaxShellNeighbours best record ids and weights, plus Σ of the outer
//               layers' mean α (004 eq. 12's sum; the view-averaged α of each outer sector);
//   clusters    each cluster (prototype or instance) as one GPU instance: its placement and the scene orientation
//               as a model matrix, so instances share their prototype's meshes and sectors; its lighting samples
//               along the axis (position, tangent, frame normal); the placed outer layers' bounds.
//
// The seams: level of detail plugs in at prepare_prototypes (the meshes' tessellation and layers per
// prototype), motion at place_clusters (a new orientation or placement per frame re-runs only that stage).
//
// The structs are std430 mirrors of the GLSL that reads them (shaders/gl/shell.vert, shell_shade.glsl,
// shell_lighting.comp, shell_shadow.comp); their layout is part of that contract.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cmath>

#include <glm/glm.hpp>
#include <span>
#include <utility>
#include <vector>

#include "models/core/bulk.h"
#include "models/hair_style.h"
#include "models/strands.h"
#include "online/shells/shell_settings.h"

namespace coif {

struct ShellVertex {  // shell.vert's attributes 0..4
    glm::vec3 position, tangent, normal;
    glm::vec2 texcoord;       // (u / 2π, t)
    glm::vec3 axis_normal;    // the cylinder's frame normal n(t)
};
struct ShellSector {  // shell_shade.glsl ShellSector
    glm::uvec4 id{0};         // nearest records, best first
    glm::vec4 weight{0};
    // x: Σ ᾱ of the outer sectors at the same (i, k); y: Σ ᾱ of every layer there (both thinned); z: the records'
    // thinning c ∈ [0, 1] (online/scene/cook.h sector_thinning; shaders/gl/record_atlas.glsl thinned_alpha); w unused.
    glm::vec4 shadow{0.0f, 0.0f, 1.0f, 0.0f};
};
struct ShellInstance {  // shell.vert ShellInstance
    glm::mat4 model;
    glm::uvec4 info;          // x: first sector of the prototype, y: cluster index
};
struct LightingSample {  // shaders/gl/lighting_samples.glsl
    // The cluster's elliptic cross-section there rides in the w components: its half-axes A (position.w) and B
    // (tangent.w), world units, along e1 = cos θ n + sin θ (t × n) and t × e1, θ in normal.w (radians;
    // models/generalized_cylinder.h ellipse_axes), so that motion, which turns t and n, turns the ellipse too.
    glm::vec4 position;       // world
    glm::vec4 tangent, normal;
    // How the fibres' tangents tilt about `tangent` here (measure_fibre_tilts; zero until measured): tilts are
    // vectors ⟂ tangent whose length is the angle (radians); their mean, and the principal axes a, b of their
    // spread about it, scaled so that the four tilts mean ± a, mean ± b have the fibres' second moment
    // (shaders/lighting/fibre_tangents.glsl). xyz; w unused.
    glm::vec4 tilt_mean{0.0f}, tilt_a{0.0f}, tilt_b{0.0f};
    // The cross-section's axis of A, e1 = cos θ n + sin θ (t × n) with n the frame normal made ⟂ t (as
    // lighting_samples.glsl sample_ellipse_axis); zero where the normal runs along the tangent.
    glm::vec3 ellipse_axis() const {
        const glm::vec3 t = glm::normalize(glm::vec3(tangent));
        const glm::vec3 across = glm::vec3(normal) - glm::dot(glm::vec3(normal), t) * t;
        if (!(glm::length(across) > 1e-6f)) return glm::vec3(0.0f);
        const glm::vec3 n = glm::normalize(across);
        return std::cos(normal.w) * n + std::sin(normal.w) * glm::cross(t, n);
    }
};
// One layer mesh inside the shared vertex and index arrays.
struct MeshRange {
    std::uint32_t first = 0;  // index offset
    std::int32_t count = 0;   // indices
    std::int32_t base_vertex = 0;
    std::int32_t vertex_count = 0;
};

struct PreparedShells {
    DiskLayout layout;
    // Prototypes (slots in order of first use by a cluster).
    std::vector<std::size_t> prototypes;           // slot → the style's cluster index of the prototype
    Bulk<ShellVertex> vertices;
    Bulk<std::uint32_t> indices;
    std::vector<std::vector<MeshRange>> meshes;    // [slot][layer]: a prototype's own layer count (HairStyle::layout_of)
    std::vector<ShellSector> sectors;              // [sector_base(slot) + its layout's sector index]
    std::size_t triangles = 0;
    // Clusters, in style order.
    std::vector<std::size_t> cluster_proto;        // cluster → slot
    std::vector<ShellInstance> instances;
    std::vector<std::uint32_t> cluster_ids;        // the per-instance attribute: 0, 1, 2, …
    std::vector<glm::vec3> cluster_centre;         // world, the axis at t = ½ (the sorted compositing's key)
    int lighting_rows = 0;                         // lighting samples per cluster along t
    std::vector<LightingSample> samples;           // cluster-major
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  // the placed outer layers (world, oriented)

    std::size_t clusters() const { return cluster_proto.size(); }
    // A prototype's layout: `layout` with the slot's own layer count (its layer meshes).
    DiskLayout layout_of_slot(std::size_t slot) const;
    // Where each slot's sectors begin in `sectors`, and after the last the count they need (slots + 1 entries).
    std::vector<std::size_t> sector_bases() const;
};

// The rotation that turns the style's mean root→tip direction (from its clusters' axes) to −y
// (models/strands.h hang_axis_rotation): identity for y-up styles, and for those whose source says they are in coif's
// y-up frame already (source "axes": kStyleAxesYUp, written by `coif style import`: it oriented the strands, or their
// format states its axes, as TressFX's does, whose mohawk sweeps along −z and must not be turned).
glm::mat3 style_orientation(const HairStyle& style);
// What turns a character's body, in the frame of the strand file the style was imported from, into the shells' space:
// style_orientation · style_source_rotation (the turn the strands had on import, then the one they have when drawn).
glm::mat3 body_orientation(const HairStyle& style);
// Each cluster's root (its axis at t = 0), turned by `orientation` into the shells' space: where skinning keeps it on the
// skin (models/skinning.h cluster_transform).
std::vector<glm::vec3> cluster_roots(const HairStyle& style, const glm::mat3& orientation);

// Every cluster's bounding box in the shells' space: its outermost layer mesh's box in the prototype's coordinates,
// placed by its instance (8 corners; an oriented box, tight for long, thin clusters).
// The prototypes' boxes (min, max) are the part that depends only on the meshes: made once, placed per frame.
using ClusterBox = std::array<glm::vec3, 8>;
using PrototypeBox = std::pair<glm::vec3, glm::vec3>;
std::vector<PrototypeBox> prototype_boxes(const PreparedShells& shells);
std::vector<ClusterBox> cluster_boxes(const PreparedShells& shells, std::span<const PrototypeBox> prototypes);
// Whether a box can show in a view: one with every corner outside one plane of `view_projection`'s frustum
// (OpenGL clip space −w ≤ x, y, z ≤ w; the near plane is taken as z ≥ −w, which also keeps everything of a [0, w]
// depth range) cannot.
bool box_in_view(const glm::mat4& view_projection, const ClusterBox& box);

// Stage 2 (after stage 1, online/scene/cook.h prepare_prototypes): instances, lighting samples and bounds of every cluster under `orientation`.
// `lighting_rows_per_hsv`: lighting samples per HSV along t (0: the layout's mesh_t, one per mesh row);
// throws coif::Error::parameter outside 0..kMaxMeshSubdivision.
void place_clusters(PreparedShells& shells, const HairStyle& style, const glm::mat3& orientation,
                    int lighting_rows_per_hsv = 0);
// How the strands' tangents tilt about the axis at each lighting sample (LightingSample::tilt_*), from the strand
// segments whose nearest lighting sample of their own cluster it is, length-weighted. `strands` as sampled from
// the style (models/style_strands.h), turned here by `orientation` as the samples are; `strand_cluster[s]` strand
// s's cluster. A sample that no segment is nearest to keeps zero tilts (its fibres are lit along the axis).
// Returns the RMS tilt over all segments (radians): how far the fibres stray from the one tangent a cluster is lit
// with (ShellStats::tangent_spread). Throws coif::Error::parameter if the sizes disagree or a cluster index is out
// of range.
float measure_fibre_tilts(PreparedShells& shells, const Strands& strands, std::span<const std::uint32_t> strand_cluster,
                          const glm::mat3& orientation);
// measure_fibre_tilts one cluster at a time (for a caller that keeps each cluster's sums between cooks of a style being
// edited, online/scene/cook.h): the length-weighted tilt moments of a cluster's strands at each of its lighting samples,
// summed in the strands' order, and its share of the RMS. set_fibre_tilts of every cluster's sums is
// measure_fibre_tilts, bit for bit.
struct FibreTiltSums {
    struct Moments {
        double w = 0;
        glm::dvec2 sum{0.0};
        glm::dvec3 sum2{0.0};  // xx, yy, xy
    };
    std::vector<Moments> rows;  // per lighting sample of the cluster
    double angle2 = 0, weight = 0;
};
// `strands`: the cluster's own, as sampled (not turned). Throws as measure_fibre_tilts.
FibreTiltSums cluster_fibre_tilt_sums(const PreparedShells& shells, std::size_t cluster, const Strands& strands,
                                      const glm::mat3& orientation);
// Sets every lighting sample's tilts from its cluster's sums (one per cluster, in order); returns the RMS tilt.
float set_fibre_tilts(PreparedShells& shells, std::span<const FibreTiltSums> clusters);
// How far the lighting can skip samples along the clusters (ShellSettings::lighting_step): the largest step k ≤ `wanted`
// dividing lighting_rows − 1 at which 90 % of the skipped samples' axis tangents lie within `max_angle` radians of the
// (normalised) linear interpolation between the lit samples around them. A curled style keeps every sample, a smooth
// one may skip: the R lobe's highlight follows the tangent within its width β_R. `worst` (if given) receives, per step
// tried, that 90th-percentile angle.
int lighting_step_within(const PreparedShells& shells, int wanted, float max_angle, std::vector<float>* worst = nullptr);

}  // namespace coif
