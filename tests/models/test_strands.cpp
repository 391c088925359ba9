// Strand files: the real models of ../shared/data against the figures of its PROVENANCE.md, the
// .hair round trip, and every kind of bad input.
#include <cmath>
#include <cstring>
#include <fstream>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/atomic_file.h"
#include "models/core/error.h"
#include "models/strands.h"
#include "tests/common/test_data.h"

namespace coif {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct Expected {
    const char* file;
    size_t strands, points, points_min, points_max;
    glm::dvec3 bbox_min, bbox_max;
    double length_mean, chord_over_length;
    glm::dvec3 hang;
};

// Figures from ../shared/data/PROVENANCE.md (printed there to 2 decimals for the bounding box, 1 for
// lengths, 2 for chord/length and direction). Tolerances: half a unit of the last printed digit, except
// the bounding box, whose figures were rounded twice (6 significant digits, then 2 decimals: 213.3848
// became 213.385, then 213.39), so one full unit of the last digit.
const Expected kModels[] = {
    {"Bangs_100.hair", 100, 1165, 5, 21, {11.86, 17.10, 31.75}, {247.86, 236.95, 204.86}, 81.7, 0.95, {-1.00, 0.009, -0.004}},
    {"Bangs_100.data", 100, 1165, 5, 21, {11.86, 17.10, 31.75}, {247.86, 236.95, 204.86}, 81.7, 0.95, {-1.00, 0.009, -0.004}},
    {"Curly_100.hair", 100, 2528, 10, 47, {7.59, 28.92, 20.18}, {222.45, 213.39, 253.26}, 48.0, 0.74, {-0.999, -0.003, -0.053}},
    {"Curly_100.ply", 100, 2528, 10, 47, {7.59, 28.92, 20.18}, {222.45, 213.39, 253.26}, 48.0, 0.74, {-0.999, -0.003, -0.053}},
    {"harolongo.data", 7905, 166005, 21, 21, {-11.83, -14.26, -18.62}, {10.50, 14.20, 4.59}, 23.5, 0.78, {-0.33, -0.90, -0.28}},
};

class RealModel : public ::testing::TestWithParam<Expected> {};

TEST_P(RealModel, MatchesProvenanceFigures) {
    const Expected& e = GetParam();
    COIF_SHARED_DATA(path, e.file);
    const Strands s = read_strands(path);
    const StrandStats st = strand_stats(s);
    EXPECT_EQ(st.strands, e.strands);
    EXPECT_EQ(st.points, e.points);
    EXPECT_EQ(st.points_min, e.points_min);
    EXPECT_EQ(st.points_max, e.points_max);
    EXPECT_EQ(s.skipped_single_point, 0u);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(st.bbox_min[k], e.bbox_min[k], 0.01) << "axis " << k;
        EXPECT_NEAR(st.bbox_max[k], e.bbox_max[k], 0.01) << "axis " << k;
        EXPECT_NEAR(st.mean_root_to_tip[k], e.hang[k], 0.005) << "axis " << k;
    }
    EXPECT_NEAR(st.length_mean, e.length_mean, 0.05);
    EXPECT_NEAR(st.chord_over_length_mean, e.chord_over_length, 0.005);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealModel, ::testing::ValuesIn(kModels),
                         [](const auto& info) {
                             std::string n = info.param.file;
                             for (char& c : n) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });

// The same strands, split alike and with bit-identical points.
void expect_identical_strands(const fs::path& a_path, const fs::path& b_path) {
    const Strands a = read_strands(a_path), b = read_strands(b_path);
    EXPECT_EQ(a.offsets, b.offsets);
    ASSERT_EQ(a.points.size(), b.points.size());
    EXPECT_EQ(0, std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(glm::vec3)));
}

TEST(Strands, BangsHairAndDataHoldIdenticalStrands) {
    COIF_SHARED_DATA(hair, "Bangs_100.hair");
    COIF_SHARED_DATA(data, "Bangs_100.data");
    expect_identical_strands(hair, data);
}

TEST(Strands, CurlyPlyAndHairHoldIdenticalStrands) {
    // PROVENANCE.md: Curly_100.hair keeps the PLY's float32 points byte for byte and its nsegs as segments.
    COIF_SHARED_DATA(ply, "Curly_100.ply");
    COIF_SHARED_DATA(hair, "Curly_100.hair");
    expect_identical_strands(ply, hair);
}

TEST(Strands, TressFxMohawkMatchesProvenanceFiguresInCentimetres) {
    // PROVENANCE.md's figures are in the file's metres, to 3 decimals (bounding box, lengths) or 2 (chord,
    // direction); coif reads centimetres (× 100). Tolerance: one unit of the last printed digit for the box
    // (0.001 m = 0.1 cm), half a unit elsewhere.
    COIF_SHARED_DATA(path, "Ratboy_mohawk.tfx");
    const Strands s = read_strands(path);
    const StrandStats st = strand_stats(s);
    EXPECT_EQ(st.strands, 2228u);
    EXPECT_EQ(st.points, 71296u);
    EXPECT_EQ(st.points_min, 32u);
    EXPECT_EQ(st.points_max, 32u);
    const glm::dvec3 lo(-9.5, 21.4, -33.6), hi(11.7, 111.0, 27.1), hang(-0.01, 0.09, -1.00);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(st.bbox_min[k], lo[k], 0.1) << "axis " << k;
        EXPECT_NEAR(st.bbox_max[k], hi[k], 0.1) << "axis " << k;
        EXPECT_NEAR(st.mean_root_to_tip[k], hang[k], 0.005) << "axis " << k;
    }
    EXPECT_NEAR(st.root_bbox_min.y, 22.0, 0.5);  // roots span y 0.22–0.91 m
    EXPECT_NEAR(st.root_bbox_max.y, 91.0, 0.5);
    EXPECT_NEAR(st.length_max, 29.5, 0.05);
    EXPECT_NEAR(st.length_mean, 10.3, 0.05);
    EXPECT_NEAR(st.chord_over_length_mean, 0.96, 0.005);
    // 47 strands shorter than 0.01 m, 9 shorter than 0.001 m.
    int under_1cm = 0, under_1mm = 0;
    for (std::size_t i = 0; i < s.strand_count(); ++i) {
        double length = 0;
        for (std::uint32_t p = s.offsets[i] + 1; p < s.offsets[i + 1]; ++p) length += glm::length(glm::dvec3(s.points[p] - s.points[p - 1]));
        under_1cm += length < 1.0;
        under_1mm += length < 0.1;
    }
    EXPECT_EQ(under_1cm, 47);
    EXPECT_EQ(under_1mm, 9);
    // y-up as TressFX states: the mohawk sweeps along −z, and no rotation is guessed from that.
    EXPECT_TRUE(st.axes_stated);
    EXPECT_EQ(hang_axis_rotation(st), glm::mat3(1.0f));
}

TEST(Strands, HairRewriteIsByteIdenticalToTheOriginal) {
    COIF_SHARED_DATA(path, "Curly_100.hair");
    const auto dir = test::scratch_dir("rewrite");
    write_hair(dir / "curly.hair", read_hair(path));
    EXPECT_EQ(read_file_bytes(path), read_file_bytes(dir / "curly.hair"));
    fs::remove_all(dir);
}

Strands synthetic(bool with_optional_arrays) {
    Strands s;
    for (int k = 0; k < 5; ++k) {
        std::vector<glm::vec3> pts;
        for (int i = 0; i < 3 + k; ++i) pts.push_back({0.1f * float(k) + 1e-7f * float(i), -1.3f * float(i), 0.7f * std::sin(float(i))});
        s.add_strand(pts);
    }
    if (with_optional_arrays) {
        for (size_t i = 0; i < s.points.size(); ++i) {
            s.thickness.push_back(0.01f * float(i));
            s.transparency.push_back(0.5f / float(i + 1));
            s.colors.push_back({0.1f, 0.2f * float(i % 3), 0.3f});
        }
    }
    s.default_thickness = 0.07f;
    s.default_color = {0.2f, 0.4f, 0.6f};
    std::strcpy(s.info.data(), "written by a coif test");
    return s;
}

void expect_bit_identical(const Strands& a, const Strands& b) {
    EXPECT_EQ(a.offsets, b.offsets);
    const auto same = [](const auto& x, const auto& y) {
        return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
    };
    EXPECT_TRUE(same(a.points, b.points));
    EXPECT_TRUE(same(a.thickness, b.thickness));
    EXPECT_TRUE(same(a.transparency, b.transparency));
    EXPECT_TRUE(same(a.colors, b.colors));
    EXPECT_EQ(std::memcmp(&a.default_color, &b.default_color, 12), 0);
    EXPECT_EQ(a.default_thickness, b.default_thickness);
    EXPECT_EQ(a.info, b.info);
}

TEST(Strands, HairWriteReadRoundTripsBitExactly) {
    const auto dir = test::scratch_dir("roundtrip");
    for (bool optional : {false, true}) {
        const Strands s = synthetic(optional);
        write_hair(dir / "s.hair", s);
        expect_bit_identical(s, read_hair(dir / "s.hair"));
    }
    fs::remove_all(dir);
}

// ── bad input ──────────────────────────────────────────────────────────────────────────────────────

class BadStrandFile : public ::testing::Test {
protected:
    void SetUp() override { dir = test::scratch_dir("bad-strands"); }
    void TearDown() override { fs::remove_all(dir); }
    fs::path write(const std::string& name, const std::vector<std::byte>& bytes) {
        const fs::path p = dir / name;
        std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        return p;
    }
    std::vector<std::byte> valid_hair() {
        write_hair(dir / "valid.hair", synthetic(false));
        return read_file_bytes(dir / "valid.hair");
    }
    template <class T>
    static void poke(std::vector<std::byte>& b, size_t at, T v) { std::memcpy(b.data() + at, &v, sizeof v); }
    // The error must name the file and contain `what`.
    template <class F>
    void expect_error(F&& read, const fs::path& p, const std::string& what) {
        try {
            read(p);
            ADD_FAILURE() << "no error for " << p;
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), p);
            EXPECT_THAT(e.what(), HasSubstr(what));
        }
    }
    fs::path dir;
};

TEST_F(BadStrandFile, HairWrongMagic) {
    auto b = valid_hair();
    b[0] = std::byte{'X'};
    expect_error(read_hair, write("magic.hair", b), "wrong magic");
}

TEST_F(BadStrandFile, HairEmptyAndTruncatedHeader) {
    expect_error(read_hair, write("empty.hair", {}), "truncated");
    auto b = valid_hair();
    b.resize(60);
    expect_error(read_hair, write("header.hair", b), "truncated");
}

TEST_F(BadStrandFile, HairTruncatedArrays) {
    auto b = valid_hair();
    b.resize(b.size() - 5);
    expect_error(read_hair, write("arrays.hair", b), "truncated");
}

TEST_F(BadStrandFile, HairCountsDisagreeWithFileSize) {
    auto b = valid_hair();
    poke<std::uint32_t>(b, 8, 1000);  // point count
    expect_error(read_hair, write("count.hair", b), "but the file has");
    auto c = valid_hair();
    c.resize(c.size() + 12);
    expect_error(read_hair, write("extra.hair", c), "but the file has");
}

TEST_F(BadStrandFile, HairSegmentsDisagreeWithPointCount) {
    auto b = valid_hair();
    poke<std::uint16_t>(b, 128, 7);  // first strand's segment count, total no longer matches
    expect_error(read_hair, write("segs.hair", b), "add up to");
}

// Refused from the header alone: were anything allocated from these counts, ASan would report
// an allocation-size-too-big or out-of-memory instead of the error.
TEST_F(BadStrandFile, HairAbsurdCountsRefusedBeforeAllocating) {
    auto b = valid_hair();
    poke<std::uint32_t>(b, 4, 0xFFFFFFFFu);
    expect_error(read_hair, write("strands.hair", b), "absurd");
    auto c = valid_hair();
    poke<std::uint32_t>(c, 8, 0xFFFFFFFFu);
    expect_error(read_hair, write("points.hair", c), "absurd");
}

TEST_F(BadStrandFile, HairNaNAndInfCoordinates) {
    auto b = valid_hair();
    const size_t first_point = 128 + 2 * 5;
    poke<float>(b, first_point + 4 * 4, std::nanf(""));
    expect_error(read_hair, write("nan.hair", b), "NaN or infinite");
    auto c = valid_hair();
    poke<float>(c, first_point, INFINITY);
    expect_error(read_hair, write("inf.hair", c), "NaN or infinite");
}

TEST_F(BadStrandFile, HairZeroSegmentsAndZeroLengthStrands) {
    Strands s;
    s.add_strand({{0, 0, 0}, {1, 0, 0}});
    s.add_strand({{2, 2, 2}, {2, 2, 2}, {2, 2, 2}});
    expect_error([&](const fs::path& p) { write_hair(p, s); }, dir / "zero.hair", "zero length");
    EXPECT_FALSE(fs::exists(dir / "zero.hair"));

    auto b = valid_hair();
    poke<std::uint16_t>(b, 128, 0);      // strand 0: zero segments ...
    poke<std::uint16_t>(b, 130, 3 + 2);  // ... its 2 lost points moved to strand 1, so the totals still agree
    expect_error(read_hair, write("zeroseg.hair", b), "zero segments");
}

std::vector<std::byte> usc(const std::vector<std::int32_t>& ints_and_floats_as_ints) {
    std::vector<std::byte> b(ints_and_floats_as_ints.size() * 4);
    std::memcpy(b.data(), ints_and_floats_as_ints.data(), b.size());
    return b;
}
std::int32_t f(float v) {
    std::int32_t i;
    std::memcpy(&i, &v, 4);
    return i;
}

TEST_F(BadStrandFile, DataValidAndSinglePointStrandsSkipped) {
    const auto p = write("ok.data", usc({2, 1, f(0), f(0), f(0), 2, f(0), f(0), f(0), f(1), f(0), f(0)}));
    const Strands s = read_usc_data(p);
    EXPECT_EQ(s.strand_count(), 1u);
    EXPECT_EQ(s.skipped_single_point, 1u);
}

TEST_F(BadStrandFile, DataTruncatedEmptyAndTrailing) {
    expect_error(read_usc_data, write("empty.data", {}), "truncated");
    expect_error(read_usc_data, write("trunc.data", usc({1, 3, f(0), f(0), f(0), f(1), f(0)})), "does not fit");
    expect_error(read_usc_data, write("trail.data", usc({1, 2, f(0), f(0), f(0), f(1), f(0), f(0), 77})), "bytes after");
}

TEST_F(BadStrandFile, DataAbsurdAndNegativeCounts) {
    expect_error(read_usc_data, write("huge.data", usc({0x7FFFFFFF, 2})), "cannot fit");
    expect_error(read_usc_data, write("neg.data", usc({-5})), "not positive");
    expect_error(read_usc_data, write("negpts.data", usc({1, -2, 0, 0})), "does not fit");
    expect_error(read_usc_data, write("hugepts.data", usc({1, 0x7FFFFFFF, 0, 0})), "does not fit");
}

TEST_F(BadStrandFile, DataNaNCoordinates) {
    expect_error(read_usc_data, write("nan.data", usc({1, 2, f(0), f(NAN), f(0), f(1), f(0), f(0)})), "NaN or infinite");
}

// The tfx and ply seeds of the fuzzer (tests/fuzz/corpus/): hand-made, valid.
std::vector<std::byte> seed(const std::string& name) { return read_file_bytes(test::source_dir() / "tests/fuzz/corpus" / name); }

TEST_F(BadStrandFile, TfxSeedReadsInCentimetres) {
    const Strands s = read_strands(write("ok.tfx", seed("tfx/two_strands.tfx")));
    EXPECT_EQ(s.strand_count(), 2u);
    EXPECT_EQ(s.points.size(), 8u);
    EXPECT_FLOAT_EQ(s.points[0].y, 100.0f);  // 1.0 m
    EXPECT_TRUE(s.axes_stated);
}

TEST_F(BadStrandFile, TfxTruncatedAbsurdAndNaN) {
    const auto good = seed("tfx/two_strands.tfx");
    expect_error(read_strands, write("empty.tfx", {}), "fewer than the 160-byte TressFX header");
    auto b = good;
    b.resize(b.size() - 4);
    expect_error(read_strands, write("trunc.tfx", b), "past the end");
    b = good;
    poke<std::uint32_t>(b, 4, 0xFFFFFFFFu);  // strand count
    expect_error(read_strands, write("huge.tfx", b), "is absurd");
    b = good;
    poke<std::uint32_t>(b, 4, 1000000);  // plausible, but not in this file
    expect_error(read_strands, write("count.tfx", b), "past the end");
    b = good;
    poke<std::uint32_t>(b, 8, 1);  // one point per strand
    expect_error(read_strands, write("v1.tfx", b), "points per strand");
    b = good;
    poke<std::uint32_t>(b, 20, 1u << 30);  // vertex UV offset
    expect_error(read_strands, write("offset.tfx", b), "outside the");
    b = good;
    poke<float>(b, 0, NAN);
    expect_error(read_strands, write("version.tfx", b), "not a TressFX version");
    b = good;
    poke<float>(b, 160 + 4, NAN);
    expect_error(read_strands, write("nan.tfx", b), "NaN or infinite");
}

TEST_F(BadStrandFile, PlySeedsRead) {
    EXPECT_EQ(read_strands(write("a.ply", seed("ply/two_strands_with_colour.ply"))).points.size(), 8u);
    EXPECT_EQ(read_strands(write("b.ply", seed("ply/plain.ply"))).strand_count(), 3u);
}

TEST_F(BadStrandFile, PlyBadHeadersCountsAndEncodings) {
    const auto text = [](const std::string& t) {
        std::vector<std::byte> b(t.size());
        std::memcpy(b.data(), t.data(), t.size());
        return b;
    };
    const std::string head = "ply\nformat binary_little_endian 1.0\n";
    const std::string vertex = "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n";
    expect_error(read_strands, write("empty.ply", {}), "not a PLY file");
    expect_error(read_strands, write("noend.ply", text(head + vertex)), "no \"end_header\"");
    expect_error(read_strands, write("ascii.ply", text("ply\nformat ascii 1.0\n" + vertex + "end_header\n")), "binary_little_endian 1.0 only");
    expect_error(read_strands, write("list.ply", text(head + vertex + "element face 1\nproperty list uchar int vertex_indices\nend_header\n")),
                 "list properties");
    expect_error(read_strands, write("huge.ply", text(head + "element vertex 99999999999\nproperty float x\nend_header\n")),
                 "do not fit");
    expect_error(read_strands, write("nostrand.ply", text(head + "element vertex 0\nproperty float x\nend_header\n")), "no strand element");
    auto b = seed("ply/plain.ply");
    b.resize(b.size() - 1);
    expect_error(read_strands, write("trunc.ply", b), "do not fit");
    b = seed("ply/plain.ply");
    b.push_back(std::byte{0});
    expect_error(read_strands, write("trail.ply", b), "bytes after");
    b = seed("ply/plain.ply");
    poke<std::uint16_t>(b, b.size() - 2, 40);  // the last strand's nsegs: more points than the file has
    expect_error(read_strands, write("nsegs.ply", b), "add up to more than");
    b = seed("ply/plain.ply");
    const std::string h(reinterpret_cast<const char*>(b.data()), b.size());
    poke<float>(b, h.find("end_header\n") + 11 + 4, NAN);
    expect_error(read_strands, write("nan.ply", b), "NaN or infinite");
}

TEST_F(BadStrandFile, UnknownExtensionAndMissingFile) {
    expect_error(read_strands, write("x.obj", {}), "unknown strand file extension");
    expect_error(read_strands, dir / "missing.hair", "no such file");
}

TEST(Strands, HangAxisRotationTakesMinusXToMinusY) {
    StrandStats st;
    st.mean_root_to_tip = {-1, 0, 0};
    EXPECT_NEAR(glm::length(hang_axis_rotation(st) * glm::vec3(-1, 0, 0) - glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
    st.mean_root_to_tip = {0, 0.2, -0.98};
    EXPECT_NEAR(glm::length(hang_axis_rotation(st) * glm::vec3(0, 0, -1) - glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
    const glm::mat3 r = hang_axis_rotation(st);
    EXPECT_NEAR(glm::determinant(r), 1.0f, 1e-6f);  // a rotation, not a reflection
}

}  // namespace
}  // namespace coif
