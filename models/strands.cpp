#include "models/strands.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "models/core/atomic_file.h"
#include "models/core/error.h"

namespace coif {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kHairHeaderBytes = 128;
enum HairFlags : std::uint32_t { kSegments = 1, kPoints = 2, kThickness = 4, kTransparency = 8, kColors = 16 };

// Bounds-checked little-endian reader over a file's bytes; every failure names the byte offset.
class Reader {
public:
    Reader(const fs::path& path, const std::vector<std::byte>& bytes) : path_(path), bytes_(bytes) {}
    std::size_t offset() const { return pos_; }
    std::size_t remaining() const { return bytes_.size() - pos_; }
    template <class T>
    T get(const char* what) {
        need(sizeof(T), what);
        T v;
        std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    void read(void* dst, std::size_t n, const char* what) {
        need(n, what);
        std::memcpy(dst, bytes_.data() + pos_, n);
        pos_ += n;
    }
    void need(std::size_t n, const char* what) const {
        if (n > remaining())
            throw Error(path_, "byte " + std::to_string(pos_),
                        std::string("file is truncated: ") + what + " needs " + std::to_string(n) + " bytes, only " +
                            std::to_string(remaining()) + " left");
    }

private:
    const fs::path& path_;
    const std::vector<std::byte>& bytes_;
    std::size_t pos_ = 0;
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void Strands::add_strand(const std::vector<glm::vec3>& strand_points) {
    if (offsets.empty()) offsets.push_back(0);
    points.insert(points.end(), strand_points.begin(), strand_points.end());
    offsets.push_back(static_cast<std::uint32_t>(points.size()));
}

void Strands::add_strands(const Strands& other) {
    if (other.strand_count() == 0) return;
    if (offsets.empty()) offsets.push_back(0);
    const auto base = static_cast<std::uint32_t>(points.size());
    points.insert(points.end(), other.points.begin(), other.points.end());
    for (std::size_t i = 1; i < other.offsets.size(); ++i) offsets.push_back(base + other.offsets[i]);
}

void Strands::validate(const fs::path& source) const {
    if (offsets.empty()) {
        if (!points.empty()) throw Error(source, "strands", "points without strand offsets");
        return;
    }
    if (offsets.front() != 0 || offsets.back() != points.size())
        throw Error(source, "strands", "strand offsets do not cover the point array");
    const auto check_size = [&](std::size_t n, const char* what) {
        if (n != 0 && n != points.size())
            throw Error(source, what, std::to_string(n) + " values for " + std::to_string(points.size()) + " points");
    };
    check_size(thickness.size(), "thickness");
    check_size(transparency.size(), "transparency");
    check_size(colors.size(), "colours");
    for (std::size_t s = 0; s + 1 < offsets.size(); ++s) {
        const std::uint32_t b = offsets[s], e = offsets[s + 1];
        if (e < b) throw Error(source, "strand " + std::to_string(s), "offsets decrease");
        if (e - b < 2)
            throw Error(source, "strand " + std::to_string(s),
                        "has " + std::to_string(e - b) + " point(s); a strand needs at least 2");
        double length = 0;
        for (std::uint32_t i = b; i < e; ++i) {
            if (!finite(points[i]))
                throw Error(source, "strand " + std::to_string(s) + ", point " + std::to_string(i - b),
                            "coordinate is NaN or infinite");
            if (i > b) length += glm::length(glm::dvec3(points[i]) - glm::dvec3(points[i - 1]));
        }
        if (!(length > 0))
            throw Error(source, "strand " + std::to_string(s), "has zero length (all its points coincide)");
    }
    for (std::size_t i = 0; i < thickness.size(); ++i)
        if (!std::isfinite(thickness[i]) || thickness[i] < 0)
            throw Error(source, "thickness of point " + std::to_string(i), "is negative, NaN or infinite");
    for (std::size_t i = 0; i < transparency.size(); ++i)
        if (!std::isfinite(transparency[i]))
            throw Error(source, "transparency of point " + std::to_string(i), "is NaN or infinite");
    for (std::size_t i = 0; i < colors.size(); ++i)
        if (!finite(colors[i])) throw Error(source, "colour of point " + std::to_string(i), "is NaN or infinite");
}

namespace {
// The strand formats, once: read_strands, strand_extensions and strand_format_name read this table.
struct StrandFormat {
    const char* extension;
    const char* name;
    Strands (*parse)(const std::vector<std::byte>&, const fs::path&);
};
constexpr StrandFormat kStrandFormats[] = {
    {".hair", "Yuksel .hair", parse_hair},
    {".data", "USC-HairSalon .data", parse_usc_data},
    {".tfx", "AMD TressFX .tfx", parse_tfx},
    {".ply", "hairutil binary .ply", parse_ply},
};

const StrandFormat* strand_format(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const StrandFormat& f : kStrandFormats)
        if (ext == f.extension) return &f;
    return nullptr;
}
}  // namespace

Strands read_strands(const fs::path& path) {
    const StrandFormat* f = strand_format(path);
    if (!f)
        throw Error(path, "", "unknown strand file extension '" + path.extension().string() + "' (coif reads " +
                                  strand_extensions() + ")");
    return f->parse(read_file_bytes(path), path);
}

const std::string& strand_extensions() {
    static const std::string text = [] {
        std::string t;
        const std::size_t n = std::size(kStrandFormats);
        for (std::size_t i = 0; i < n; ++i) t += std::string(i == 0 ? "" : i + 1 == n ? " or " : ", ") + kStrandFormats[i].extension;
        return t;
    }();
    return text;
}

std::string strand_format_name(const fs::path& path) {
    const StrandFormat* f = strand_format(path);
    return f ? f->name : "unknown format";
}

Strands read_hair(const fs::path& path) { return parse_hair(read_file_bytes(path), path); }

Strands read_usc_data(const fs::path& path) { return parse_usc_data(read_file_bytes(path), path); }

Strands parse_hair(const std::vector<std::byte>& bytes, const fs::path& path) {
    Reader in(path, bytes);
    char magic[4];
    in.read(magic, 4, "the 128-byte header");
    if (std::memcmp(magic, "HAIR", 4) != 0) throw Error(path, "byte 0", "wrong magic: not a .hair file (expected \"HAIR\")");
    in.need(kHairHeaderBytes - 4, "the 128-byte header");
    const std::uint64_t S = in.get<std::uint32_t>("strand count");
    const std::uint64_t P = in.get<std::uint32_t>("point count");
    const std::uint32_t flags = in.get<std::uint32_t>("flags");
    const std::uint32_t default_segments = in.get<std::uint32_t>("default segment count");
    Strands out;
    out.default_thickness = in.get<float>("default thickness");
    out.default_transparency = in.get<float>("default transparency");
    in.read(&out.default_color, 12, "default colour");
    in.read(out.info.data(), out.info.size(), "information string");

    if (S > kMaxStrands)
        throw Error(path, "header", "strand count " + std::to_string(S) + " is absurd (limit " + std::to_string(kMaxStrands) + ")");
    if (P > kMaxPoints)
        throw Error(path, "header", "point count " + std::to_string(P) + " is absurd (limit " + std::to_string(kMaxPoints) + ")");
    if (flags & ~std::uint32_t(31)) throw Error(path, "header", "unknown flag bits " + std::to_string(flags));
    if (!(flags & kPoints)) throw Error(path, "header", "the file has no points array (flag bit 1 is clear)");
    if (S == 0) throw Error(path, "header", "the file holds no strands");

    // The file size must be exactly what the header announces: check before allocating anything.
    std::uint64_t expected = kHairHeaderBytes + P * 12;
    if (flags & kSegments) expected += S * 2;
    if (flags & kThickness) expected += P * 4;
    if (flags & kTransparency) expected += P * 4;
    if (flags & kColors) expected += P * 12;
    if (expected != bytes.size())
        throw Error(path, "header",
                    "the header announces " + std::to_string(S) + " strands and " + std::to_string(P) + " points (" +
                        std::to_string(expected) + " bytes) but the file has " + std::to_string(bytes.size()) + " bytes" +
                        (expected > bytes.size() ? " (truncated?)" : ""));

    std::vector<std::uint16_t> segments;
    if (flags & kSegments) {
        segments.resize(S);
        in.read(segments.data(), S * 2, "segments array");
    } else if (default_segments == 0 || default_segments > 65535) {
        throw Error(path, "header", "no segments array and a default segment count of " + std::to_string(default_segments));
    }
    out.offsets.resize(S + 1);
    out.offsets[0] = 0;
    std::uint64_t total = 0;
    for (std::uint64_t s = 0; s < S; ++s) {
        const std::uint64_t segs = (flags & kSegments) ? segments[s] : default_segments;
        if (segs == 0) throw Error(path, "strand " + std::to_string(s), "has zero segments (a single point, no hair)");
        total += segs + 1;
        if (total > P) break;
        out.offsets[s + 1] = static_cast<std::uint32_t>(total);
    }
    if (total != P)
        throw Error(path, "segments array",
                    "strand point counts add up to " + std::string(total > P ? "more than" : std::to_string(total) + ", not") +
                        " the header's " + std::to_string(P) + " points");
    out.points.resize(P);
    in.read(out.points.data(), P * 12, "points array");
    if (flags & kThickness) {
        out.thickness.resize(P);
        in.read(out.thickness.data(), P * 4, "thickness array");
    }
    if (flags & kTransparency) {
        out.transparency.resize(P);
        in.read(out.transparency.data(), P * 4, "transparency array");
    }
    if (flags & kColors) {
        out.colors.resize(P);
        in.read(out.colors.data(), P * 12, "colours array");
    }
    out.validate(path);
    return out;
}

Strands parse_usc_data(const std::vector<std::byte>& bytes, const fs::path& path) {
    Reader in(path, bytes);
    const std::int32_t S = in.get<std::int32_t>("strand count");
    if (S <= 0) throw Error(path, "byte 0", "strand count " + std::to_string(S) + " is not positive");
    // Every strand needs at least its 4-byte count: refuse absurd counts before allocating.
    if (static_cast<std::uint64_t>(S) > kMaxStrands || static_cast<std::uint64_t>(S) > in.remaining() / 4)
        throw Error(path, "byte 0",
                    "strand count " + std::to_string(S) + " cannot fit in the " + std::to_string(bytes.size()) + "-byte file");
    Strands out;
    out.offsets.reserve(static_cast<std::size_t>(S) + 1);
    out.offsets.push_back(0);
    out.points.reserve(in.remaining() / 16);
    for (std::int32_t s = 0; s < S; ++s) {
        const std::size_t at = in.offset();
        const std::int32_t n = in.get<std::int32_t>("strand point count");
        if (n < 0 || static_cast<std::uint64_t>(n) > in.remaining() / 12)
            throw Error(path, "byte " + std::to_string(at) + " (strand " + std::to_string(s) + ")",
                        "point count " + std::to_string(n) + " does not fit in the rest of the file (truncated?)");
        if (n == 0) throw Error(path, "byte " + std::to_string(at) + " (strand " + std::to_string(s) + ")", "strand has no points");
        if (out.points.size() + static_cast<std::size_t>(n) > kMaxPoints)
            throw Error(path, "strand " + std::to_string(s), "total point count is absurd");
        if (n == 1) {  // a scalp mark without hair (USC convention): skip it
            in.need(12, "point");
            in.get<std::array<float, 3>>("point");
            ++out.skipped_single_point;
            continue;
        }
        const std::size_t first = out.points.size();
        out.points.resize(first + static_cast<std::size_t>(n));
        in.read(out.points.data() + first, static_cast<std::size_t>(n) * 12, "strand points");
        out.offsets.push_back(static_cast<std::uint32_t>(out.points.size()));
    }
    if (in.remaining() != 0)
        throw Error(path, "byte " + std::to_string(in.offset()),
                    std::to_string(in.remaining()) + " bytes after the last of the " + std::to_string(S) +
                        " strands the header announces");
    if (out.strand_count() == 0) throw Error(path, "", "the file holds no strand with more than one point");
    out.validate(path);
    return out;
}

void write_hair(const fs::path& path, const Strands& strands) {
    strands.validate(path);
    const std::size_t S = strands.strand_count(), P = strands.points.size();
    if (S == 0) throw Error(path, "", "refusing to write a .hair file with no strands");
    for (std::size_t s = 0; s < S; ++s)
        if (strands.point_count(s) - 1 > 65535)
            throw Error(path, "strand " + std::to_string(s), "has more than 65535 segments, which .hair cannot store");
    std::uint32_t flags = kSegments | kPoints;
    if (!strands.thickness.empty()) flags |= kThickness;
    if (!strands.transparency.empty()) flags |= kTransparency;
    if (!strands.colors.empty()) flags |= kColors;

    std::vector<std::byte> bytes;
    const auto put = [&](const void* p, std::size_t n) {
        const auto* b = static_cast<const std::byte*>(p);
        bytes.insert(bytes.end(), b, b + n);
    };
    const std::uint32_t header[4] = {static_cast<std::uint32_t>(S), static_cast<std::uint32_t>(P), flags, 0};
    put("HAIR", 4);
    put(header, sizeof header);
    put(&strands.default_thickness, 4);
    put(&strands.default_transparency, 4);
    put(&strands.default_color, 12);
    put(strands.info.data(), strands.info.size());
    for (std::size_t s = 0; s < S; ++s) {
        const std::uint16_t segs = static_cast<std::uint16_t>(strands.point_count(s) - 1);
        put(&segs, 2);
    }
    put(strands.points.data(), P * 12);
    if (!strands.thickness.empty()) put(strands.thickness.data(), P * 4);
    if (!strands.transparency.empty()) put(strands.transparency.data(), P * 4);
    if (!strands.colors.empty()) put(strands.colors.data(), P * 12);
    write_file_atomic(path, bytes);
}

StrandStats strand_stats(const Strands& strands) {
    StrandStats st;
    st.strands = strands.strand_count();
    st.points = strands.points.size();
    if (st.strands == 0) return st;
    constexpr double inf = std::numeric_limits<double>::infinity();
    st.bbox_min = st.root_bbox_min = glm::dvec3(inf);
    st.bbox_max = st.root_bbox_max = glm::dvec3(-inf);
    st.points_min = std::numeric_limits<std::size_t>::max();
    st.length_min = inf;
    double length_sum = 0, chord_ratio_sum = 0;
    std::size_t segments = 0;
    glm::dvec3 dir_sum(0);
    for (std::size_t s = 0; s < st.strands; ++s) {
        const std::uint32_t b = strands.offsets[s], e = strands.offsets[s + 1];
        st.points_min = std::min<std::size_t>(st.points_min, e - b);
        st.points_max = std::max<std::size_t>(st.points_max, e - b);
        double length = 0;
        for (std::uint32_t i = b; i < e; ++i) {
            const glm::dvec3 p(strands.points[i]);
            st.bbox_min = glm::min(st.bbox_min, p);
            st.bbox_max = glm::max(st.bbox_max, p);
            if (i > b) length += glm::length(p - glm::dvec3(strands.points[i - 1]));
        }
        segments += e - b - 1;
        const glm::dvec3 root(strands.points[b]), tip(strands.points[e - 1]);
        st.root_bbox_min = glm::min(st.root_bbox_min, root);
        st.root_bbox_max = glm::max(st.root_bbox_max, root);
        st.length_min = std::min(st.length_min, length);
        st.length_max = std::max(st.length_max, length);
        length_sum += length;
        if (length > 0) chord_ratio_sum += glm::length(tip - root) / length;
        dir_sum += tip - root;  // chord vectors, weighted by length (as ../shared/data/inspect_hair.py)
    }
    st.points_mean = double(st.points) / double(st.strands);
    st.length_mean = length_sum / double(st.strands);
    st.segment_length_mean = segments ? length_sum / double(segments) : 0.0;
    st.chord_over_length_mean = chord_ratio_sum / double(st.strands);
    st.mean_root_to_tip = glm::length(dir_sum) > 0 ? glm::normalize(dir_sum) : glm::dvec3(0, -1, 0);

    const glm::dvec3 d = st.mean_root_to_tip;
    const glm::dvec3 a = glm::abs(d);
    const char* axis = a.x >= a.y && a.x >= a.z ? (d.x < 0 ? "-x" : "+x")
                     : a.y >= a.z               ? (d.y < 0 ? "-y" : "+y")
                                                : (d.z < 0 ? "-z" : "+z");
    st.axes_stated = strands.axes_stated;
    if (strands.axes_stated)
        st.axis_convention = std::string("y-up as the format states, metres read as centimetres (x 100); hair hangs along ") + axis +
                             ", kept as it is (no rotation is guessed)";
    else
        st.axis_convention = std::string("coordinates as stored (no axis swap or scaling); hair hangs along ") + axis +
                             (std::string(axis) == "-y" ? ", so the model is y-up like coif's scenes"
                                                        : std::string(", so coif rotates ") + axis + " to -y when it places the model in a y-up scene");
    return st;
}

glm::mat3 hang_axis_rotation(const StrandStats& stats) {
    if (stats.axes_stated) return glm::mat3(1.0f);
    const glm::dvec3 d = stats.mean_root_to_tip;
    const glm::dvec3 a = glm::abs(d);
    glm::vec3 from;
    if (a.x >= a.y && a.x >= a.z) from = {d.x < 0 ? -1.f : 1.f, 0, 0};
    else if (a.y >= a.z) from = {0, d.y < 0 ? -1.f : 1.f, 0};
    else from = {0, 0, d.z < 0 ? -1.f : 1.f};
    const glm::vec3 to(0, -1, 0);
    if (from == to) return glm::mat3(1.0f);
    if (from == -to) return glm::mat3(glm::vec3(-1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1));  // 180° about z
    // Rotation by 90° taking `from` to `to` about axis from × to (Rodrigues with sin = 1, cos = 0).
    const glm::vec3 k = glm::normalize(glm::cross(from, to));
    const glm::mat3 K(glm::vec3(0, k.z, -k.y), glm::vec3(-k.z, 0, k.x), glm::vec3(k.y, -k.x, 0));
    return glm::mat3(1.0f) + K + K * K;
}

Strands oriented_y_up(Strands strands) {
    const glm::mat3 r = hang_axis_rotation(strand_stats(strands));
    for (auto& p : strands.points) p = r * p;
    return strands;
}

float auto_fiber_radius(const Strands& strands) {
    const StrandStats st = strand_stats(strands);
    return auto_fiber_radius(st.bbox_min, st.bbox_max);
}

float auto_fiber_radius(glm::dvec3 bbox_min, glm::dvec3 bbox_max) {
    return kAutoRadiusFraction * static_cast<float>(glm::length(bbox_max - bbox_min));
}

}  // namespace coif
