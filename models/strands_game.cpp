// The game and tool strand formats: AMD TressFX's .tfx and hairutil's binary .ply (layouts in strands.h).
// Every count is checked against the file's size before anything is allocated from it.
#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/bytes.h"
#include "models/core/error.h"
#include "models/core/units.h"
#include "models/strands.h"

namespace coif {
namespace fs = std::filesystem;
using bytes::get;

namespace {

constexpr std::size_t kTfxHeaderBytes = 160;
constexpr std::uint64_t kMaxTfxPointsPerStrand = 1024;  // TressFX itself allows 4..64
constexpr std::size_t kMaxPlyHeaderBytes = 64 * 1024;

std::string place(std::size_t byte) { return "byte " + std::to_string(byte); }

}  // namespace

Strands parse_tfx(const std::vector<std::byte>& in, const fs::path& path) {
    if (in.size() < kTfxHeaderBytes)
        throw Error(path, "header", "the file has " + std::to_string(in.size()) + " bytes, fewer than the 160-byte TressFX header");
    const float version = get<float>(in.data());
    const std::uint64_t S = get<std::uint32_t>(in.data() + 4), V = get<std::uint32_t>(in.data() + 8);
    const std::uint64_t positions = get<std::uint32_t>(in.data() + 12);
    if (!std::isfinite(version) || version < 1.0f || version >= 100.0f)
        throw Error(path, place(0), "version field " + std::to_string(version) + " is not a TressFX version (not a .tfx file?)");
    if (S == 0) throw Error(path, place(4), "the file holds no strands");
    if (S > kMaxStrands) throw Error(path, place(4), "strand count " + std::to_string(S) + " is absurd (limit " + std::to_string(kMaxStrands) + ")");
    if (V < 2 || V > kMaxTfxPointsPerStrand)
        throw Error(path, place(8), "points per strand " + std::to_string(V) + " outside 2.." + std::to_string(kMaxTfxPointsPerStrand));
    for (int k = 0; k < 5; ++k) {  // positions, strand UVs, vertex UVs, thickness, colours
        const std::uint64_t offset = get<std::uint32_t>(in.data() + 12 + 4 * k);
        if (offset != 0 && (offset < kTfxHeaderBytes || offset > in.size()))
            throw Error(path, place(12 + 4 * static_cast<std::size_t>(k)),
                        "offset " + std::to_string(offset) + " lies outside the " + std::to_string(in.size()) + "-byte file");
    }
    if (positions == 0) throw Error(path, place(12), "the file has no vertex positions (offset 0)");
    const std::uint64_t P = S * V;
    if (P > kMaxPoints) throw Error(path, place(4), "point count " + std::to_string(P) + " is absurd (limit " + std::to_string(kMaxPoints) + ")");
    if (positions + P * 16 > in.size())
        throw Error(path, place(12),
                    std::to_string(S) + " strands of " + std::to_string(V) + " points need " + std::to_string(P * 16) +
                        " bytes of positions from byte " + std::to_string(positions) + ", past the end of the " +
                        std::to_string(in.size()) + "-byte file (truncated?)");
    Strands out;
    out.points.resize(P);
    out.offsets.resize(S + 1);
    const float scale = static_cast<float>(kCentimetresPerMetre);
    for (std::uint64_t i = 0; i < P; ++i) {
        const std::byte* p = in.data() + positions + i * 16;
        out.points[i] = glm::vec3(get<float>(p), get<float>(p + 4), get<float>(p + 8)) * scale;
    }
    for (std::uint64_t s = 0; s <= S; ++s) out.offsets[s] = static_cast<std::uint32_t>(s * V);
    out.axes_stated = true;
    out.validate(path);
    return out;
}

namespace {

// A PLY scalar type, resolved once from its header name (the records are read by a switch, not by names).
enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64, Unknown };

struct PlyTypeName {
    const char* name;
    PlyType type;
    std::size_t size;
};
constexpr PlyTypeName kPlyTypes[] = {
    {"char", PlyType::Int8, 1},     {"int8", PlyType::Int8, 1},       {"uchar", PlyType::UInt8, 1},   {"uint8", PlyType::UInt8, 1},
    {"short", PlyType::Int16, 2},   {"int16", PlyType::Int16, 2},     {"ushort", PlyType::UInt16, 2}, {"uint16", PlyType::UInt16, 2},
    {"int", PlyType::Int32, 4},     {"int32", PlyType::Int32, 4},     {"uint", PlyType::UInt32, 4},   {"uint32", PlyType::UInt32, 4},
    {"float", PlyType::Float32, 4}, {"float32", PlyType::Float32, 4}, {"double", PlyType::Float64, 8}, {"float64", PlyType::Float64, 8},
};

struct PlyProperty {
    std::string name, type_name;
    PlyType type = PlyType::Unknown;
    std::size_t size = 0, offset = 0;  // bytes, and within the record
    bool is_float() const { return type == PlyType::Float32 || type == PlyType::Float64; }
};
struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
    std::size_t record = 0;
    const PlyProperty* find(const std::string& n) const {
        for (const PlyProperty& p : properties)
            if (p.name == n) return &p;
        return nullptr;
    }
};

double ply_value(const std::byte* p, PlyType t) {
    switch (t) {
        case PlyType::Int8: return get<std::int8_t>(p);
        case PlyType::UInt8: return get<std::uint8_t>(p);
        case PlyType::Int16: return get<std::int16_t>(p);
        case PlyType::UInt16: return get<std::uint16_t>(p);
        case PlyType::Int32: return get<std::int32_t>(p);
        case PlyType::UInt32: return get<std::uint32_t>(p);
        case PlyType::Float32: return get<float>(p);
        case PlyType::Float64: return get<double>(p);
        case PlyType::Unknown: break;
    }
    return 0.0;  // unreachable: the header refuses unknown types
}

}  // namespace

Strands parse_ply(const std::vector<std::byte>& in, const fs::path& path) {
    const std::string_view text(reinterpret_cast<const char*>(in.data()), std::min(in.size(), kMaxPlyHeaderBytes));
    if (text.substr(0, 4) != "ply\n") throw Error(path, place(0), "not a PLY file (it does not start with \"ply\")");
    const std::size_t end = text.find("end_header\n");
    if (end == std::string_view::npos)
        throw Error(path, "header", "no \"end_header\" line in the first " + std::to_string(kMaxPlyHeaderBytes) + " bytes");
    const std::size_t data_begin = end + 11;
    std::vector<PlyElement> elements;
    bool binary_le = false;
    std::istringstream header{std::string(text.substr(4, end - 4))};
    std::string line;
    for (int number = 2; std::getline(header, line); ++number) {
        const std::string where = "header line " + std::to_string(number);
        std::istringstream words(line);
        std::string key;
        words >> key;
        if (key.empty() || key == "comment" || key == "obj_info") continue;
        if (key == "format") {
            std::string format, version;
            words >> format >> version;
            if (format != "binary_little_endian" || version != "1.0")
                throw Error(path, where, "format '" + format + " " + version + "': coif reads binary_little_endian 1.0 only");
            binary_le = true;
        } else if (key == "element") {
            PlyElement e;
            std::string count;
            words >> e.name >> count;
            const auto [ptr, ec] = std::from_chars(count.data(), count.data() + count.size(), e.count);
            if (e.name.empty() || ec != std::errc() || ptr != count.data() + count.size())
                throw Error(path, where, "expected \"element NAME COUNT\"");
            elements.push_back(std::move(e));
        } else if (key == "property") {
            if (elements.empty()) throw Error(path, where, "a property before any element");
            PlyProperty p;
            words >> p.type_name >> p.name;
            if (p.type_name == "list") throw Error(path, where, "list properties are not supported (hairutil's strands have none)");
            for (const PlyTypeName& t : kPlyTypes)
                if (p.type_name == t.name) p.type = t.type, p.size = t.size;
            if (p.type == PlyType::Unknown || p.name.empty()) throw Error(path, where, "unknown property type '" + p.type_name + "'");
            PlyElement& e = elements.back();
            p.offset = e.record;
            e.record += p.size;
            e.properties.push_back(std::move(p));
        } else {
            throw Error(path, where, "unknown header keyword '" + key + "'");
        }
    }
    if (!binary_le) throw Error(path, "header", "no format line");
    // Where each element's records start, checked against the file size before anything is allocated.
    std::uint64_t at = data_begin;
    const PlyElement *vertex = nullptr, *strand = nullptr;
    std::uint64_t vertex_at = 0, strand_at = 0;
    for (const PlyElement& e : elements) {
        if (e.record == 0 && e.count > 0) throw Error(path, "element " + e.name, "has records but no properties");
        if (e.count > (in.size() - std::min<std::uint64_t>(at, in.size())) / std::max<std::size_t>(e.record, 1))
            throw Error(path, "element " + e.name,
                        std::to_string(e.count) + " records of " + std::to_string(e.record) + " bytes do not fit in the rest of the " +
                            std::to_string(in.size()) + "-byte file (truncated?)");
        if (e.name == "vertex") vertex = &e, vertex_at = at;
        if (e.name == "strand") strand = &e, strand_at = at;
        at += e.count * e.record;
    }
    if (at != in.size())
        throw Error(path, place(at), std::to_string(in.size() - at) + " bytes after the last element the header announces");
    if (!vertex) throw Error(path, "header", "no vertex element");
    if (!strand || !strand->find("nsegs")) throw Error(path, "header", "no strand element with an nsegs property (not hairutil strands?)");
    const PlyProperty* axes[3] = {vertex->find("x"), vertex->find("y"), vertex->find("z")};
    for (const PlyProperty* a : axes)
        if (!a || !a->is_float()) throw Error(path, "element vertex", "needs float or double properties x, y and z");
    const PlyProperty& nsegs = *strand->find("nsegs");
    if (nsegs.is_float()) throw Error(path, "element strand", "nsegs must be an integer property");
    if (strand->count == 0) throw Error(path, "element strand", "the file holds no strands");
    if (strand->count > kMaxStrands || vertex->count > kMaxPoints)
        throw Error(path, "header", "strand or vertex count is absurd (limits " + std::to_string(kMaxStrands) + ", " + std::to_string(kMaxPoints) + ")");

    Strands out;
    out.offsets.resize(strand->count + 1);
    std::uint64_t total = 0;
    for (std::uint64_t s = 0; s < strand->count; ++s) {
        const double n = ply_value(in.data() + strand_at + s * strand->record + nsegs.offset, nsegs.type);
        if (n < 1) throw Error(path, "strand " + std::to_string(s), "has " + std::to_string(static_cast<long long>(n)) + " segments (at least 1)");
        total += static_cast<std::uint64_t>(n) + 1;
        if (total > vertex->count)
            throw Error(path, "strand " + std::to_string(s), "strand point counts add up to more than the " + std::to_string(vertex->count) + " vertices");
        out.offsets[s + 1] = static_cast<std::uint32_t>(total);
    }
    if (total != vertex->count)
        throw Error(path, "element strand", "strand point counts add up to " + std::to_string(total) + ", not the " +
                                                std::to_string(vertex->count) + " vertices");
    out.points.resize(vertex->count);
    for (std::uint64_t i = 0; i < vertex->count; ++i) {
        const std::byte* r = in.data() + vertex_at + i * vertex->record;
        for (int c = 0; c < 3; ++c) out.points[i][c] = static_cast<float>(ply_value(r + axes[c]->offset, axes[c]->type));
    }
    out.validate(path);
    return out;
}

}  // namespace coif
