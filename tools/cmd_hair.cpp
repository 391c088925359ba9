// coif hair inspect|convert — real strand files (.hair, .data, .tfx, .ply), and inspect of a character's body
// (.tfxmesh, .obj) and strand skinning (.tfxbone).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <utility>

#include "models/character.h"
#include "models/core/error.h"
#include "models/strands.h"
#include "tools/cli.h"

namespace {
namespace fs = std::filesystem;

nlohmann::json vec_json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json stats_json(const fs::path& path, const coif::Strands& strands, const coif::StrandStats& st) {
    return {{"file", path.string()},
            {"format", coif::strand_format_name(path)},
            {"strands", st.strands},
            {"points", st.points},
            {"points_per_strand", {{"min", st.points_min}, {"mean", st.points_mean}, {"max", st.points_max}}},
            {"skipped_single_point_strands", strands.skipped_single_point},
            {"bbox", {{"min", vec_json(st.bbox_min)}, {"max", vec_json(st.bbox_max)}, {"extent", vec_json(st.bbox_max - st.bbox_min)}}},
            {"root_bbox", {{"min", vec_json(st.root_bbox_min)}, {"max", vec_json(st.root_bbox_max)}}},
            {"strand_length", {{"min", st.length_min}, {"mean", st.length_mean}, {"max", st.length_max}}},
            {"segment_length_mean", st.segment_length_mean},
            {"chord_over_length_mean", st.chord_over_length_mean},
            {"mean_root_to_tip", vec_json(st.mean_root_to_tip)},
            {"has_thickness", !strands.thickness.empty()},
            {"has_colors", !strands.colors.empty()},
            {"axis_convention", st.axis_convention}};
}

void print_stats(const fs::path& path, const coif::Strands& strands, const coif::StrandStats& st) {
    const auto v = [](const glm::dvec3& a) {
        char b[96];
        std::snprintf(b, sizeof b, "(%.2f, %.2f, %.2f)", a.x, a.y, a.z);
        return std::string(b);
    };
    std::printf("%s  (%s)\n", path.string().c_str(), coif::strand_format_name(path).c_str());
    std::printf("  strands             %zu", st.strands);
    if (strands.skipped_single_point) std::printf("  (+%llu one-point scalp marks skipped)", static_cast<unsigned long long>(strands.skipped_single_point));
    std::printf("\n  points              %zu  (per strand min %zu, mean %.2f, max %zu)\n", st.points, st.points_min, st.points_mean, st.points_max);
    std::printf("  bounding box        min %s  max %s\n", v(st.bbox_min).c_str(), v(st.bbox_max).c_str());
    std::printf("  extent              %s\n", v(st.bbox_max - st.bbox_min).c_str());
    std::printf("  roots box           min %s  max %s\n", v(st.root_bbox_min).c_str(), v(st.root_bbox_max).c_str());
    std::printf("  strand length       min %.2f  mean %.2f  max %.2f  (file units)\n", st.length_min, st.length_mean, st.length_max);
    std::printf("  segment length      mean %.3f\n", st.segment_length_mean);
    std::printf("  chord / length      %.3f  (1 = straight, lower = wavier)\n", st.chord_over_length_mean);
    std::printf("  hangs along         %s  (mean root-to-tip direction)\n", v(st.mean_root_to_tip).c_str());
    std::printf("  per-point data      thickness %s, colours %s\n", strands.thickness.empty() ? "no" : "yes",
                strands.colors.empty() ? "no" : "yes");
    std::printf("  axes                %s\n", st.axis_convention.c_str());
}

// A character's body mesh (models/character.h).
nlohmann::json body_json(const fs::path& path, const coif::BodyMesh& m) {
    return {{"file", path.string()},
            {"format", coif::body_format_name(path)},
            {"bones", m.bones.size()},
            {"vertices", m.positions.size()},
            {"triangles", m.triangles.size()},
            {"bbox", {{"min", vec_json(m.bounds().first)}, {"max", vec_json(m.bounds().second)}}},
            {"weights_renormalised", m.renormalised},
            {"min_weight_sum", m.min_weight_sum},
            {"units", m.axes_stated ? "centimetres, y-up (read from metres)" : "as stored (the format states none)"}};
}

// Which bones the strands lean on most: (name, strands whose largest weight is on it), most first.
std::vector<std::pair<std::string, std::size_t>> main_bones(const coif::StrandSkinning& s) {
    std::vector<std::size_t> count(s.bones.size(), 0);
    for (const coif::BoneInfluence& b : s.strands) {
        int best = 0;
        for (int k = 1; k < 4; ++k)
            if (b.weight[k] > b.weight[best]) best = k;
        ++count[static_cast<std::size_t>(b.bone[best])];
    }
    std::vector<std::pair<std::string, std::size_t>> out;
    for (std::size_t i = 0; i < count.size(); ++i)
        if (count[i]) out.emplace_back(s.bones[i], count[i]);
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    return out;
}

nlohmann::json skinning_json(const fs::path& path, const coif::StrandSkinning& s) {
    nlohmann::json bones = nlohmann::json::array();
    for (const auto& [name, n] : main_bones(s)) bones.push_back({{"bone", name}, {"strands", n}});
    return {{"file", path.string()},
            {"format", "AMD TressFX .tfxbone"},
            {"bones", s.bones.size()},
            {"strands", s.strands.size()},
            {"weights_renormalised", s.renormalised},
            {"min_weight_sum", s.min_weight_sum},
            {"main_bones", bones}};
}

void print_body(const fs::path& path, const coif::BodyMesh& m) {
    const auto [lo, hi] = m.bounds();
    std::printf("%s  (%s)\n", path.string().c_str(), coif::body_format_name(path).c_str());
    std::printf("  bones               %zu\n  vertices            %zu\n  triangles           %zu\n", m.bones.size(), m.positions.size(),
                m.triangles.size());
    std::printf("  bounding box        min (%.2f, %.2f, %.2f)  max (%.2f, %.2f, %.2f)\n", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    if (!m.bones.empty())
        std::printf("  weights             %zu vertices renormalised (smallest sum %.3f)\n", m.renormalised, m.min_weight_sum);
    std::printf("  units               %s\n", m.axes_stated ? "centimetres, y-up (read from metres)" : "as stored (the format states none)");
}

void print_skinning(const fs::path& path, const coif::StrandSkinning& s) {
    std::printf("%s  (AMD TressFX .tfxbone)\n", path.string().c_str());
    std::printf("  bones               %zu\n  strands             %zu\n", s.bones.size(), s.strands.size());
    std::printf("  weights             %zu strands renormalised (smallest sum %.3f)\n", s.renormalised, s.min_weight_sum);
    std::printf("  strands by main bone\n");
    for (const auto& [name, n] : main_bones(s)) std::printf("    %6zu  %s\n", n, name.c_str());
}

void add_hair(CLI::App& root) {
    CLI::App* hair = coif::cli::noun(root, "hair", "Strand files: inspect and convert (.hair Yuksel, .data USC-HairSalon, .tfx AMD TressFX, .ply hairutil)");

    struct InspectOptions {
        std::vector<std::string> files;
        bool json = false;
    };
    auto io = std::make_shared<InspectOptions>();
    CLI::App* inspect = hair->add_subcommand(
        "inspect",
        "Read strand files and print what they hold: strand and point counts, points per strand, bounding box,\n"
        "strand and segment lengths, waviness (chord/length), the direction the hair hangs, and the axis\n"
        "convention coif assumes. Coordinates are reported as read: as stored in the file (units are the file's own),\n"
        "except TressFX's metres, read as centimetres.\n"
        "Also a character's body (" + coif::body_extensions() + ": bones, vertices, triangles, bounding box, weights) and\n"
        "a TressFX strand skinning (.tfxbone: bones, strands, renormalised weights, the bones the strands lean on).");
    inspect->add_option("files", io->files, "Strand files (" + coif::strand_extensions() + "), bodies (" + coif::body_extensions() + ") or .tfxbone")
        ->required()
        ->check(CLI::ExistingFile);
    coif::cli::add_json_flag(inspect, io->json);
    coif::cli::examples(inspect, "  coif hair inspect ../shared/data/harolongo.data\n  coif hair inspect a.hair b.data --json\n"
                                 "  coif hair inspect ../shared/data/Ratboy_body.tfxmesh ../shared/data/Ratboy_mohawk.tfxbone");
    inspect->callback([io] {
        nlohmann::json all = nlohmann::json::array();
        for (const auto& f : io->files) {
            if (!coif::body_format_name(f).empty()) {
                const coif::BodyMesh m = coif::read_body(f);
                if (io->json) all.push_back(body_json(f, m));
                else print_body(f, m);
                continue;
            }
            if (fs::path(f).extension() == ".tfxbone") {
                const coif::StrandSkinning s = coif::read_tfxbone(f);
                if (io->json) all.push_back(skinning_json(f, s));
                else print_skinning(f, s);
                continue;
            }
            const coif::Strands strands = coif::read_strands(f);
            const coif::StrandStats st = coif::strand_stats(strands);
            if (io->json) all.push_back(stats_json(f, strands, st));
            else print_stats(f, strands, st);
        }
        if (io->json) coif::cli::print_json(io->files.size() == 1 ? all[0] : all);
    });

    struct ConvertOptions {
        std::string in, out;
        bool y_up = false;
    };
    auto co = std::make_shared<ConvertOptions>();
    CLI::App* convert = hair->add_subcommand(
        "convert",
        "Convert a strand file to Yuksel's .hair format (written atomically: a failed conversion leaves no file).\n"
        "Points are copied bit for bit unless --y-up is given.");
    convert->add_option("input", co->in, "Strand file to read (" + coif::strand_extensions() + ")")->required()->check(CLI::ExistingFile);
    convert->add_option("output", co->out, "The .hair file to write")->required();
    convert->add_flag("--y-up", co->y_up,
                      "Rotate the model so that its hair hangs along -y (coif's y-up convention); e.g. the CT2Hair "
                      "models hang along -x");
    coif::cli::examples(convert, "  coif hair convert ../shared/data/Bangs_100.data bangs.hair\n"
                                 "  coif hair convert ../shared/data/Curly_100.hair curly_yup.hair --y-up");
    convert->callback([co] {
        if (fs::path(co->out).extension() != ".hair")
            throw coif::Error(co->out, "", "the output must be a .hair file");
        coif::cli::lock_output(co->out);
        coif::Strands strands = coif::read_strands(co->in);
        if (co->y_up) strands = coif::oriented_y_up(std::move(strands));
        coif::write_hair(co->out, strands);
        std::fprintf(stderr, "wrote %s: %zu strands, %zu points\n", co->out.c_str(), strands.strand_count(),
                     strands.points.size());
    });
}

COIF_REGISTER_COMMAND(10, add_hair);

}  // namespace
