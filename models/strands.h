#pragma once
// Hair strands as read from real strand files, and the two formats coif reads.
//
// ── Cem Yuksel's HAIR format (.hair; read and write; see cyHairFile.h in cemyuksel/cyCodeBase) ──
//   All little-endian. A 128-byte header:
//     char[4]   "HAIR"
//     uint32    strand count S
//     uint32    total point count P
//     uint32    flags: bit0 segments array, bit1 points array, bit2 thickness array,
//                      bit3 transparency array, bit4 colours array
//     uint32    default segment count per strand (used when there is no segments array)
//     float32   default thickness, float32 default transparency, float32×3 default colour
//     char[88]  free-form information (kept byte for byte)
//   then, in this order, the arrays whose bits are set: uint16 segments[S], float32 points[P·3],
//   float32 thickness[P], float32 transparency[P], float32 colours[P·3].
//   Strand i has segments[i] (or the default) segments, i.e. segments + 1 points.
//
// ── USC-HairSalon format (.data; read) ──
//   int32 strand count S, then per strand: int32 point count n, n × float32 (x, y, z). Little-endian.
//   USC files mark scalp positions without hair as strands of ONE point; those carry no hair, so
//   they are skipped on read and counted in `Strands::skipped_single_point`.
//
// ── AMD TressFX 4 guide strands (.tfx; read; TressFXFileFormat.h in GPUOpen-Effects/TressFX) ──
//   All little-endian. A 160-byte header: float32 version, uint32 strand count S, uint32 points per strand
//   V, then uint32 byte offsets of the vertex positions, strand UVs, vertex UVs, thickness and colours
//   (0: absent), then 32 reserved uint32. The positions are S·V float4 (x, y, z, w) from their offset,
//   strand after strand; w is TressFX's "movable" flag (0 on the fixed root points), not a coordinate.
//   coif reads the positions only. TressFX assets are in metres: they are read into centimetres, coif's
//   scene unit (× kCentimetresPerMetre, models/core/units.h), and are y-up.
//
// ── hairutil's binary PLY strands (.ply; read; kenshi84/hairutil) ──
//   An ASCII header "ply", "format binary_little_endian 1.0", then `element NAME COUNT` lines each
//   followed by its `property TYPE NAME` lines, up to "end_header\n"; then each element's records, in
//   header order, each record its properties packed in order. coif needs `element vertex` with float or
//   double x, y, z and `element strand` with one integer property `nsegs` (segments per strand: nsegs + 1
//   points, in vertex order); other elements (hairutil's edge) and properties (its per-vertex colour) are
//   skipped. List properties and other encodings (ascii, big-endian) are refused. Coordinates are kept as
//   stored (units not stated). Hand-written: Debian packages no PLY library.
//
// What bad input gets (a coif::Error naming the file, the place and the problem; nothing is
// allocated from an unchecked count): a wrong magic; a file shorter than its header; counts that
// disagree with the file size or with each other (checked before allocating); absurd counts
// (S or P above kMaxStrands / kMaxPoints); a strand of a .hair file with zero segments; a strand
// whose points all coincide (zero length); NaN or infinite coordinates, thickness or colours.
//
// Axes and units: coordinates are kept exactly as stored in the file (no axis swap, no scaling), so
// a .hair round trip is bit-exact. Neither format states its axes or units. coif's scene convention
// is right-handed, y up, centimetres; `strand_stats` reports the mean root→tip direction so a caller
// can tell a y-up model (hair hangs along −y, e.g. harolongo.data) from one that hangs along −x
// (the CT2Hair-derived Bangs/Curly files) and orient it (see `hang_axis_rotation`).
#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace coif {

// Largest counts coif accepts from a file header, far above any real model (Yuksel's largest
// models have 50k strands and 3.4M points; USC files 10k × 100) but small enough to allocate.
inline constexpr std::uint64_t kMaxStrands = 10'000'000;
inline constexpr std::uint64_t kMaxPoints = 200'000'000;

struct Strands {
    std::vector<glm::vec3> points;        // all points, each strand root → tip
    std::vector<std::uint32_t> offsets;   // strand_count()+1 entries; strand i is points[offsets[i], offsets[i+1])
    std::vector<float> thickness;         // empty, or one per point
    std::vector<float> transparency;      // empty, or one per point
    std::vector<glm::vec3> colors;        // empty, or one per point (linear RGB as stored)

    // .hair header defaults, kept for bit-exact round trips and used when the arrays are empty.
    float default_thickness = 1.0f;
    float default_transparency = 0.0f;
    glm::vec3 default_color{1.0f};
    std::array<char, 88> info{};

    std::uint64_t skipped_single_point = 0;  // .data: one-point strands (scalp marks) skipped on read
    // The format states its axes (TressFX: y-up, read from metres into centimetres): nothing is guessed from
    // where the hair hangs (a mohawk sweeps along −z on a y-up head), so hang_axis_rotation is the identity.
    bool axes_stated = false;

    std::size_t strand_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
    std::size_t point_count(std::size_t strand) const { return offsets[strand + 1] - offsets[strand]; }

    void add_strand(const std::vector<glm::vec3>& strand_points);
    // Appends the strands of `other` (their points only, as add_strand: no per-point attributes).
    void add_strands(const Strands& other);
    // Throws coif::Error (with `source` as the file) if the arrays are inconsistent or hold NaN/Inf,
    // a strand has < 2 points, or a strand has zero length.
    void validate(const std::filesystem::path& source) const;
};

// By extension: .hair (Yuksel), .data (USC-HairSalon), .tfx (TressFX) or .ply (hairutil). Throws
// coif::Error on any problem.
Strands read_strands(const std::filesystem::path& path);
Strands read_hair(const std::filesystem::path& path);
Strands read_usc_data(const std::filesystem::path& path);
// The same, from bytes already in memory; `name` is used in error messages.
Strands parse_hair(const std::vector<std::byte>& bytes, const std::filesystem::path& name);
Strands parse_usc_data(const std::vector<std::byte>& bytes, const std::filesystem::path& name);
Strands parse_tfx(const std::vector<std::byte>& bytes, const std::filesystem::path& name);
Strands parse_ply(const std::vector<std::byte>& bytes, const std::filesystem::path& name);
// The strand extensions read_strands knows, for messages and help: ".hair, .data, .tfx or .ply".
const std::string& strand_extensions();
// The format read_strands reads `path` as, in words ("AMD TressFX .tfx"), by its extension.
std::string strand_format_name(const std::filesystem::path& path);

// Writes a .hair file atomically, with the segments and points arrays always, and the thickness,
// transparency and colour arrays when present. Throws coif::Error (after validate()) on bad strands.
void write_hair(const std::filesystem::path& path, const Strands& strands);

struct StrandStats {
    std::size_t strands = 0, points = 0;
    std::size_t points_min = 0, points_max = 0;
    double points_mean = 0;
    glm::dvec3 bbox_min{0}, bbox_max{0};
    glm::dvec3 root_bbox_min{0}, root_bbox_max{0};
    double length_min = 0, length_mean = 0, length_max = 0;
    double segment_length_mean = 0;
    double chord_over_length_mean = 0;   // |tip − root| / arc length: 1 straight, lower wavy/curly
    glm::dvec3 mean_root_to_tip{0};      // unit vector along the sum of root→tip chords: where the hair hangs
    std::string axis_convention;         // what coif assumes about the axes, in words
    bool axes_stated = false;            // Strands::axes_stated: no rotation is guessed
};

StrandStats strand_stats(const Strands& strands);

// Rotation that takes the dominant hang axis of the strands (±x, ±y or ±z, from the mean root→tip
// direction) to −y, coif's "down". Identity for y-up models, and for formats that state their axes.
glm::mat3 hang_axis_rotation(const StrandStats& stats);
// `strands` turned by hang_axis_rotation of their own stats: coif's y-up orientation.
Strands oriented_y_up(Strands strands);

// Default fibre radius as a fraction of the strands' bounding-box diagonal: 1e-3 gives 0.04 cm for a
// 40 cm head, about 0.8 px wide at coif render's default framing (720×480, 40° fov) — close to the 1-px
// GL lines of the strand preview. Real hair is ~0.004 cm in radius, but the models here are 100–8 000
// guide strands, not the ~100 000 of a head, so physical fibres would leave the hair see-through.
// Used alike by the reference path tracer (offline/reference.h) and the strand renderer (online/).
inline constexpr float kAutoRadiusFraction = 1e-3f;
float auto_fiber_radius(const Strands& strands);
// The same from the strands' bounding box (StrandStats::bbox_min/max), for a caller that has it already.
float auto_fiber_radius(glm::dvec3 bbox_min, glm::dvec3 bbox_max);

}  // namespace coif
