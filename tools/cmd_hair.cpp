// coif hair inspect|convert — real strand files (.hair, .data).
#include <cstdio>
#include <iostream>
#include <utility>

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
        "except TressFX's metres, read as centimetres.");
    inspect->add_option("files", io->files, "Strand files (" + coif::strand_extensions() + ")")->required()->check(CLI::ExistingFile);
    coif::cli::add_json_flag(inspect, io->json);
    coif::cli::examples(inspect, "  coif hair inspect ../shared/data/harolongo.data\n  coif hair inspect a.hair b.data --json");
    inspect->callback([io] {
        nlohmann::json all = nlohmann::json::array();
        for (const auto& f : io->files) {
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
