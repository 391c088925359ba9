// coif compare A B — image-quality numbers of B (test) against A (reference): PSNR, SSIM and FLIP on
// linear and tone-mapped pixels over a mask of hair pixels (models/core/image_metrics.h).
#include <cmath>
#include <cstdio>

#include "models/core/error.h"
#include "models/core/image.h"
#include "models/core/image_metrics.h"
#include "tools/cli.h"

namespace {

struct CompareCliOptions {
    std::string a, b, heatmap, mask = "auto";
    float exposure = 0.0f;
    double ppd = coif::kFlipPixelsPerDegree;
    bool json = false;
};

nlohmann::json metric_json(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return v;
}

nlohmann::json metrics_json(const coif::MetricSet& m) {
    return {{"psnr_db", metric_json(m.psnr_db)}, {"ssim", m.ssim}, {"flip_mean", m.flip}};
}

void add_compare(CLI::App& root) {
    auto o = std::make_shared<CompareCliOptions>();
    CLI::App* cmd = root.add_subcommand(
        "compare",
        "Image-quality numbers of image B (the test) against image A (the reference): PSNR, SSIM, FLIP\n"
        "Computed over the pixels that show hair:\n"
        "  PSNR  in dB (\"inf\" for identical pixels); linear: peak = 99th percentile of A's brightest channel on the mask; tone-mapped: peak 1\n"
        "  SSIM  Wang et al. 2004, 11x11 Gaussian window (sigma 1.5 px), mean over RGB\n"
        "  FLIP  mean of the FLIP error map (Andersson et al. 2020, implemented here from the paper; 0 = identical,\n"
        "        1 = maximal): LDR-FLIP on the tone-mapped images, HDR-FLIP (2021) on the linear ones\n"
        "Tone-mapped means the PNG tone map: sRGB(clamp(linear * 2^exposure, 0, 1)); a PNG compares as its own pixels.\n"
        "Hair mask (--mask): 'alpha' = alpha > 0.05; 'background' = differs from the uniform colour of the four\n"
        "corners by more than 1.5/255; 'auto' picks alpha when an image has informative alpha, else background;\n"
        "the mask is the union over A and B; 'none' = every pixel. Images must have the same size.\n"
        "--heatmap writes the per-pixel LDR-FLIP error as a false-colour picture (magma-like ramp: black = no error,\n"
        "pale yellow = 1; pixels outside the mask at quarter brightness).");
    cmd->add_option("A", o->a, "Reference image (.exr, .png, .hdr, anything OpenImageIO reads)")->required();
    cmd->add_option("B", o->b, "Test image, same size as A")->required();
    cmd->add_option("--heatmap", o->heatmap, "Write the FLIP error picture here (.png or .exr)");
    cmd->add_option("--mask", o->mask, "Hair mask: auto, alpha, background or none")
        ->check(CLI::IsMember({"auto", "alpha", "background", "none"}));
    cmd->add_option("--exposure", o->exposure, "Exposure in stops applied before the tone map of the tone-mapped metrics");
    cmd->add_option("--ppd", o->ppd, "FLIP viewing condition: pixels per degree of visual angle (default: 0.7 m wide 4K screen at 0.7 m)");
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif compare reference.exr render.exr\n"
                             "  coif compare reference.exr render.png --heatmap flip.png --json\n"
                             "  coif compare a.exr b.exr --mask none --exposure 1");
    cmd->callback([o] {
        const coif::Image a = coif::read_image(o->a);
        const coif::Image b = coif::read_image(o->b);
        coif::CompareOptions co;
        co.mask = coif::parse_mask_mode(o->mask);
        co.exposure = o->exposure;
        co.pixels_per_degree = o->ppd;
        const coif::CompareResult r = coif::compare_images(a, b, co, o->a, o->b);
        if (!o->heatmap.empty()) {
            coif::WriteOptions wo;
            wo.description = "coif compare: per-pixel LDR-FLIP of " + o->b + " against " + o->a + " (magma-like ramp, 0 black, 1 pale yellow)";
            coif::write_image(o->heatmap, coif::error_heatmap(r.flip_tone_mapped, r.mask), wo);
        }
        if (o->json) {
            coif::cli::print_json({{"a", o->a},
                                   {"b", o->b},
                                   {"width", r.width},
                                   {"height", r.height},
                                   {"mask", {{"rule", r.mask.rule}, {"pixels", r.mask.count}}},
                                   {"exposure", o->exposure},
                                   {"pixels_per_degree", o->ppd},
                                   {"linear_peak", r.linear_peak},
                                   {"hdr_flip_exposures", {{"start", r.hdr_exposures.start}, {"stop", r.hdr_exposures.stop}, {"count", r.hdr_exposures.count}}},
                                   {"linear", metrics_json(r.linear)},
                                   {"tone_mapped", metrics_json(r.tone_mapped)},
                                   {"tone_mapped_all_pixels", metrics_json(r.tone_mapped_all)},
                                   {"heatmap", o->heatmap}});
            return;
        }
        std::printf("A (reference)  %s\nB (test)       %s\n", o->a.c_str(), o->b.c_str());
        std::printf("size           %dx%d\n", r.width, r.height);
        std::printf("hair mask      %zu pixels (%.1f %%): %s\n", r.mask.count, 100.0 * double(r.mask.count) / (double(r.width) * r.height),
                    r.mask.rule.c_str());
        std::printf("\n%-28s %10s %8s %10s\n", "", "PSNR (dB)", "SSIM", "mean FLIP");
        const auto row = [](const char* name, const coif::MetricSet& m) {
            std::printf("%-28s %10s %8.4f %10.4f\n", name, coif::format_metric(m.psnr_db, 2).c_str(), m.ssim, m.flip);
        };
        row("linear, hair pixels", r.linear);
        row("tone-mapped, hair pixels", r.tone_mapped);
        row("tone-mapped, all pixels", r.tone_mapped_all);
        std::printf("\nlinear: PSNR/SSIM peak %.4g; FLIP = HDR-FLIP over %d exposures from %.2f to %.2f stops\n", r.linear_peak,
                    r.hdr_exposures.count, r.hdr_exposures.start, r.hdr_exposures.stop);
        if (!o->heatmap.empty()) std::printf("heatmap        %s\n", o->heatmap.c_str());
    });
}

COIF_REGISTER_COMMAND(72, add_compare);

}  // namespace
