#pragma once
// A cooked hairstyle: everything the shell renderer (online/shell_renderer.h) draws a style with, as data
// (CookedShells), and its file, the `.coif` asset that `coif bake` writes and the runtime loads without the HRIR
// database or FLANN. Cooking from a style is online/scene/cook.h.
//
// The `.coif` file, version 5 (3: LightingSample carries the cross-section's ellipse in its w components; 4: every asset
// carries its grid's strands, which the key lights' fine grid is made from; 5: each sector carries its records'
// thinning in shadow.z, and its shadow sums are thinned). Little-endian, IEEE-754 floats, every
// section 8-byte aligned:
//
//   byte 0   8  magic "COIFHAIR"
//   byte 8   u32 format version (kHairAssetVersion)
//   byte 12  u32 section count (20 in version 5)
//   byte 16  u64 file size in bytes
//   byte 24  u64 XXH3-64 checksum of bytes 32 … end (models/core/checksum.h)
//   byte 32  the sections, in this order, each a u32 tag (4 ASCII characters), u32 element size in bytes, u64
//            element count, then count × size bytes, then zeros to the next multiple of 8:
//     META  1 byte   JSON object, UTF-8: "format": "coif-hair-asset"; "style" (its name); "database" (the HRIR
//                    database cooked against, for messages) and "database_records" (its record count);
//                    "coif_version"; "layout" (models/generalized_disk.h DiskLayout: core_radius, layers, s_t, s_u,
//                    grid_s, grid_r, mesh_t, mesh_u, gaussian_width); "prototype_layers" (each prototype's layer
//                    count, in order, 1..64; only when one differs from the layout's); "lighting_rows"; "bounds" and
//                    "frame" ([min xyz, max xyz]: the placed outer layers, and the box a camera frames, that of
//                    the style's strands turned y-up); "tangent_spread" (RMS fibre tilt, radians);
//                    "auto_fiber_radius"; "shadow_strands"; "atlas" (width, height, tiles_per_row, views,
//                    hrir_length, lo and scale as 3 × 4 numbers, re_norm: online/shells/record_atlas.h); "grid"
//                    (dims, origin, voxel, strands_min, strands_max: online/shells/shadow_grid.h); "params" (the
//                    defaults the asset was baked with: the parameters file's keys, online/shells/shell_settings.h);
//                    "body_orientation" (9 numbers, column-major: CookedShells::body_orientation); "bones" (the
//                    skeleton's bone names, [] when the style has no bone weights).
//     VERT 56 bytes  ShellVertex (online/shells/prepared_shells.h): the prototypes' layer meshes' vertices
//     INDX  4        u32 indices, per mesh relative to its base vertex
//     MESH 16        MeshRange (first, count, base_vertex, vertex_count), prototype-major, its layer count per prototype
//     PROT  4        u32 per prototype: the style's cluster index it was made from
//     SECT 48        ShellSector: per prototype, its layout's sector_count(): record ids (into the atlas), weights, shadow sums
//                    and the records' thinning c ∈ [0, 1] (shadow.z)
//     CPRO  4        u32 per cluster: its prototype
//     INST 80        ShellInstance per cluster: model matrix, (first sector, cluster index, 0, 0)
//     CCEN 12        vec3 per cluster: the axis's centre, world
//     SAMP 96        LightingSample per cluster × lighting_rows (online/shells/prepared_shells.h: the w components hold the ellipse)
//     ATLS  1        the record atlas's RGBA8 texels, width × height × 4, row 0 first
//     MALP  4        f32 per atlas record: mean α
//     MA0_  4        f32 per atlas record: mean re a0
//     GDIA 16        vec4 per voxel: the shadow grid's (xx, yy, zz, xy), x fastest
//     GOFF  8        vec2 per voxel: (xz, yz)
//     ROOT 12        vec3 per cluster: its axis's root (CookedShells::roots)
//     SPNT 12        vec3 per point of the shadow strands (CookedShells::shadow_source: the points)
//     SOFF  4        u32 per shadow strand, and one more: where its points start (the last: the point count)
//     SCLU  4        u32 per shadow strand: its cluster
//                    (the key lights' fine grid, online/shells/shadow_grid.h kKeyLightGridSize, is made from them
//                    when first drawn, as from the style's strands cooked live; 3 MB of the default style's)
//     SKIN 32        BoneInfluence per cluster (i32 bone × 4 into "bones", f32 weight × 4), or none (no "bones")
//
// What the sections imply is not stored: each cluster's index (the per-instance attribute 0, 1, 2, …) and the
// triangle count are derived on reading.
//
// The atlas holds only the records the sectors use, quantised with the ranges of the whole database and with its
// re_norm, so that an asset draws bit-identically to its style cooked live (both draw a CookedShells).
//
// Compatibility: the version changes whenever anything above changes; a reader accepts exactly the versions it
// was written for (this one: 5) and refuses any other with an error that names both, so an asset is re-baked
// with `coif bake` after such a change. Readers never guess at a layout.
//
// Reading validates everything a hostile file could use to make the renderer read out of bounds: sizes, counts
// that must agree, every index and record id in range, every float finite; any failure throws coif::Error naming
// the file and the byte or field.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "models/core/bulk.h"
#include "models/skinning.h"
#include "models/strands.h"
#include "online/shells/prepared_shells.h"
#include "online/shells/record_atlas.h"
#include "online/shells/shadow_grid.h"
#include "online/shells/shell_settings.h"

namespace coif {

inline constexpr std::uint32_t kHairAssetVersion = 5;

// The strands voxelized into a cooked hair's shadow grid, in the shells' space (points and offsets only): an asset's
// viewed in its mapping, so that loading does not copy them (they are read on the first draw with key lights, and on
// the first motion).
struct ShadowStrands {
    Bulk<glm::vec3> points;
    Bulk<std::uint32_t> offsets;  // strand i is points[offsets[i], offsets[i + 1])
    Strands strands() const;      // a copy, as Strands (points and offsets)
};

struct CookedShells {
    std::string name;             // the style's
    PreparedShells shells;        // sector ids index atlas records
    RecordAtlas atlas;            // the records the sectors use; ranges and re_norm of the whole database
    DensityGrid grid;             // the shadow grid
    float tangent_spread = 0;     // RMS tilt of the strands about their cluster's axis (measure_fibre_tilts)
    float auto_fiber_radius = 0;  // coif reference's auto radius of the same strands as turned
    std::uint64_t shadow_strands = 0;    // strands voxelized into the grid
    std::uint64_t database_records = 0;  // records of the database cooked against
    std::string source;           // where it came from, for messages: the database's path, or the asset's
    std::string database;         // the database cooked against (its path; informative)
    glm::vec3 frame_min{0.0f}, frame_max{0.0f};  // the box a camera frames: the style's strands, turned y-up
    gl::ShellSettings defaults;   // the parameters it was baked with (a live cook: the library's defaults)
    // What moving the clusters needs (ShellRenderer::set_cluster_transforms; HairRenderer's bone poses):
    glm::mat3 body_orientation{1.0f};  // turns a body in the style's strand file's frame into the shells' space
    std::vector<glm::vec3> roots;      // per cluster: its axis's root, in the shells' space (cluster_roots)
    // The strands voxelized into `grid` and each one's cluster: voxelized finer, they give the key lights' grid; moved
    // with their clusters and voxelized again, a moved hair's grid.
    ShadowStrands shadow_source;
    std::vector<std::uint32_t> shadow_strand_cluster;
    std::optional<StyleSkinning> skinning;  // the style's bone weights (models/skinning.h), when it has them
};

// The asset's bytes, and its file (written atomically: nothing is left at `path` on failure).
std::vector<std::byte> hair_asset_bytes(const CookedShells& cooked);
void write_hair_asset(const std::filesystem::path& path, const CookedShells& cooked);
// Parses and validates an asset held in memory; `file` names it in errors. Throws coif::Error.
CookedShells parse_hair_asset(std::span<const std::byte> bytes, const std::filesystem::path& file);
// Maps the file and parses it. Throws coif::Error (cannot open, truncated, corrupt, another version, …).
CookedShells read_hair_asset(const std::filesystem::path& path);
// Whether the file starts with the asset's magic (how `coif render` tells an asset from a style).
bool is_hair_asset(const std::filesystem::path& path);

}  // namespace coif
