#include "online/shells/hair_asset.h"

#include <algorithm>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numeric>
#include <nlohmann/json.hpp>
#include <type_traits>

#include "models/core/atomic_file.h"
#include "models/core/bytes.h"
#include "models/core/checksum.h"
#include "models/core/error.h"
#include "models/core/json_field.h"

namespace coif {
namespace {

constexpr char kMagic[8] = {'C', 'O', 'I', 'F', 'H', 'A', 'I', 'R'};
constexpr std::size_t kHeader = 32;
constexpr std::uint32_t kSections = 20;
// Bounds that no real asset comes near and that keep a hostile one from asking for absurd memory.
constexpr std::uint64_t kMaxElements = 1ull << 31;
constexpr int kMaxLayoutCount = 4096;
constexpr std::size_t kMaxBones = 1 << 16;

static_assert(sizeof(ShellVertex) == 56 && sizeof(MeshRange) == 16 && sizeof(ShellSector) == 48 &&
              sizeof(ShellInstance) == 80 && sizeof(LightingSample) == 96 && sizeof(glm::vec3) == 12 &&
              sizeof(BoneInfluence) == 32);
static_assert(std::is_trivially_copyable_v<ShellVertex> && std::is_trivially_copyable_v<LightingSample>);

std::uint32_t tag(const char (&t)[5]) {
    return std::uint32_t(std::uint8_t(t[0])) | std::uint32_t(std::uint8_t(t[1])) << 8 |
           std::uint32_t(std::uint8_t(t[2])) << 16 | std::uint32_t(std::uint8_t(t[3])) << 24;
}
std::string tag_name(std::uint32_t t) {
    std::string s;
    for (int i = 0; i < 4; ++i) {
        const char c = static_cast<char>((t >> (8 * i)) & 0xff);
        s += (c >= 32 && c < 127) ? c : '?';
    }
    return s;
}

nlohmann::json vec_json(glm::vec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); }
nlohmann::json vec_json(glm::vec4 v) { return nlohmann::json::array({v.x, v.y, v.z, v.w}); }

class Writer {
public:
    template <class T>
    void section(const char (&name)[5], std::span<const T> items) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes::put(out, tag(name));
        bytes::put(out, static_cast<std::uint32_t>(sizeof(T)));
        bytes::put(out, static_cast<std::uint64_t>(items.size()));
        const auto* p = reinterpret_cast<const std::byte*>(items.data());
        out.insert(out.end(), p, p + items.size_bytes());
        while (out.size() % 8) out.push_back(std::byte{0});
        ++count;
    }
    std::vector<std::byte> out = std::vector<std::byte>(kHeader, std::byte{0});
    std::uint32_t count = 0;
};

nlohmann::json meta_json(const CookedShells& c) {
    const PreparedShells& p = c.shells;
    const DiskLayout& L = p.layout;
    nlohmann::json j;
    j["format"] = "coif-hair-asset";
    j["style"] = c.name;
    j["database"] = c.database;
    j["database_records"] = c.database_records;
    j["coif_version"] = COIF_VERSION;
    j["layout"] = {{"core_radius", L.core_radius}, {"layers", L.layers}, {"s_t", L.s_t}, {"s_u", L.s_u},
                   {"grid_s", L.grid_s}, {"grid_r", L.grid_r}, {"mesh_t", L.mesh_t}, {"mesh_u", L.mesh_u},
                   {"gaussian_width", L.gaussian_width}};
    // Prototypes of their own layer count (HairStyle::layout_of): every prototype's, in slot order; absent when all have
    // the layout's.
    if (std::any_of(p.meshes.begin(), p.meshes.end(), [&](const auto& m) { return m.size() != static_cast<std::size_t>(L.layers); })) {
        nlohmann::json layers = nlohmann::json::array();
        for (const auto& m : p.meshes) layers.push_back(m.size());
        j["prototype_layers"] = std::move(layers);
    }
    j["lighting_rows"] = p.lighting_rows;
    j["bounds"] = {vec_json(p.bounds_min), vec_json(p.bounds_max)};
    j["frame"] = {vec_json(c.frame_min), vec_json(c.frame_max)};
    j["tangent_spread"] = c.tangent_spread;
    j["auto_fiber_radius"] = c.auto_fiber_radius;
    j["shadow_strands"] = c.shadow_strands;
    const RecordAtlas& a = c.atlas;
    nlohmann::json lo = nlohmann::json::array(), scale = nlohmann::json::array();
    for (int part = 0; part < kAtlasParts; ++part) {
        lo.push_back(vec_json(a.lo[part]));
        scale.push_back(vec_json(a.scale[part]));
    }
    j["atlas"] = {{"width", a.width}, {"height", a.height}, {"tiles_per_row", a.tiles_per_row}, {"views", a.views},
                  {"hrir_length", a.hrir_length}, {"lo", lo}, {"scale", scale}, {"re_norm", a.re_norm}};
    const DensityGrid& g = c.grid;
    j["grid"] = {{"dims", {g.dims.x, g.dims.y, g.dims.z}}, {"origin", vec_json(g.origin)}, {"voxel", g.voxel},
                 {"strands_min", vec_json(g.strands_min)}, {"strands_max", vec_json(g.strands_max)}};
    j["params"] = gl::shell_settings_json(c.defaults);
    nlohmann::json turn = nlohmann::json::array();
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) turn.push_back(c.body_orientation[col][row]);
    j["body_orientation"] = turn;
    j["bones"] = c.skinning ? c.skinning->bones : std::vector<std::string>{};
    return j;
}

// ---- reading ----------------------------------------------------------------------------------------

class Reader {
public:
    Reader(std::span<const std::byte> b, const std::filesystem::path& f) : data(b), file(f) {}

    [[noreturn]] void fail(std::size_t at, const std::string& what) const {
        throw Error(file, "byte " + std::to_string(at), what);
    }
    [[noreturn]] void fail(const std::string& place, const std::string& what) const { throw Error(file, place, what); }

    // The next section, which must be `name` with elements of T, copied.
    template <class T>
    std::vector<T> section(const char (&name)[5]) {
        const std::span<const T> items = next<T>(name);
        // Copied once into uninitialised storage (a sized vector would zero it first: twice the page faults).
        return std::vector<T>(items.begin(), items.end());
    }
    // The same, viewed in place when the bytes are kept alive (a mapped file), else copied.
    template <class T>
    Bulk<T> bulk(const char (&name)[5]) {
        if (!keeper) return section<T>(name);
        return Bulk<T>(next<T>(name), keeper);
    }

    std::span<const std::byte> data;
    const std::filesystem::path& file;
    std::shared_ptr<const void> keeper;  // keeps `data` alive, when it may be viewed after parsing
    std::size_t at = kHeader;

private:
    // The next section's elements, where they lie. The section starts 8-byte aligned in a page-aligned mapping or
    // buffer, aligned enough for T.
    template <class T>
    std::span<const T> next(const char (&name)[5]) {
        const std::size_t start = at;
        if (data.size() - at < 16) fail(at, "truncated: section " + std::string(name) + " is missing");
        const auto t = bytes::get<std::uint32_t>(data.data() + at);
        const auto size = bytes::get<std::uint32_t>(data.data() + at + 4);
        const auto count = bytes::get<std::uint64_t>(data.data() + at + 8);
        if (t != tag(name)) fail(at, "expected section " + std::string(name) + ", found " + tag_name(t));
        if (size != sizeof(T))
            fail(at + 4, "section " + std::string(name) + " has elements of " + std::to_string(size) + " bytes (expected " +
                             std::to_string(sizeof(T)) + ")");
        if (count > kMaxElements) fail(at + 8, "section " + std::string(name) + ": absurd element count " + std::to_string(count));
        at += 16;
        const std::uint64_t n = count * sizeof(T);
        if (n > data.size() - at)
            fail(start, "truncated: section " + std::string(name) + " needs " + std::to_string(n) + " bytes, " +
                            std::to_string(data.size() - at) + " are left");
        const std::span<const T> items(reinterpret_cast<const T*>(data.data() + at), count);
        at += n;
        const std::size_t padded = (at + 7) / 8 * 8;
        if (padded > data.size()) fail(at, "truncated: section " + std::string(name) + "'s padding is missing");
        at = padded;
        return items;
    }
};

bool finite(float v) { return std::isfinite(v); }
template <int N>
bool finite(const glm::vec<N, float>& v) {
    for (int i = 0; i < N; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}
bool finite(const glm::mat4& m) { return finite(m[0]) && finite(m[1]) && finite(m[2]) && finite(m[3]); }

template <int N>
glm::vec<N, float> vec_of(const nlohmann::json& j, const std::string& place, const Reader& r) {
    const std::string expected = "expected " + std::to_string(N) + " numbers";
    if (!j.is_array() || j.size() != N) r.fail(place, expected);
    glm::vec<N, float> v;
    for (int i = 0; i < N; ++i) {
        if (!j[i].is_number()) r.fail(place, expected);
        v[i] = j[i].get<float>();
    }
    if (!finite(v)) r.fail(place, "not finite");
    return v;
}

template <class T>
T field(const nlohmann::json& j, const char* key, const char* where, const Reader& r) {
    try {
        return json_field<T>(j, key, where);
    } catch (const Error& e) {
        r.fail(e.place(), e.problem());
    }
}
int int_in(const nlohmann::json& j, const char* key, const char* where, int lo, int hi, const Reader& r) {
    const auto v = field<long long>(j, key, where, r);
    if (v < lo || v > hi)
        r.fail(std::string(where) + "/" + key, "must be " + std::to_string(lo) + ".." + std::to_string(hi) + ", not " + std::to_string(v));
    return static_cast<int>(v);
}
double double_of(const nlohmann::json& j, const char* key, const char* where, const Reader& r) {
    const auto v = field<double>(j, key, where, r);
    if (!std::isfinite(v) || std::abs(v) > 3.0e38) r.fail(std::string(where) + "/" + key, "not a finite float");
    return v;
}
float float_of(const nlohmann::json& j, const char* key, const char* where, const Reader& r) {
    return static_cast<float>(double_of(j, key, where, r));
}

}  // namespace

std::vector<std::byte> hair_asset_bytes(const CookedShells& c) {
    const PreparedShells& p = c.shells;
    Writer w;
    const std::string meta = meta_json(c).dump();
    w.section("META", std::span<const char>(meta.data(), meta.size()));
    w.section("VERT", std::span<const ShellVertex>(p.vertices));
    w.section("INDX", std::span<const std::uint32_t>(p.indices));
    std::vector<MeshRange> meshes;
    for (const auto& proto : p.meshes) meshes.insert(meshes.end(), proto.begin(), proto.end());
    w.section("MESH", std::span<const MeshRange>(meshes));
    std::vector<std::uint32_t> protos(p.prototypes.begin(), p.prototypes.end());
    w.section("PROT", std::span<const std::uint32_t>(protos));
    w.section("SECT", std::span<const ShellSector>(p.sectors));
    std::vector<std::uint32_t> cluster_proto(p.cluster_proto.begin(), p.cluster_proto.end());
    w.section("CPRO", std::span<const std::uint32_t>(cluster_proto));
    w.section("INST", std::span<const ShellInstance>(p.instances));
    w.section("CCEN", std::span<const glm::vec3>(p.cluster_centre));
    w.section("SAMP", std::span<const LightingSample>(p.samples));
    w.section("ATLS", std::span<const std::uint8_t>(c.atlas.texels));
    w.section("MALP", std::span<const float>(c.atlas.mean_alpha));
    w.section("MA0_", std::span<const float>(c.atlas.mean_a0));
    w.section("GDIA", std::span<const glm::vec4>(c.grid.diagonal_xy));
    w.section("GOFF", std::span<const glm::vec2>(c.grid.off_diagonal));
    w.section("ROOT", std::span<const glm::vec3>(c.roots));
    w.section("SPNT", std::span<const glm::vec3>(c.shadow_source.points));
    w.section("SOFF", std::span<const std::uint32_t>(c.shadow_source.offsets));
    w.section("SCLU", std::span<const std::uint32_t>(c.shadow_strand_cluster));
    w.section("SKIN", c.skinning ? std::span<const BoneInfluence>(c.skinning->clusters) : std::span<const BoneInfluence>());
    std::vector<std::byte>& out = w.out;
    std::memcpy(out.data(), kMagic, 8);
    std::memcpy(out.data() + 8, &kHairAssetVersion, 4);
    std::memcpy(out.data() + 12, &w.count, 4);
    const std::uint64_t size = out.size();
    std::memcpy(out.data() + 16, &size, 8);
    const std::uint64_t sum = checksum(std::span<const std::byte>(out).subspan(kHeader));
    std::memcpy(out.data() + 24, &sum, 8);
    return out;
}

void write_hair_asset(const std::filesystem::path& path, const CookedShells& cooked) {
    write_file_atomic(path, hair_asset_bytes(cooked));
}

namespace {

// `keeper`, when not null, keeps `data` alive: the large arrays are then viewed in place rather than copied.
CookedShells parse(std::span<const std::byte> data, const std::filesystem::path& file, std::shared_ptr<const void> keeper) {
    Reader r(data, file);
    r.keeper = std::move(keeper);
    if (data.size() < kHeader)
        r.fail(data.size(), "truncated: " + std::to_string(data.size()) + " bytes is shorter than the 32-byte header");
    if (std::memcmp(data.data(), kMagic, 8) != 0) r.fail(0, "not a coif hair asset (bad magic)");
    const auto version = bytes::get<std::uint32_t>(data.data() + 8);
    if (version != kHairAssetVersion)
        r.fail(8, "asset format version " + std::to_string(version) + " (this coif reads version " +
                      std::to_string(kHairAssetVersion) + "; bake the asset again with this coif)");
    const auto sections = bytes::get<std::uint32_t>(data.data() + 12);
    if (sections != kSections) r.fail(12, std::to_string(sections) + " sections (version " + std::to_string(kHairAssetVersion) + " has " + std::to_string(kSections) + ")");
    const auto size = bytes::get<std::uint64_t>(data.data() + 16);
    if (size != data.size())
        r.fail(16, "the header says " + std::to_string(size) + " bytes, the file has " + std::to_string(data.size()) +
                       " (truncated or extended)");
    const auto sum = bytes::get<std::uint64_t>(data.data() + 24);
    if (sum != checksum(data.subspan(kHeader))) r.fail(24, "checksum mismatch (the file is corrupt)");

    CookedShells c;
    c.source = file.string();
    const std::vector<char> meta_text = r.section<char>("META");
    const nlohmann::json meta = [&] {
        try {
            return parse_json(std::string_view(meta_text.data(), meta_text.size()), file);
        } catch (const Error& e) {
            r.fail("META: " + e.place(), e.problem());
        }
    }();
    if (!meta.is_object() || meta.value("format", "") != "coif-hair-asset") r.fail("META", "not a coif hair asset's metadata");
    c.name = field<std::string>(meta, "style", "META", r);
    c.database = field<std::string>(meta, "database", "META", r);
    c.database_records = field<std::uint64_t>(meta, "database_records", "META", r);
    PreparedShells& p = c.shells;
    if (!meta.contains("layout") || !meta["layout"].is_object()) r.fail("META/layout", "missing");
    const nlohmann::json& lj = meta["layout"];
    DiskLayout& L = p.layout;
    L.layers = int_in(lj, "layers", "META/layout", 1, 64, r);
    L.s_t = int_in(lj, "s_t", "META/layout", 1, kMaxLayoutCount, r);
    L.s_u = int_in(lj, "s_u", "META/layout", 1, kMaxLayoutCount, r);
    L.grid_s = int_in(lj, "grid_s", "META/layout", 1, kMaxLayoutCount, r);
    L.grid_r = int_in(lj, "grid_r", "META/layout", 1, kMaxLayoutCount, r);
    L.mesh_t = int_in(lj, "mesh_t", "META/layout", 1, kMaxMeshSubdivision, r);
    L.mesh_u = int_in(lj, "mesh_u", "META/layout", 1, kMaxMeshSubdivision, r);
    L.core_radius = double_of(lj, "core_radius", "META/layout", r);
    L.gaussian_width = double_of(lj, "gaussian_width", "META/layout", r);
    if (!(L.core_radius >= 0 && L.core_radius < 1)) r.fail("META/layout/core_radius", "must be in [0, 1)");
    if (L.sector_count() > kMaxElements) r.fail("META/layout", "absurd sector count");
    std::vector<int> proto_layers;  // empty: every prototype has the layout's
    if (meta.contains("prototype_layers")) {
        const nlohmann::json& pl = meta["prototype_layers"];
        if (!pl.is_array() || pl.empty() || pl.size() > kMaxElements) r.fail("META/prototype_layers", "expected a layer count per prototype");
        for (std::size_t q = 0; q < pl.size(); ++q) {
            if (!pl[q].is_number_integer() || pl[q].get<long long>() < 1 || pl[q].get<long long>() > 64)
                r.fail("META/prototype_layers/" + std::to_string(q), "must be a whole number 1..64");
            proto_layers.push_back(pl[q].get<int>());
        }
    }
    p.lighting_rows = int_in(meta, "lighting_rows", "META", 2, 1 << 16, r);
    const auto box = [&](const char* key, glm::vec3& lo, glm::vec3& hi) {
        if (!meta.contains(key) || !meta[key].is_array() || meta[key].size() != 2)
            r.fail(std::string("META/") + key, "expected [min, max]");
        lo = vec_of<3>(meta[key][0], std::string("META/") + key + "/0", r);
        hi = vec_of<3>(meta[key][1], std::string("META/") + key + "/1", r);
    };
    box("bounds", p.bounds_min, p.bounds_max);
    box("frame", c.frame_min, c.frame_max);
    c.tangent_spread = float_of(meta, "tangent_spread", "META", r);
    c.auto_fiber_radius = float_of(meta, "auto_fiber_radius", "META", r);
    if (!(c.auto_fiber_radius > 0)) r.fail("META/auto_fiber_radius", "must be > 0");
    c.shadow_strands = field<std::uint64_t>(meta, "shadow_strands", "META", r);
    if (!meta.contains("atlas") || !meta["atlas"].is_object()) r.fail("META/atlas", "missing");
    const nlohmann::json& aj = meta["atlas"];
    RecordAtlas& a = c.atlas;
    a.width = int_in(aj, "width", "META/atlas", 1, 1 << 16, r);
    a.height = int_in(aj, "height", "META/atlas", 1, 1 << 16, r);
    a.tiles_per_row = int_in(aj, "tiles_per_row", "META/atlas", 1, 1 << 16, r);
    a.views = int_in(aj, "views", "META/atlas", 1, 4096, r);
    a.hrir_length = int_in(aj, "hrir_length", "META/atlas", 1, 4096, r);
    a.re_norm = float_of(aj, "re_norm", "META/atlas", r);
    for (int part = 0; part < kAtlasParts; ++part) {
        if (!aj.contains("lo") || !aj["lo"].is_array() || aj["lo"].size() != kAtlasParts || !aj.contains("scale") ||
            !aj["scale"].is_array() || aj["scale"].size() != kAtlasParts)
            r.fail("META/atlas", "lo and scale must be 3 × 4 numbers");
        a.lo[part] = vec_of<4>(aj["lo"][part], "META/atlas/lo", r);
        a.scale[part] = vec_of<4>(aj["scale"][part], "META/atlas/scale", r);
        if (!glm::all(glm::greaterThan(a.scale[part], glm::vec4(0.0f)))) r.fail("META/atlas/scale", "must be > 0");
    }
    if (a.width != a.tiles_per_row * (a.hrir_length + 2)) r.fail("META/atlas", "width does not match tiles_per_row × (hrir_length + 2)");
    if (!meta.contains("grid") || !meta["grid"].is_object()) r.fail("META/grid", "missing");
    const nlohmann::json& gj = meta["grid"];
    DensityGrid& g = c.grid;
    if (!gj.contains("dims") || !gj["dims"].is_array() || gj["dims"].size() != 3) r.fail("META/grid/dims", "expected 3 integers");
    for (int i = 0; i < 3; ++i) {
        if (!gj["dims"][i].is_number_integer()) r.fail("META/grid/dims", "expected 3 integers");
        const auto d = gj["dims"][i].get<long long>();
        if (d < 1 || d > 512) r.fail("META/grid/dims", "each must be 1..512");
        g.dims[i] = static_cast<int>(d);
    }
    g.origin = vec_of<3>(gj.value("origin", nlohmann::json()), "META/grid/origin", r);
    g.voxel = float_of(gj, "voxel", "META/grid", r);
    if (!(g.voxel > 0)) r.fail("META/grid/voxel", "must be > 0");
    g.strands_min = vec_of<3>(gj.value("strands_min", nlohmann::json()), "META/grid/strands_min", r);
    g.strands_max = vec_of<3>(gj.value("strands_max", nlohmann::json()), "META/grid/strands_max", r);
    if (!meta.contains("body_orientation") || !meta["body_orientation"].is_array() || meta["body_orientation"].size() != 9)
        r.fail("META/body_orientation", "expected 9 numbers");
    for (int i = 0; i < 9; ++i) {
        if (!meta["body_orientation"][i].is_number()) r.fail("META/body_orientation", "expected 9 numbers");
        c.body_orientation[i / 3][i % 3] = meta["body_orientation"][i].get<float>();
    }
    if (!finite(c.body_orientation[0]) || !finite(c.body_orientation[1]) || !finite(c.body_orientation[2]))
        r.fail("META/body_orientation", "not finite");
    const std::vector<std::string> bones = field<std::vector<std::string>>(meta, "bones", "META", r);
    if (bones.size() > kMaxBones) r.fail("META/bones", "absurd bone count " + std::to_string(bones.size()));
    if (!meta.contains("params")) r.fail("META/params", "missing");
    try {
        c.defaults = gl::shell_settings_from_json(meta["params"], file.string());
    } catch (const Error& e) {
        r.fail("META/params: " + e.place(), e.problem());
    }

    // The arrays, and every count and index they must agree on.
    p.vertices = r.bulk<ShellVertex>("VERT");
    p.indices = r.bulk<std::uint32_t>("INDX");
    const std::vector<MeshRange> meshes = r.section<MeshRange>("MESH");
    const std::vector<std::uint32_t> protos = r.section<std::uint32_t>("PROT");
    p.sectors = r.section<ShellSector>("SECT");
    const std::vector<std::uint32_t> cluster_proto = r.section<std::uint32_t>("CPRO");
    p.instances = r.section<ShellInstance>("INST");
    p.cluster_centre = r.section<glm::vec3>("CCEN");
    p.samples = r.section<LightingSample>("SAMP");
    a.texels = r.bulk<std::uint8_t>("ATLS");
    a.mean_alpha = r.section<float>("MALP");
    a.mean_a0 = r.section<float>("MA0_");
    g.diagonal_xy = r.bulk<glm::vec4>("GDIA");
    g.off_diagonal = r.bulk<glm::vec2>("GOFF");
    c.roots = r.section<glm::vec3>("ROOT");
    c.shadow_source.points = r.bulk<glm::vec3>("SPNT");
    c.shadow_source.offsets = r.bulk<std::uint32_t>("SOFF");
    c.shadow_strand_cluster = r.section<std::uint32_t>("SCLU");
    std::vector<BoneInfluence> influences = r.section<BoneInfluence>("SKIN");
    if (r.at != data.size()) r.fail(r.at, "unexpected bytes after the last section");

    const std::size_t P = protos.size(), C = cluster_proto.size();
    if (P == 0 || C == 0) r.fail("PROT", "the asset has no clusters");
    p.prototypes.assign(protos.begin(), protos.end());
    if (proto_layers.empty()) proto_layers.assign(P, L.layers);
    if (proto_layers.size() != P) r.fail("META/prototype_layers", "expected one layer count per prototype");
    std::size_t all_layers = 0;
    for (const int n : proto_layers) all_layers += static_cast<std::size_t>(n);
    if (meshes.size() != all_layers) r.fail("MESH", "expected a mesh range per prototype and layer");
    p.meshes.assign(P, {});
    std::size_t next = 0;
    for (std::size_t q = 0; q < P; ++q) {
        for (int j = 0; j < proto_layers[q]; ++j, ++next) {
            const MeshRange& m = meshes[next];
            const std::string place = "MESH " + std::to_string(next);
            if (m.count < 0 || m.count % 3 || m.base_vertex < 0 || m.vertex_count < 1 ||
                std::uint64_t(m.first) + std::uint64_t(m.count) > p.indices.size() ||
                std::uint64_t(m.base_vertex) + std::uint64_t(m.vertex_count) > p.vertices.size())
                r.fail(place, "outside the vertex or index arrays");
            for (std::int32_t i = 0; i < m.count; ++i)
                if (p.indices[m.first + static_cast<std::uint32_t>(i)] >= static_cast<std::uint32_t>(m.vertex_count))
                    r.fail(place, "an index outside its mesh's vertices");
            p.meshes[q].push_back(m);
            p.triangles += static_cast<std::size_t>(m.count) / 3;
        }
    }
    if (p.sectors.size() != p.sector_bases().back()) r.fail("SECT", "expected each prototype's layout's sectors");
    const std::size_t atlas_records = a.mean_alpha.size();
    if (a.mean_a0.size() != atlas_records) r.fail("MA0_", "one mean per atlas record expected");
    const std::uint64_t tiles_needed = atlas_records * kAtlasParts;
    const std::uint64_t tile_rows = (tiles_needed + a.tiles_per_row - 1) / a.tiles_per_row;
    if (tile_rows * static_cast<std::uint64_t>(a.views + 2) > static_cast<std::uint64_t>(a.height))
        r.fail("META/atlas", "the atlas is too small for its records");
    if (a.texels.size() != static_cast<std::size_t>(a.width) * a.height * 4) r.fail("ATLS", "expected width × height × 4 bytes");
    for (std::size_t s = 0; s < p.sectors.size(); ++s) {
        const ShellSector& q = p.sectors[s];
        for (int n = 0; n < gl::kMaxShellNeighbours; ++n)
            if (q.id[n] >= atlas_records) r.fail("SECT " + std::to_string(s), "a record id outside the atlas");
        if (!finite(q.weight) || !finite(q.shadow)) r.fail("SECT " + std::to_string(s), "not finite");
        if (!(q.shadow.z >= 0.0f && q.shadow.z <= 1.0f)) r.fail("SECT " + std::to_string(s), "a thinning outside [0, 1]");
    }
    for (const std::uint32_t v : cluster_proto)
        if (v >= P) r.fail("CPRO", "a prototype index out of range");
    p.cluster_proto.assign(cluster_proto.begin(), cluster_proto.end());
    p.cluster_ids.resize(C);
    std::iota(p.cluster_ids.begin(), p.cluster_ids.end(), 0u);
    if (p.instances.size() != C || p.cluster_centre.size() != C) r.fail("INST", "one instance and centre per cluster expected");
    const std::vector<std::size_t> sector_base = p.sector_bases();
    for (std::size_t i = 0; i < C; ++i) {
        const ShellInstance& in = p.instances[i];
        if (!finite(in.model) || in.info.x != sector_base[p.cluster_proto[i]] || in.info.y != i ||
            !finite(p.cluster_centre[i]))
            r.fail("INST " + std::to_string(i), "does not match its cluster");
    }
    if (p.samples.size() != C * static_cast<std::size_t>(p.lighting_rows)) r.fail("SAMP", "expected clusters × lighting_rows samples");
    for (std::size_t i = 0; i < p.samples.size(); ++i) {
        const LightingSample& q = p.samples[i];
        if (!finite(q.position) || !finite(q.tangent) || !finite(q.normal) || !finite(q.tilt_mean) || !finite(q.tilt_a) ||
            !finite(q.tilt_b))
            r.fail("SAMP " + std::to_string(i), "not finite");
    }
    for (std::size_t i = 0; i < p.vertices.size(); ++i) {
        const ShellVertex& v = p.vertices[i];
        if (!finite(v.position) || !finite(v.tangent) || !finite(v.normal) || !finite(v.texcoord) || !finite(v.axis_normal))
            r.fail("VERT " + std::to_string(i), "not finite");
    }
    for (const float v : a.mean_alpha)
        if (!finite(v)) r.fail("MALP", "not finite");
    for (const float v : a.mean_a0)
        if (!finite(v)) r.fail("MA0_", "not finite");
    const std::size_t voxels = static_cast<std::size_t>(g.dims.x) * g.dims.y * g.dims.z;
    if (g.diagonal_xy.size() != voxels || g.off_diagonal.size() != voxels) r.fail("GDIA", "expected one value per voxel");
    for (std::size_t i = 0; i < voxels; ++i)
        if (!finite(g.diagonal_xy[i]) || !finite(g.off_diagonal[i])) r.fail("GDIA", "not finite");
    if (c.roots.size() != C) r.fail("ROOT", "one root per cluster expected");
    for (const glm::vec3& v : c.roots)
        if (!finite(v)) r.fail("ROOT", "not finite");
    const ShadowStrands& st = c.shadow_source;
    if (st.offsets.empty()) {
        if (!st.points.empty() || !c.shadow_strand_cluster.empty()) r.fail("SOFF", "shadow strand points without offsets");
    } else {
        if (st.offsets.size() != c.shadow_strand_cluster.size() + 1 || st.offsets.size() - 1 != c.shadow_strands)
            r.fail("SOFF", "expected one offset per shadow strand and one more (META/shadow_strands)");
        if (st.offsets[0] != 0 || st.offsets[st.offsets.size() - 1] != st.points.size())
            r.fail("SOFF", "must run from 0 to the point count");
        for (std::size_t i = 1; i < st.offsets.size(); ++i)
            if (st.offsets[i] < st.offsets[i - 1]) r.fail("SOFF " + std::to_string(i), "offsets must not decrease");
    }
    for (const glm::vec3& v : st.points)
        if (!finite(v)) r.fail("SPNT", "not finite");
    for (const std::uint32_t v : c.shadow_strand_cluster)
        if (v >= C) r.fail("SCLU", "a cluster index out of range");
    if (bones.empty() != influences.empty()) r.fail("SKIN", "bone weights and bone names go together");
    if (!bones.empty()) {
        if (influences.size() != C) r.fail("SKIN", "one bone influence per cluster expected");
        for (std::size_t i = 0; i < C; ++i)
            for (int k = 0; k < 4; ++k)
                if (influences[i].bone[k] < 0 || static_cast<std::size_t>(influences[i].bone[k]) >= bones.size() ||
                    !(influences[i].weight[k] >= 0.0f && influences[i].weight[k] <= 1.0f))
                    r.fail("SKIN " + std::to_string(i), "a bone outside META/bones or a weight outside [0, 1]");
        c.skinning = StyleSkinning{bones, std::move(influences)};
    }
    return c;
}

}  // namespace

Strands ShadowStrands::strands() const {
    Strands s;
    s.points.assign(points.begin(), points.end());
    s.offsets.assign(offsets.begin(), offsets.end());
    return s;
}

CookedShells parse_hair_asset(std::span<const std::byte> data, const std::filesystem::path& file) {
    return parse(data, file, nullptr);
}

CookedShells read_hair_asset(const std::filesystem::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw Error(path, "", std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        throw Error(path, "", "not a regular file");
    }
    const auto size = static_cast<std::size_t>(st.st_size);
    if (size == 0) {
        ::close(fd);
        throw Error(path, "byte 0", "truncated: the file is empty");
    }
    void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);  // read ahead in one go
    ::close(fd);
    if (map == MAP_FAILED) throw Error(path, "", std::string("cannot map: ") + std::strerror(errno));
    // The mapping lives as long as the arrays viewed in it (Bulk): until the renderer has uploaded them and let go.
    const std::shared_ptr<const void> mapping(map, [size](const void* p) { ::munmap(const_cast<void*>(p), size); });
    return parse(std::span<const std::byte>(static_cast<const std::byte*>(map), size), path, mapping);
}

bool is_hair_asset(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    return in.read(magic, 8) && std::memcmp(magic, kMagic, 8) == 0;
}

}  // namespace coif
