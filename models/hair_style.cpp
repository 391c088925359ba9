#include "models/hair_style.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "models/core/atomic_file.h"
#include "models/core/error.h"
#include "models/core/json_field.h"
#include "models/core/units.h"

namespace coif {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kNonFinite = "__coif_non_finite_number__";  // stands in for NaN/Infinity literals

// Replaces the non-standard literals NaN, Infinity, inf (optionally signed) and numbers that
// overflow a double (1e999) outside strings by a marker string, so that the validator reports them
// at their JSON path instead of failing with a bare syntax error.
std::string mark_non_finite(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            out += c;
            if (c == '\\' && i + 1 < text.size()) out += text[++i];
            else if (c == '"') in_string = false;
            continue;
        }
        if (c == '"') {
            in_string = true;
            out += c;
            continue;
        }
        std::size_t j = i + ((c == '-' || c == '+') ? 1 : 0);
        if (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) {
            std::size_t e = j;
            while (e < text.size() && (std::isdigit(static_cast<unsigned char>(text[e])) || text[e] == '.' || text[e] == 'e' ||
                                       text[e] == 'E' || text[e] == '+' || text[e] == '-'))
                ++e;
            const std::string token(text.substr(i, e - i));
            if (!std::isfinite(std::strtod(token.c_str(), nullptr))) out += std::string("\"") + kNonFinite + "\"";
            else out += token;
            i = e - 1;
            continue;
        }
        bool matched = false;
        for (const char* word : {"NaN", "nan", "Infinity", "infinity", "inf"}) {
            const std::size_t n = std::char_traits<char>::length(word);
            if (text.substr(j, n) == word && (j + n >= text.size() || !std::isalnum(static_cast<unsigned char>(text[j + n])))) {
                out += std::string("\"") + kNonFinite + "\"";
                i = j + n - 1;
                matched = true;
                break;
            }
        }
        if (!matched) out += c;
    }
    return out;
}

// Validating reader: every failure names the file and the JSON pointer of the value.
struct Reader {
    const fs::path& file;

    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw Error(file, "JSON " + (path.empty() ? std::string("/") : path), what);
    }
    static std::string type_name(const json& v) {
        if (v.is_string() && v.get<std::string>() == kNonFinite) return "a non-finite number (NaN or infinity)";
        return std::string(v.type_name());
    }
    const json& field(const json& obj, const std::string& path, const char* key) const {
        if (!obj.is_object()) fail(path, "expected an object, got " + type_name(obj));
        const auto it = obj.find(key);
        if (it == obj.end()) fail(path + "/" + key, "missing field \"" + std::string(key) + "\"");
        return *it;
    }
    double number(const json& v, const std::string& path) const {
        if (v.is_string() && v.get<std::string>() == kNonFinite) fail(path, "NaN or infinity; every number must be finite");
        if (!v.is_number()) fail(path, "expected a number, got " + type_name(v));
        const double x = v.get<double>();
        if (!std::isfinite(x)) fail(path, "NaN or infinity; every number must be finite");
        return x;
    }
    double positive(const json& v, const std::string& path, const char* what) const {
        const double x = number(v, path);
        if (x < 0) fail(path, std::string(what) + " " + std::to_string(x) + " is negative; it must be > 0");
        if (x == 0) fail(path, std::string(what) + " is zero; it must be > 0");
        return x;
    }
    long long integer(const json& v, const std::string& path, long long lo, long long hi) const {
        const double x = number(v, path);
        if (x != std::floor(x)) fail(path, "expected an integer, got " + std::to_string(x));
        if (x < static_cast<double>(lo) || x > static_cast<double>(hi))
            fail(path, number_text(x) + " is out of range [" + std::to_string(lo) + ", " +
                           std::to_string(hi) + "]");
        return static_cast<long long>(x);
    }
    const json& array(const json& v, const std::string& path, std::size_t min, std::size_t max) const {
        if (!v.is_array()) fail(path, "expected an array, got " + type_name(v));
        if (v.size() < min) fail(path, "has " + std::to_string(v.size()) + " entries; at least " + std::to_string(min) + " needed");
        if (v.size() > max) fail(path, "has " + std::to_string(v.size()) + " entries; at most " + std::to_string(max) + " allowed");
        return v;
    }
    std::string string(const json& v, const std::string& path) const {
        if (!v.is_string() || v.get<std::string>() == kNonFinite) fail(path, "expected a string, got " + type_name(v));
        return v.get<std::string>();
    }
    glm::dvec3 vec3(const json& v, const std::string& path) const {
        array(v, path, 3, 3);
        return {number(v[0], path + "/0"), number(v[1], path + "/1"), number(v[2], path + "/2")};
    }
    Spline1 spline1(const json& v, const std::string& path, bool radius, double scale = 1.0) const {
        array(v, path, 1, kMaxControlPoints);
        std::vector<double> c;
        c.reserve(v.size());
        for (std::size_t i = 0; i < v.size(); ++i) {
            const std::string p = path + "/" + std::to_string(i);
            c.push_back(scale * (radius ? positive(v[i], p, "radius") : number(v[i], p)));
        }
        return Spline1(std::move(c));
    }
};

DiskLayout read_layout(const Reader& rd, const json& doc) {
    const json& l = rd.field(doc, "", "layout");
    DiskLayout out;
    const double core = rd.number(rd.field(l, "/layout", "core_radius"), "/layout/core_radius");
    if (core < 0 || core >= 1) rd.fail("/layout/core_radius", "core radius " + std::to_string(core) + " must lie in [0, 1)");
    out.core_radius = core;
    out.layers = static_cast<int>(rd.integer(rd.field(l, "/layout", "layers"), "/layout/layers", 1, kMaxLayers));
    out.s_t = static_cast<int>(rd.integer(rd.field(l, "/layout", "s_t"), "/layout/s_t", 1, kMaxSamplesT));
    out.s_u = static_cast<int>(rd.integer(rd.field(l, "/layout", "s_u"), "/layout/s_u", 1, kMaxSamplesU));
    const json& g = rd.array(rd.field(l, "/layout", "grid"), "/layout/grid", 2, 2);
    out.grid_s = static_cast<int>(rd.integer(g[0], "/layout/grid/0", 1, kMaxGridCells));
    out.grid_r = static_cast<int>(rd.integer(g[1], "/layout/grid/1", 1, kMaxGridCells));
    const json& m = rd.array(rd.field(l, "/layout", "mesh"), "/layout/mesh", 2, 2);
    out.mesh_t = static_cast<int>(rd.integer(m[0], "/layout/mesh/0", 1, kMaxMeshSubdivision));
    out.mesh_u = static_cast<int>(rd.integer(m[1], "/layout/mesh/1", 1, kMaxMeshSubdivision));
    out.gaussian_width = rd.positive(rd.field(l, "/layout", "gaussian_width"), "/layout/gaussian_width", "Gaussian width");
    return out;
}

std::shared_ptr<DensitySource> read_density(const Reader& rd, const json& d, const std::string& path, const DiskLayout& layout) {
    auto out = std::make_shared<DensitySource>();
    const std::string kind = rd.string(rd.field(d, path, "kind"), path + "/kind");
    if (kind == "uniform") {
        out->kind = DensitySource::Kind::Uniform;
        out->value = rd.number(rd.field(d, path, "value"), path + "/value");
        if (out->value < 0) rd.fail(path + "/value", "density " + std::to_string(out->value) + " is negative");
    } else if (kind == "strands") {
        out->kind = DensitySource::Kind::Strands;
        out->strand_weight = rd.positive(rd.field(d, path, "strand_weight"), path + "/strand_weight", "strand weight");
        const std::string sp = path + "/strands";
        const json& runs = rd.array(rd.field(d, path, "strands"), sp, 0, 100'000'000);
        out->strands.reserve(runs.size());
        for (std::size_t r = 0; r < runs.size(); ++r) {
            const std::string rp = sp + "/" + std::to_string(r);
            const json& run = rd.array(runs[r], rp, 3, 1 + 2 * static_cast<std::size_t>(layout.s_t + 1));
            if (run.size() % 2 == 0) rd.fail(rp, "expected [first_plane, v, u_deg, v, u_deg, …] (an odd number of entries)");
            StrandRun sr;
            sr.first_plane = static_cast<int>(rd.integer(run[0], rp + "/0", 0, layout.s_t));
            const std::size_t planes = (run.size() - 1) / 2;
            if (sr.first_plane + planes > static_cast<std::size_t>(layout.s_t) + 1)
                rd.fail(rp, "runs past the last sector plane (" + std::to_string(layout.s_t) + ")");
            for (std::size_t q = 0; q < planes; ++q) {
                const double v = rd.number(run[1 + 2 * q], rp + "/" + std::to_string(1 + 2 * q));
                if (v < 0) rd.fail(rp + "/" + std::to_string(1 + 2 * q), "relative radius v is negative");
                const double u = rd.number(run[2 + 2 * q], rp + "/" + std::to_string(2 + 2 * q)) * kRadiansPerDegree;
                sr.vu.emplace_back(v, u);
            }
            out->strands.push_back(std::move(sr));
        }
    } else if (kind == "grids") {
        out->kind = DensitySource::Kind::Grids;
        const std::string gp = path + "/sectors";
        const json& g = rd.array(rd.field(d, path, "sectors"), gp, layout.sector_count(), layout.sector_count());
        const std::size_t cells = static_cast<std::size_t>(layout.grid_s) * layout.grid_r;
        out->grids.reserve(g.size());
        for (std::size_t s = 0; s < g.size(); ++s) {
            const std::string p = gp + "/" + std::to_string(s);
            const json& a = rd.array(g[s], p, cells, cells);
            std::vector<float> values;
            values.reserve(cells);
            for (std::size_t c = 0; c < cells; ++c) {
                const double x = rd.number(a[c], p + "/" + std::to_string(c));
                if (x < 0) rd.fail(p + "/" + std::to_string(c), "density " + std::to_string(x) + " is negative");
                values.push_back(static_cast<float>(x));
            }
            out->grids.push_back(std::move(values));
        }
    } else {
        rd.fail(path + "/kind", "unknown density kind \"" + kind + "\" (uniform, strands or grids)");
    }
    return out;
}

nlohmann::ordered_json round_json(double x, int digits) {
    if (digits <= 0 || x == 0) return x;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    return std::strtod(buf, nullptr);
}

}  // namespace

// ───────────────────────────── hierarchy ─────────────────────────────

void HairStyle::resolve(const fs::path& file) {
    const std::size_t n = clusters.size();
    std::vector<int> state(n, 0);  // 0 unvisited, 1 on the current chain, 2 done
    for (std::size_t start = 0; start < n; ++start) {
        std::vector<std::size_t> chain;
        std::size_t c = start;
        while (state[c] == 0 && clusters[c].instance_of) {
            state[c] = 1;
            chain.push_back(c);
            const std::size_t next = *clusters[c].instance_of;
            if (next >= n) throw Error(file, "JSON /clusters/" + std::to_string(c) + "/instance_of", "refers to no cluster");
            if (state[next] == 1) {
                std::string cycle;
                bool on = false;
                for (std::size_t k : chain) {
                    if (k == next) on = true;
                    if (on) cycle += clusters[k].name + " → ";
                }
                throw Error(file, "JSON /clusters/" + std::to_string(c) + "/instance_of",
                            "instance references form a cycle: " + cycle + clusters[next].name);
            }
            c = next;
        }
        if (state[c] == 0) {  // a prototype
            if (!clusters[c].shape) throw Error(file, "JSON /clusters/" + std::to_string(c), "has neither geometry nor instance_of");
            clusters[c].prototype = c;
            clusters[c].placement = {};
            state[c] = 2;
        }
        for (std::size_t k = chain.size(); k-- > 0;) {
            Cluster& cl = clusters[chain[k]];
            const Cluster& target = clusters[*cl.instance_of];
            cl.prototype = target.prototype;
            cl.placement = cl.transform.after(target.placement);
            cl.shape = clusters[cl.prototype].shape;
            cl.density = clusters[cl.prototype].density;
            state[chain[k]] = 2;
        }
    }
}

std::vector<MacroCluster> HairStyle::macro_clusters() const {
    std::vector<MacroCluster> out;
    std::map<std::size_t, std::size_t> index;
    for (std::size_t c = 0; c < clusters.size(); ++c)
        if (clusters[c].prototype == c && !clusters[c].instance_of) {
            index[c] = out.size();
            out.push_back({c, {c}});
        }
    for (std::size_t c = 0; c < clusters.size(); ++c)
        if (clusters[c].instance_of) out[index.at(clusters[c].prototype)].members.push_back(c);
    return out;
}

std::size_t HairStyle::prototype_count() const {
    std::size_t n = 0;
    for (const Cluster& c : clusters) n += c.instance_of ? 0 : 1;
    return n;
}

DiskLayout HairStyle::layout_of(std::size_t c) const {
    DiskLayout l = layout;
    const int own = clusters.at(clusters.at(c).prototype).layers;
    if (own > 0) l.layers = own;
    return l;
}

// ───────────────────────────── reading ─────────────────────────────

HairStyle style_from_json(const json& doc, const fs::path& file) {
    const Reader rd{file};
    if (!doc.is_object()) rd.fail("", "a style file is a JSON object, got " + Reader::type_name(doc));
    const std::string format = rd.string(rd.field(doc, "", "format"), "/format");
    if (format != "coif-style") rd.fail("/format", "unknown format \"" + format + "\" (expected \"coif-style\")");
    const json& version = rd.field(doc, "", "version");
    const double ver = rd.number(version, "/version");
    if (ver != kStyleVersion)
        rd.fail("/version", "unknown version " + version.dump() + " (this coif reads version " + std::to_string(kStyleVersion) + ")");
    HairStyle style;
    if (doc.contains("name")) style.name = rd.string(doc["name"], "/name");
    if (doc.contains("units")) style.units = rd.string(doc["units"], "/units");
    if (doc.contains("source")) style.source = doc["source"];
    style.layout = read_layout(rd, doc);

    const json& clusters = rd.array(rd.field(doc, "", "clusters"), "/clusters", 1, kMaxClusters);
    // Memory check before anything is allocated per cluster: density grids of every cluster, each of its own layers.
    std::vector<int> layers(clusters.size(), 0);
    std::uint64_t all_layers = 0;
    for (std::size_t i = 0; i < clusters.size(); ++i) {
        const std::string p = "/clusters/" + std::to_string(i);
        if (clusters[i].is_object() && clusters[i].contains("layers"))
            layers[i] = static_cast<int>(rd.integer(clusters[i]["layers"], p + "/layers", 1, kMaxLayers));
        all_layers += static_cast<std::uint64_t>(layers[i] > 0 ? layers[i] : style.layout.layers);
    }
    const std::uint64_t per_layer = static_cast<std::uint64_t>(style.layout.s_t + 1) * style.layout.s_u * style.layout.grid_s *
                                    style.layout.grid_r * sizeof(float);
    if (per_layer * all_layers > kMaxStyleBytes)
        rd.fail("/layout", "the density grids of " + std::to_string(clusters.size()) + " clusters would need " +
                               std::to_string(per_layer * all_layers >> 20) + " MiB (limit " +
                               std::to_string(kMaxStyleBytes >> 20) + " MiB); lower s_t, s_u, layers or grid");
    std::map<std::string, std::size_t> names;
    for (std::size_t i = 0; i < clusters.size(); ++i) {
        const std::string p = "/clusters/" + std::to_string(i);
        const std::string name = rd.string(rd.field(clusters[i], p, "name"), p + "/name");
        if (!names.emplace(name, i).second) rd.fail(p + "/name", "duplicate cluster name \"" + name + "\"");
    }
    style.clusters.resize(clusters.size());
    for (std::size_t i = 0; i < clusters.size(); ++i) {
        const std::string p = "/clusters/" + std::to_string(i);
        const json& c = clusters[i];
        Cluster& cl = style.clusters[i];
        cl.name = rd.string(c["name"], p + "/name");
        if (c.contains("instance_of")) {
            const std::string target = rd.string(c["instance_of"], p + "/instance_of");
            const auto it = names.find(target);
            if (it == names.end()) rd.fail(p + "/instance_of", "no cluster is named \"" + target + "\"");
            cl.instance_of = it->second;
            const json& t = rd.field(c, p, "transform");
            const std::string tp = p + "/transform";
            cl.transform.scale = rd.positive(rd.field(t, tp, "scale"), tp + "/scale", "scale");
            const json& q = rd.array(rd.field(t, tp, "rotation"), tp + "/rotation", 4, 4);
            const glm::dquat rot(rd.number(q[0], tp + "/rotation/0"), rd.number(q[1], tp + "/rotation/1"),
                                 rd.number(q[2], tp + "/rotation/2"), rd.number(q[3], tp + "/rotation/3"));
            const double norm = glm::length(rot);
            if (!(norm > 1e-12)) rd.fail(tp + "/rotation", "a rotation quaternion [w, x, y, z] must not be zero");
            cl.transform.rotation = rot / norm;
            cl.transform.translation = rd.vec3(rd.field(t, tp, "translation"), tp + "/translation");
            for (const char* geometry_key : {"trajectory", "a", "b", "theta_deg", "density", "layers"})
                if (c.contains(geometry_key))
                    rd.fail(p + "/" + geometry_key, "an instance shares its prototype's geometry and density; remove this field");
            continue;
        }
        const json& tj = rd.array(rd.field(c, p, "trajectory"), p + "/trajectory", 2, kMaxControlPoints);
        std::vector<glm::dvec3> control;
        control.reserve(tj.size());
        for (std::size_t k = 0; k < tj.size(); ++k) control.push_back(rd.vec3(tj[k], p + "/trajectory/" + std::to_string(k)));
        Spline1 a = rd.spline1(rd.field(c, p, "a"), p + "/a", true);
        Spline1 b = rd.spline1(rd.field(c, p, "b"), p + "/b", true);
        Spline1 theta = rd.spline1(rd.field(c, p, "theta_deg"), p + "/theta_deg", false, kRadiansPerDegree);
        try {
            cl.shape = std::make_shared<GeneralizedCylinder>(Spline3(std::move(control)), std::move(a), std::move(b), std::move(theta));
        } catch (const std::invalid_argument& e) {
            rd.fail(p + "/trajectory", e.what());
        }
        cl.layers = layers[i];
        DiskLayout own = style.layout;
        if (cl.layers > 0) own.layers = cl.layers;
        cl.density = read_density(rd, rd.field(c, p, "density"), p + "/density", own);
    }
    if (doc.contains("skinning")) {
        const json& sk = doc["skinning"];
        StyleSkinning s;
        const json& bones = rd.array(rd.field(sk, "/skinning", "bones"), "/skinning/bones", 1, kMaxBones);
        for (std::size_t b = 0; b < bones.size(); ++b) s.bones.push_back(rd.string(bones[b], "/skinning/bones/" + std::to_string(b)));
        const json& cs = rd.array(rd.field(sk, "/skinning", "clusters"), "/skinning/clusters", clusters.size(), clusters.size());
        s.clusters.resize(cs.size());
        for (std::size_t c = 0; c < cs.size(); ++c) {
            const std::string p = "/skinning/clusters/" + std::to_string(c);
            const json& pairs = rd.array(cs[c], p, 1, 4);
            BoneInfluence& in = s.clusters[c];
            float sum = 0.0f;
            for (std::size_t k = 0; k < pairs.size(); ++k) {
                const std::string q = p + "/" + std::to_string(k);
                rd.array(pairs[k], q, 2, 2);
                in.bone[static_cast<int>(k)] = static_cast<int>(rd.integer(pairs[k][0], q + "/0", 0, static_cast<long long>(s.bones.size()) - 1));
                const double w = rd.number(pairs[k][1], q + "/1");
                if (w < 0) rd.fail(q + "/1", "a bone weight must not be negative");
                in.weight[static_cast<int>(k)] = static_cast<float>(w);
                sum += static_cast<float>(w);
            }
            if (!(sum >= kMinWeightSum)) rd.fail(p, "the weights sum to " + std::to_string(sum) + ", below " + std::to_string(kMinWeightSum));
            in.weight /= sum;
        }
        style.skinning = std::move(s);
    }
    style.resolve(file);
    return style;
}

HairStyle parse_style(std::string_view text, const fs::path& file) {
    return style_from_json(parse_json(mark_non_finite(text), file), file);
}

bool style_axes_stated(const HairStyle& style) {
    return style.source.is_object() && style.source.contains("axes") && style.source["axes"].is_string() &&
           style.source["axes"].get<std::string>() == kStyleAxesYUp;
}

glm::mat3 style_source_rotation(const HairStyle& style) {
    glm::mat3 r(1.0f);
    if (!style.source.is_object() || !style.source.contains("rotation_applied")) return r;
    const nlohmann::json& rows = style.source["rotation_applied"];
    if (!rows.is_array() || rows.size() != 3) return r;
    for (int i = 0; i < 3; ++i) {
        if (!rows[i].is_array() || rows[i].size() != 3) return glm::mat3(1.0f);
        for (int j = 0; j < 3; ++j) {
            if (!rows[i][j].is_number()) return glm::mat3(1.0f);
            r[j][i] = rows[i][j].get<float>();  // row i, column j
        }
    }
    return r;
}

HairStyle read_style(const fs::path& path) {
    const std::vector<std::byte> bytes = read_file_bytes(path);
    return parse_style(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

// ───────────────────────────── writing ─────────────────────────────

nlohmann::ordered_json style_to_json(const HairStyle& style) {
    using json = nlohmann::ordered_json;  // fields in a readable order: format and version first
    constexpr int kDigits = 7;  // control points and crossings: float precision is plenty
    const DiskLayout& l = style.layout;
    json doc = json::object();
    doc["format"] = "coif-style";
    doc["version"] = kStyleVersion;
    if (!style.name.empty()) doc["name"] = style.name;
    if (!style.units.empty()) doc["units"] = style.units;
    if (!style.source.empty()) doc["source"] = json(style.source);
    doc["layout"] = {{"core_radius", l.core_radius}, {"layers", l.layers}, {"s_t", l.s_t}, {"s_u", l.s_u},
                     {"grid", {l.grid_s, l.grid_r}}, {"mesh", {l.mesh_t, l.mesh_u}}, {"gaussian_width", round_json(l.gaussian_width, kDigits)}};
    json clusters = json::array();
    for (const Cluster& c : style.clusters) {
        json j = json::object();
        j["name"] = c.name;
        if (c.instance_of) {
            j["instance_of"] = style.clusters[*c.instance_of].name;
            const Similarity& t = c.transform;
            j["transform"] = {{"scale", round_json(t.scale, 9)},
                              {"rotation", {round_json(t.rotation.w, 9), round_json(t.rotation.x, 9), round_json(t.rotation.y, 9), round_json(t.rotation.z, 9)}},
                              {"translation", {round_json(t.translation.x, 9), round_json(t.translation.y, 9), round_json(t.translation.z, 9)}}};
            clusters.push_back(std::move(j));
            continue;
        }
        json traj = json::array();
        for (const glm::dvec3& p : c.shape->trajectory().control())
            traj.push_back({round_json(p.x, kDigits), round_json(p.y, kDigits), round_json(p.z, kDigits)});
        j["trajectory"] = std::move(traj);
        const auto list = [&](const Spline1& s, double scale) {
            json a = json::array();
            for (double x : s.control()) a.push_back(round_json(x * scale, kDigits));
            return a;
        };
        j["a"] = list(c.shape->a_spline(), 1.0);
        j["b"] = list(c.shape->b_spline(), 1.0);
        j["theta_deg"] = list(c.shape->theta_spline(), 1.0 / kRadiansPerDegree);
        if (c.layers > 0) j["layers"] = c.layers;
        const DensitySource& d = *c.density;
        json dj = json::object();
        switch (d.kind) {
            case DensitySource::Kind::Uniform:
                dj = {{"kind", "uniform"}, {"value", d.value}};
                break;
            case DensitySource::Kind::Strands: {
                json runs = json::array();
                for (const StrandRun& r : d.strands) {
                    json run = json::array({r.first_plane});
                    for (const glm::dvec2& vu : r.vu) {
                        // v to 1e-3 of the radius, u to 0.1°: far below a density grid cell.
                        run.push_back(std::round(vu.x * 1000.0) / 1000.0);
                        run.push_back(std::round(vu.y / kRadiansPerDegree * 10.0) / 10.0);
                    }
                    runs.push_back(std::move(run));
                }
                dj = {{"kind", "strands"}, {"strand_weight", d.strand_weight}, {"strands", std::move(runs)}};
                break;
            }
            case DensitySource::Kind::Grids: {
                json sectors = json::array();
                for (const auto& g : d.grids) {
                    json a = json::array();
                    for (float x : g) a.push_back(round_json(x, 6));
                    sectors.push_back(std::move(a));
                }
                dj = {{"kind", "grids"}, {"sectors", std::move(sectors)}};
                break;
            }
        }
        j["density"] = std::move(dj);
        clusters.push_back(std::move(j));
    }
    doc["clusters"] = std::move(clusters);
    if (style.skinning) {
        json cs = json::array();
        for (const BoneInfluence& in : style.skinning->clusters) {
            json pairs = json::array();
            for (int k = 0; k < 4; ++k)
                if (in.weight[k] > 0.0f) pairs.push_back({in.bone[k], round_json(in.weight[k], kDigits)});
            cs.push_back(std::move(pairs));
        }
        doc["skinning"] = {{"bones", style.skinning->bones}, {"clusters", std::move(cs)}};
    }
    return doc;
}

std::string style_text(const HairStyle& style) {
    // One cluster per line keeps a large file readable and diffable; the header is indented.
    nlohmann::ordered_json doc = style_to_json(style);
    nlohmann::ordered_json clusters = std::move(doc["clusters"]);
    doc.erase("clusters");
    nlohmann::ordered_json skinning;
    if (doc.contains("skinning")) {
        skinning = std::move(doc["skinning"]);
        doc.erase("skinning");
    }
    std::string head = doc.dump(2);
    head.pop_back();  // the closing brace
    while (!head.empty() && (head.back() == '\n' || head.back() == ' ')) head.pop_back();
    std::string out = head + ",\n  \"clusters\": [\n";
    for (std::size_t i = 0; i < clusters.size(); ++i) {
        out += "    " + clusters[i].dump();
        out += i + 1 < clusters.size() ? ",\n" : "\n";
    }
    out += "  ]";
    if (!skinning.is_null())  // the bones on one line, the clusters' weights on another
        out += ",\n  \"skinning\": {\n    \"bones\": " + skinning["bones"].dump() + ",\n    \"clusters\": " + skinning["clusters"].dump() + "\n  }";
    out += "\n}\n";
    return out;
}

void write_style(const fs::path& path, const HairStyle& style) { write_file_atomic(path, style_text(style)); }

// ───────────────────────────── densities ─────────────────────────────

glm::dvec2 sector_coordinates(const SectorShape& sector, double v, double u) {
    const double du = sector.u1 - sector.u0, um = 0.5 * (sector.u0 + sector.u1);
    const double s = 0.5 + std::remainder(u - um, kTwoPi) / du;
    const double r = (v - sector.v0) / (sector.v1 - sector.v0);
    return {s * sector.width, r * sector.depth};
}

std::vector<SectorDensity> cluster_sector_densities(const GeneralizedCylinder& shape, const DiskLayout& layout,
                                                    const DensitySource& source) {
    std::vector<SectorDensity> out(layout.sector_count());
    const double lambda = layout.gaussian_width;
    std::vector<std::vector<glm::dvec2>> crossings;
    if (source.kind == DensitySource::Kind::Strands) {
        crossings.resize(static_cast<std::size_t>(layout.s_t) + 1);
        for (const StrandRun& r : source.strands)
            for (std::size_t q = 0; q < r.vu.size(); ++q) crossings[static_cast<std::size_t>(r.first_plane) + q].push_back(r.vu[q]);
    }
    std::vector<glm::dvec2> local;
    for (int i = 0; i <= layout.s_t; ++i)
        for (int j = 0; j < layout.layers; ++j)
            for (int k = 0; k < layout.s_u; ++k) {
                const std::size_t id = layout.sector_index(i, j, k);
                const SectorShape sh = sector_shape(shape, layout, i, j, k);
                switch (source.kind) {
                    case DensitySource::Kind::Uniform:
                        out[id] = density_from_function(layout.grid_s, layout.grid_r, sh.width, sh.depth,
                                                        [&](double, double) { return source.value; });
                        break;
                    case DensitySource::Kind::Grids:
                        out[id].n_s = layout.grid_s;
                        out[id].n_r = layout.grid_r;
                        out[id].width = sh.width;
                        out[id].depth = sh.depth;
                        out[id].rho = source.grids[id];
                        break;
                    case DensitySource::Kind::Strands: {
                        local.clear();
                        const double reach = kGaussianCutoff * lambda;
                        for (const glm::dvec2& vu : crossings[static_cast<std::size_t>(i)]) {
                            const glm::dvec2 x = sector_coordinates(sh, vu.x, vu.y);
                            if (x.x > -reach && x.x < sh.width + reach && x.y > -reach && x.y < sh.depth + reach) local.push_back(x);
                        }
                        out[id] = density_from_points(layout.grid_s, layout.grid_r, sh.width, sh.depth, local, lambda,
                                                      source.strand_weight);
                        break;
                    }
                }
            }
    return out;
}

StyleCounts style_counts(const HairStyle& style) {
    StyleCounts c;
    const DiskLayout& l = style.layout;
    c.clusters = style.clusters.size();
    c.prototypes = style.prototype_count();
    c.instances = c.clusters - c.prototypes;
    const auto macros = style.macro_clusters();
    c.macro_clusters = macros.size();
    for (const auto& m : macros) c.shared_macro_clusters += m.members.size() > 1 ? 1 : 0;
    c.layers = static_cast<std::size_t>(l.layers);
    std::size_t all_layers = 0;  // layered shells of every cluster
    for (std::size_t i = 0; i < style.clusters.size(); ++i) {
        const DiskLayout own = style.layout_of(i);
        all_layers += static_cast<std::size_t>(own.layers);
        c.hsvs += own.hsv_count();
        c.sectors += own.sector_count();
    }
    for (std::size_t i = 0; i < style.clusters.size(); ++i) {
        const Cluster& cl = style.clusters[i];
        if (cl.instance_of) {
            c.geometry_bytes += sizeof(Similarity);
            continue;
        }
        c.geometry_bytes += cl.shape->trajectory().size() * sizeof(glm::dvec3) +
                            (cl.shape->a_spline().size() + cl.shape->b_spline().size() + cl.shape->theta_spline().size()) * sizeof(double);
        if (cl.density->kind == DensitySource::Kind::Strands)
            for (const StrandRun& r : cl.density->strands) c.stored_strands += r.vu.empty() ? 0 : 1;
        // Prototypes' grids only: instances share them.
        c.density_bytes += style.layout_of(i).sector_count() * static_cast<std::uint64_t>(l.grid_s) * l.grid_r * sizeof(float);
    }
    // Layer meshes: position, tangent, normal (3 floats each), texcoord (2), per vertex, plus indices.
    const std::uint64_t verts = static_cast<std::uint64_t>(l.s_t * l.mesh_t + 1) * (l.s_u * l.mesh_u + 1);
    const std::uint64_t tris = static_cast<std::uint64_t>(l.s_t * l.mesh_t) * (l.s_u * l.mesh_u) * 2;
    c.mesh_bytes = (verts * 11 * sizeof(float) + tris * 3 * sizeof(std::uint32_t)) * all_layers;
    return c;
}

}  // namespace coif
