// The character formats (layouts in character.h): TressFX's .tfxmesh (text) and .tfxbone (binary), and OBJ through
// tinyobjloader. Every count is checked against the file's size before anything is allocated from it.
#include "models/character.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>
#include <tiny_obj_loader.h>

#include "models/core/atomic_file.h"
#include "models/core/bytes.h"
#include "models/core/error.h"
#include "models/core/units.h"

namespace coif {
namespace fs = std::filesystem;
using bytes::get;

namespace {

std::string str(std::uint64_t v) { return std::to_string(v); }

// Checks a set of four influences and renormalises it; `where` names it in errors.
void settle_weights(BoneInfluence& in, std::size_t bone_count, const fs::path& path, const std::string& where,
                    std::size_t& renormalised, float& min_sum) {
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const float w = in.weight[k];
        if (!std::isfinite(w)) throw Error(path, where, "weight " + std::to_string(k) + " is NaN or infinite");
        if (w < 0.0f) throw Error(path, where, "weight " + std::to_string(k) + " is negative (" + std::to_string(w) + ")");
        if (w > 0.0f && (in.bone[k] < 0 || static_cast<std::size_t>(in.bone[k]) >= bone_count))
            throw Error(path, where, "bone index " + std::to_string(in.bone[k]) + " is outside the " + str(bone_count) + " bones");
        if (w == 0.0f) in.bone[k] = 0;  // an unused slot: any index (TressFX writes 0)
        sum += w;
    }
    if (!(sum >= kMinWeightSum))
        throw Error(path, where, "weights sum to " + std::to_string(sum) + ", below " + std::to_string(kMinWeightSum) + " (not skinned?)");
    if (std::abs(sum - 1.0f) > kRenormaliseReport) ++renormalised;
    min_sum = std::min(min_sum, sum);
    in.weight /= sum;
}

// A line-by-line reader of TressFX's text mesh: tokens of the current record, '#' and blank lines skipped.
class TextLines {
public:
    TextLines(const std::vector<std::byte>& bytes, const fs::path& path)
        : text_(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path_(path) {}

    // Moves to the next record; false at the end of the file.
    bool next() {
        while (at_ < text_.size()) {
            const std::size_t end = std::min(text_.find('\n', at_), text_.size());
            line_ = text_.substr(at_, end - at_);
            at_ = end + 1;
            ++number_;
            if (!line_.empty() && line_.back() == '\r') line_.remove_suffix(1);
            const std::size_t first = line_.find_first_not_of(" \t");
            if (first == std::string_view::npos || line_[first] == '#') continue;
            line_ = line_.substr(first);
            return true;
        }
        return false;
    }
    void expect_next(const std::string& what) {
        if (!next()) throw Error(path_, "end of file", "the file ends before " + what + " (truncated?)");
    }
    std::size_t bytes_left() const { return text_.size() - std::min(at_, text_.size()); }
    std::string where() const { return "line " + str(number_); }

    // The current record as `count` fields (exactly), for numbers.
    std::vector<std::string_view> fields(std::size_t count, const std::string& what) {
        std::vector<std::string_view> out;
        std::size_t i = 0;
        while (i < line_.size() && out.size() <= count) {
            const std::size_t start = line_.find_first_not_of(" \t", i);
            if (start == std::string_view::npos) break;
            const std::size_t end = std::min(line_.find_first_of(" \t", start), line_.size());
            out.push_back(line_.substr(start, end - start));
            i = end;
        }
        if (out.size() != count)
            throw Error(path_, where(), "expected " + what + " (" + str(count) + " fields), found \"" + std::string(line_.substr(0, 80)) + "\"");
        return out;
    }
    template <class T>
    T number(std::string_view field, const std::string& what) const {
        T v{};
        const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
        if (ec != std::errc() || ptr != field.data() + field.size())
            throw Error(path_, where(), what + " \"" + std::string(field.substr(0, 40)) + "\" is not a number of its kind");
        if constexpr (std::is_floating_point_v<T>)
            if (!std::isfinite(v)) throw Error(path_, where(), what + " is NaN or infinite");
        return v;
    }
    // "KEY N", with N at most `limit` and at most bytes_left() / min_line_bytes records.
    std::uint64_t count(const char* key, std::uint64_t limit, std::size_t min_line_bytes) {
        expect_next(std::string("\"") + key + " N\"");
        const auto f = fields(2, std::string("\"") + key + " N\"");
        if (f[0] != key) throw Error(path_, where(), std::string("expected \"") + key + " N\", found \"" + std::string(f[0].substr(0, 40)) + "\"");
        const auto n = number<std::uint64_t>(f[1], key);
        if (n > limit) throw Error(path_, where(), std::string(key) + " " + str(n) + " is absurd (limit " + str(limit) + ")");
        if (n > bytes_left() / min_line_bytes)
            throw Error(path_, where(), str(n) + " records cannot fit in the " + str(bytes_left()) + " bytes left (truncated?)");
        return n;
    }
    // The record's leading index must be its order.
    void expect_index(std::string_view field, std::uint64_t k, const char* what) {
        const auto i = number<std::uint64_t>(field, std::string(what) + " index");
        if (i != k) throw Error(path_, where(), std::string(what) + " index " + str(i) + " out of order (expected " + str(k) + ")");
    }
    std::string_view rest_after_first() const {
        const std::size_t gap = line_.find_first_of(" \t");
        if (gap == std::string_view::npos) return {};
        const std::size_t start = line_.find_first_not_of(" \t", gap);
        if (start == std::string_view::npos) return {};
        std::string_view r = line_.substr(start);
        while (!r.empty() && (r.back() == ' ' || r.back() == '\t')) r.remove_suffix(1);
        return r;
    }
    std::string_view first_field() const { return line_.substr(0, std::min(line_.find_first_of(" \t"), line_.size())); }

private:
    std::string_view text_, line_;
    std::size_t at_ = 0, number_ = 0;
    const fs::path& path_;
};

// Area-weighted vertex normals of a triangle mesh (zero-area faces add nothing; a vertex on none gets +y).
std::vector<glm::vec3> face_normals(const std::vector<glm::vec3>& p, const std::vector<glm::uvec3>& tris) {
    std::vector<glm::vec3> n(p.size(), glm::vec3(0.0f));
    for (const glm::uvec3& t : tris) {
        const glm::vec3 a = glm::cross(p[t.y] - p[t.x], p[t.z] - p[t.x]);
        n[t.x] += a, n[t.y] += a, n[t.z] += a;
    }
    for (glm::vec3& v : n) v = glm::dot(v, v) > 0.0f ? glm::normalize(v) : glm::vec3(0, 1, 0);
    return n;
}

struct BodyFormat {
    const char* extension;
    const char* name;
    BodyMesh (*parse)(const std::vector<std::byte>&, const fs::path&);
};
constexpr BodyFormat kBodyFormats[] = {
    {".tfxmesh", "AMD TressFX .tfxmesh", parse_tfxmesh},
    {".obj", "Wavefront .obj", parse_obj},
};

const BodyFormat* body_format(const fs::path& path) {
    for (const BodyFormat& f : kBodyFormats)
        if (path.extension() == f.extension) return &f;
    return nullptr;
}

}  // namespace

std::pair<glm::vec3, glm::vec3> BodyMesh::bounds(const glm::mat3& orientation) const {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : positions) lo = glm::min(lo, orientation * p), hi = glm::max(hi, orientation * p);
    return {lo, hi};
}

BodyMesh BodyMesh::turned(const glm::mat3& orientation) const {
    BodyMesh out = *this;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        out.positions[i] = orientation * positions[i];
        out.normals[i] = glm::normalize(orientation * normals[i]);
    }
    return out;
}

BodyMesh parse_tfxmesh(const std::vector<std::byte>& bytes, const fs::path& path) {
    TextLines in(bytes, path);
    BodyMesh out;
    const std::uint64_t B = in.count("numOfBones", kMaxBones, 4);
    out.bones.reserve(B);
    for (std::uint64_t k = 0; k < B; ++k) {
        in.expect_next("bone " + str(k));
        in.expect_index(in.first_field(), k, "bone");
        const std::string_view name = in.rest_after_first();
        if (name.empty()) throw Error(path, in.where(), "bone " + str(k) + " has no name");
        out.bones.emplace_back(name);
    }
    const std::uint64_t V = in.count("numOfVertices", kMaxMeshVertices, 30);
    if (V < 3) throw Error(path, in.where(), "a mesh needs at least 3 vertices, the file has " + str(V));
    out.positions.resize(V);
    out.normals.resize(V);
    if (B > 0) out.influences.resize(V);
    const float scale = static_cast<float>(kCentimetresPerMetre);
    for (std::uint64_t k = 0; k < V; ++k) {
        in.expect_next("vertex " + str(k));
        const auto f = in.fields(15, "index, position, normal, 4 joints, 4 weights");
        in.expect_index(f[0], k, "vertex");
        glm::vec3 n;
        for (int c = 0; c < 3; ++c) {
            out.positions[k][c] = in.number<float>(f[1 + c], "position") * scale;
            n[c] = in.number<float>(f[4 + c], "normal");
        }
        out.normals[k] = glm::dot(n, n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f);
        BoneInfluence b;
        for (int c = 0; c < 4; ++c) {
            b.bone[c] = in.number<int>(f[7 + c], "joint index");
            b.weight[c] = in.number<float>(f[11 + c], "weight");
        }
        if (B > 0) {
            settle_weights(b, B, path, in.where(), out.renormalised, out.min_weight_sum);
            out.influences[k] = b;
        }
    }
    const std::uint64_t T = in.count("numOfTriangles", kMaxMeshTriangles, 8);
    if (T == 0) throw Error(path, in.where(), "the mesh has no triangles");
    out.triangles.resize(T);
    for (std::uint64_t k = 0; k < T; ++k) {
        in.expect_next("triangle " + str(k));
        const auto f = in.fields(4, "index and 3 vertex indices");
        in.expect_index(f[0], k, "triangle");
        for (int c = 0; c < 3; ++c) {
            const auto v = in.number<std::uint64_t>(f[1 + c], "vertex index");
            if (v >= V) throw Error(path, in.where(), "vertex index " + str(v) + " is outside the " + str(V) + " vertices");
            out.triangles[k][c] = static_cast<std::uint32_t>(v);
        }
    }
    if (in.next()) throw Error(path, in.where(), "unexpected record after the " + str(T) + " triangles");
    // Normals the file leaves zero come from the faces.
    const std::vector<glm::vec3> from_faces = face_normals(out.positions, out.triangles);
    for (std::size_t i = 0; i < out.normals.size(); ++i)
        if (out.normals[i] == glm::vec3(0.0f)) out.normals[i] = from_faces[i];
    out.axes_stated = true;
    return out;
}

BodyMesh parse_obj(const std::vector<std::byte>& bytes, const fs::path& path) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    const std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (!reader.ParseFromString(text, "", config) || !reader.Valid()) {
        std::string why = reader.Error();
        while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
        throw Error(path, "", "not a readable OBJ file: " + (why.empty() ? std::string("tinyobjloader refused it") : why));
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const std::size_t V = attrib.vertices.size() / 3;
    if (V < 3) throw Error(path, "", "a mesh needs at least 3 vertices, the file has " + str(V));
    if (V > kMaxMeshVertices) throw Error(path, "", "vertex count " + str(V) + " is absurd (limit " + str(kMaxMeshVertices) + ")");
    BodyMesh out;
    out.positions.resize(V);
    for (std::size_t i = 0; i < V; ++i) {
        for (int c = 0; c < 3; ++c) out.positions[i][c] = attrib.vertices[3 * i + c];
        if (!std::isfinite(out.positions[i].x + out.positions[i].y + out.positions[i].z))
            throw Error(path, "vertex " + str(i + 1), "position is NaN or infinite");
    }
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const auto& idx = shape.mesh.indices;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            if (shape.mesh.num_face_vertices[f] != 3)
                throw Error(path, "shape " + shape.name, "a face of " + str(shape.mesh.num_face_vertices[f]) + " vertices was not triangulated");
            glm::uvec3 t;
            for (int c = 0; c < 3; ++c) {
                const int v = idx[3 * f + c].vertex_index;
                if (v < 0 || static_cast<std::size_t>(v) >= V)
                    throw Error(path, "shape " + shape.name + ", face " + str(f + 1), "vertex index " + std::to_string(v + 1) + " is outside the " + str(V) + " vertices");
                t[c] = static_cast<std::uint32_t>(v);
            }
            out.triangles.push_back(t);
        }
    }
    if (out.triangles.empty()) throw Error(path, "", "the mesh has no faces");
    out.normals = face_normals(out.positions, out.triangles);
    return out;
}

BodyMesh read_body(const fs::path& path) {
    const BodyFormat* f = body_format(path);
    if (!f) throw Error(path, "", "unknown body mesh format '" + path.extension().string() + "' (coif reads " + body_extensions() + ")");
    return f->parse(read_file_bytes(path), path);
}

const std::string& body_extensions() {
    static const std::string text = std::string(kBodyFormats[0].extension) + " or " + kBodyFormats[1].extension;
    return text;
}

std::string body_format_name(const fs::path& path) {
    const BodyFormat* f = body_format(path);
    return f ? f->name : "";
}

StrandSkinning parse_tfxbone(const std::vector<std::byte>& in, const fs::path& path) {
    std::size_t at = 0;
    const auto need = [&](std::uint64_t n, const std::string& what) {
        if (n > in.size() - at)
            throw Error(path, "byte " + str(at), what + " needs " + str(n) + " bytes, past the end of the " + str(in.size()) + "-byte file (truncated?)");
    };
    const auto i32 = [&](const std::string& what) {
        need(4, what);
        const std::int32_t v = get<std::int32_t>(in.data() + at);
        at += 4;
        return v;
    };
    StrandSkinning out;
    const std::int32_t B = i32("the bone count");
    if (B <= 0) throw Error(path, "byte 0", "bone count " + std::to_string(B) + " is not positive");
    if (static_cast<std::uint64_t>(B) > kMaxBones || static_cast<std::uint64_t>(B) > (in.size() - at) / 9)
        throw Error(path, "byte 0", "bone count " + std::to_string(B) + " is absurd for a " + str(in.size()) + "-byte file");
    out.bones.reserve(static_cast<std::size_t>(B));
    for (std::int32_t k = 0; k < B; ++k) {
        const std::size_t start = at;
        const std::int32_t index = i32("bone " + std::to_string(k));
        if (index != k) throw Error(path, "byte " + str(start), "bone index " + std::to_string(index) + " out of order (expected " + std::to_string(k) + ")");
        const std::int32_t length = i32("bone " + std::to_string(k) + "'s name length");
        if (length <= 0 || length > 1024)
            throw Error(path, "byte " + str(start + 4), "bone " + std::to_string(k) + "'s name length " + std::to_string(length) + " is outside 1..1024");
        need(static_cast<std::uint64_t>(length), "bone " + std::to_string(k) + "'s name");
        std::string name(reinterpret_cast<const char*>(in.data() + at), static_cast<std::size_t>(length));
        at += static_cast<std::size_t>(length);
        while (!name.empty() && name.back() == '\0') name.pop_back();
        if (name.empty() || name.find('\0') != std::string::npos)
            throw Error(path, "byte " + str(start + 8), "bone " + std::to_string(k) + "'s name is empty or holds a NUL");
        out.bones.push_back(std::move(name));
    }
    const std::size_t count_at = at;
    const std::int32_t S = i32("the strand count");
    if (S <= 0) throw Error(path, "byte " + str(count_at), "strand count " + std::to_string(S) + " is not positive");
    if (static_cast<std::uint64_t>(S) * 36 != in.size() - at)
        throw Error(path, "byte " + str(count_at),
                    std::to_string(S) + " strands need " + str(static_cast<std::uint64_t>(S) * 36) + " bytes, the file has " + str(in.size() - at) +
                        " left (truncated, or trailing bytes?)");
    out.strands.resize(static_cast<std::size_t>(S));
    for (std::int32_t s = 0; s < S; ++s) {
        const std::byte* p = in.data() + at;
        const std::string where = "strand " + std::to_string(s) + " (byte " + str(at) + ")";
        if (get<std::int32_t>(p) != s)
            throw Error(path, where, "strand index " + std::to_string(get<std::int32_t>(p)) + " out of order");
        BoneInfluence b;
        for (int k = 0; k < 4; ++k) {
            b.bone[k] = get<std::int32_t>(p + 4 + 8 * k);
            b.weight[k] = get<float>(p + 8 + 8 * k);
        }
        settle_weights(b, out.bones.size(), path, where, out.renormalised, out.min_weight_sum);
        out.strands[static_cast<std::size_t>(s)] = b;
        at += 36;
    }
    return out;
}

StrandSkinning read_tfxbone(const fs::path& path) {
    if (path.extension() != ".tfxbone") throw Error(path, "", "not a .tfxbone file (by its extension)");
    return parse_tfxbone(read_file_bytes(path), path);
}

std::vector<int> bone_map(const std::vector<std::string>& from, const std::vector<std::string>& to) {
    std::vector<int> map(from.size(), -1);
    for (std::size_t i = 0; i < from.size(); ++i)
        if (const auto j = find_bone(to, from[i])) map[i] = *j;
    return map;
}

std::optional<int> find_bone(const std::vector<std::string>& bones, const std::string& name) {
    const auto it = std::find(bones.begin(), bones.end(), name);
    if (it == bones.end()) return std::nullopt;
    return static_cast<int>(it - bones.begin());
}

BodyMesh scalp_from_roots(const std::vector<glm::vec3>& roots, int segments) {
    if (roots.size() < 4) throw Error::parameter("scalp", "needs at least 4 roots");
    // The sphere |r − c|² = R²: linear least squares in (c, k = R² − |c|²) of 2 c·r + k = |r|², about the roots' mean
    // (for conditioning).
    glm::dvec3 mean(0.0);
    for (const glm::vec3& r : roots) mean += glm::dvec3(r);
    mean /= static_cast<double>(roots.size());
    glm::dmat4 N(0.0);  // the normal equations N x = b
    glm::dvec4 b(0.0);
    for (const glm::vec3& r : roots) {
        const glm::dvec3 q = glm::dvec3(r) - mean;
        const glm::dvec4 row(2.0 * q, 1.0);
        N += glm::outerProduct(row, row);
        b += row * glm::dot(q, q);
    }
    const double scale = (N[0][0] + N[1][1] + N[2][2] + N[3][3]) / 4.0;
    if (!(std::abs(glm::determinant(N)) > 1e-12 * scale * scale * scale * scale))
        throw Error::parameter("scalp", "the roots do not fix a sphere (are they on a line or a plane?)");
    const glm::dvec4 x = glm::inverse(N) * b;
    const glm::dvec3 c = mean + glm::dvec3(x);
    std::vector<double> distance;
    for (const glm::vec3& r : roots) distance.push_back(glm::distance(glm::dvec3(r), c));
    std::nth_element(distance.begin(), distance.begin() + static_cast<std::ptrdiff_t>(distance.size() / 2), distance.end());
    const double radius = distance[distance.size() / 2];
    if (!(radius > 0.0) || !std::isfinite(radius)) throw Error::parameter("scalp", "the roots do not fix a sphere");
    // The mesh: a UV sphere.
    BodyMesh m;
    const int nu = std::max(segments, 8), nv = nu / 2;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const double th = kPi * j / nv, ph = kTwoPi * i / nu;
            const glm::dvec3 s(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
            m.positions.push_back(glm::vec3(c + radius * s));
            m.normals.push_back(glm::vec3(s));
        }
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * nu + (i % nu)); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

}  // namespace coif
