#pragma once
// The character a hair sits on: its body (an opaque triangle mesh, optionally skinned to bones) and the skinning of
// the hair's strands to those bones, and the formats coif reads them from.
//
// ── AMD TressFX collision mesh (.tfxmesh; read; TressFX's Maya exporter) ──
//   Text, one record per line; lines starting with '#' and blank lines are skipped; fields are separated by blanks.
//     numOfBones B          then B lines:  index name                       (index = the line's order, 0 … B−1)
//     numOfVertices V       then V lines:  index x y z nx ny nz j0 j1 j2 j3 w0 w1 w2 w3
//     numOfTriangles T      then T lines:  index a b c                      (vertex indices, 0 … V−1)
//   j are bone indices into the B bones, w their weights. Positions are in metres, y-up, the frame of the .tfx
//   strands that sit on the mesh: they are read into centimetres (× kCentimetresPerMetre, models/core/units.h).
//
// ── AMD TressFX strand skinning (.tfxbone; read; TressFX's Maya exporter) ──
//   Binary, little-endian:
//     int32 bone count B, then per bone: int32 index (= its order), int32 name length L (with its NUL), L bytes;
//     int32 strand count S (the .tfx's), then per strand 36 bytes: int32 strand index (= its order) and
//     4 × (int32 bone index into the B bones, float32 weight).
//   Bone names, not indices, tie a .tfxbone to a mesh's skeleton (bone_map).
//
// ── Wavefront OBJ (.obj; read through Debian's tinyobjloader) ──
//   Positions and faces (triangulated); normals are computed from the faces; materials, texture coordinates and
//   groups are ignored. OBJ states no units or axes: coordinates are kept as stored. No bones.
//
// Weights (.tfxmesh per vertex, .tfxbone per strand): each must be finite and ≥ 0, a bone with a weight above 0 must
// exist, and the four must sum to at least kMinWeightSum. Sums that differ from 1 are renormalised (TressFX's
// exporter writes four truncated weights: the shipped mohawk has 72 strands summing to 0.92–0.99), and counted in
// `renormalised` (those beyond kRenormaliseReport of 1).
//
// Bad input gets a coif::Error naming the file, the line or byte, and the problem, before anything is allocated from
// an unchecked count: counts against the file's size, absurd counts, indices out of range, NaN or infinite numbers,
// truncated files, trailing bytes.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace coif {

inline constexpr float kMinWeightSum = 0.5f;        // below this a weight set is refused, not renormalised
inline constexpr float kRenormaliseReport = 0.01f;  // sums further than this from 1 are counted as renormalised
inline constexpr std::uint64_t kMaxBones = 65'536;
inline constexpr std::uint64_t kMaxMeshVertices = 50'000'000;
inline constexpr std::uint64_t kMaxMeshTriangles = 100'000'000;

// Four bone influences, weights summing to 1 (unused slots: bone 0, weight 0).
struct BoneInfluence {
    glm::ivec4 bone{0};
    glm::vec4 weight{0.0f};
};

struct BodyMesh {
    std::vector<glm::vec3> positions;   // centimetres for .tfxmesh, as stored for .obj
    std::vector<glm::vec3> normals;     // unit, one per position
    std::vector<glm::uvec3> triangles;  // counter-clockwise seen from outside as the file has them
    std::vector<std::string> bones;     // skeleton bone names (empty: not skinned)
    std::vector<BoneInfluence> influences;  // one per position when bones is not empty
    std::size_t renormalised = 0;       // vertices whose weights were renormalised (see above)
    float min_weight_sum = 1.0f;        // the smallest weight sum read
    bool axes_stated = false;           // .tfxmesh: y-up centimetres, the .tfx's frame
    // The box (min, max) of the positions turned by `orientation`.
    std::pair<glm::vec3, glm::vec3> bounds(const glm::mat3& orientation = glm::mat3(1.0f)) const;
    // The same body turned by `orientation` (a rotation): its positions and normals.
    BodyMesh turned(const glm::mat3& orientation) const;
};

struct StrandSkinning {
    std::vector<std::string> bones;         // names, in the file's order
    std::vector<BoneInfluence> strands;     // one per strand, indices into `bones`
    std::size_t renormalised = 0;
    float min_weight_sum = 1.0f;
};

// By extension: .tfxmesh or .obj. Throws coif::Error.
BodyMesh read_body(const std::filesystem::path& path);
BodyMesh parse_tfxmesh(const std::vector<std::byte>& bytes, const std::filesystem::path& name);
BodyMesh parse_obj(const std::vector<std::byte>& bytes, const std::filesystem::path& name);
StrandSkinning read_tfxbone(const std::filesystem::path& path);
StrandSkinning parse_tfxbone(const std::vector<std::byte>& bytes, const std::filesystem::path& name);
// ".tfxmesh or .obj", and the format's name in words by extension ("AMD TressFX .tfxmesh"; empty if unknown).
const std::string& body_extensions();
std::string body_format_name(const std::filesystem::path& path);

// A scalp for hair without a head (`coif render --scalp`): the sphere fitted to the roots (algebraic least squares,
// its radius the roots' median distance from its centre, so that they lie on it), as a closed mesh (`segments` around,
// segments / 2 from pole to pole; outward normals; no bones). A sphere is the ellipsoid a cap of roots fixes: their
// spread along the head's height is too short to fit its own axis. Throws coif::Error::parameter for fewer than 4
// roots, or roots on a line or a plane.
BodyMesh scalp_from_roots(const std::vector<glm::vec3>& roots, int segments = 48);

// For each of `from`'s bones, the index of the bone of the same name in `to`, or −1 when `to` has none.
std::vector<int> bone_map(const std::vector<std::string>& from, const std::vector<std::string>& to);
// The index of the bone named `name`, or nullopt.
std::optional<int> find_bone(const std::vector<std::string>& bones, const std::string& name);

}  // namespace coif
