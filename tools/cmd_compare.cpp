// coif compare A B — image-quality numbers of B (test) against A (reference): PSNR, SSIM and FLIP on
// linear and tone-mapped pixels over a mask of hair pixels, and the appearance metrics (radiance ratio,
// mask IoU, blurred PSNR/SSIM, detail ratio; models/core/image_metrics.h), with thresholds that set the
// exit status (tools/compare_report.h).
#include <cmath>
#include <cstdio>

#include "models/core/error.h"
#include "models/core/image.h"
#include "models/core/image_metrics.h"
#include "tools/cli.h"
#include "tools/compare_report.h"

namespace {

struct CompareCliOptions {
    std::string a, b, heatmap, mask = "auto";
    float exposure = 0.0f;
    double ppd = coif::kFlipPixelsPerDegree;
    double blur = coif::kDefaultBlurSigma;
    int regions = 0;
    coif::cli::CompareGates gates;
    bool json = false;
};

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
        "Appearance metrics (fibres of a render and of a reference cannot line up pixel by pixel, and per-pixel PSNR/FLIP\n"
        "reward blur; docs/quality.md says why each is there):\n"
        "  radiance ratio   per channel, B/A of the coverage-weighted mean hair radiance where both images show hair\n"
        "                   (alpha images: sum(alpha*RGB)/sum(alpha), straight alpha; others: RGB minus the background,\n"
        "                   so render both over black: coif render/reference --background 0 0 0)\n"
        "  mask IoU         |hair in A and B| / |hair in A or B|: coverage and silhouette\n"
        "  blurred PSNR/SSIM  tone-mapped, after a Gaussian blur of --blur pixels (default 2: cluster scale)\n"
        "  detail ratio     B/A of the RMS of the high-pass (image minus its 1-px Gaussian blur) inside the hair:\n"
        "                   below 1 the test is smeared, above 1 noisier\n"
        "  by region        with --regions N, the radiance ratio of each of N x N regions of the box around the hair:\n"
        "                   where the test is too bright or too dark, which the one mean hides when errors cancel\n"
        "Thresholds (--min-iou, --min-blurred-psnr, --max-flip, --detail-range, --radiance-range) gate the exit status:\n"
        "a failed one prints which and exits 1, after the report (so CI can stop on an image regression).\n"
        "--heatmap writes the per-pixel LDR-FLIP error as a false-colour picture (magma-like ramp: black = no error,\n"
        "pale yellow = 1; pixels outside the mask at quarter brightness).");
    cmd->add_option("A", o->a, "Reference image (.exr, .png, .hdr, anything OpenImageIO reads)")->required();
    cmd->add_option("B", o->b, "Test image, same size as A")->required();
    cmd->add_option("--heatmap", o->heatmap, "Write the FLIP error picture here (.png or .exr)");
    cmd->add_option("--mask", o->mask, "Hair mask: auto, alpha, background or none")
        ->check(CLI::IsMember({"auto", "alpha", "background", "none"}));
    cmd->add_option("--exposure", o->exposure, "Exposure in stops applied before the tone map of the tone-mapped metrics");
    cmd->add_option("--ppd", o->ppd, "FLIP viewing condition: pixels per degree of visual angle (default: 0.7 m wide 4K screen at 0.7 m)");
    cmd->add_option("--blur", o->blur, "Sigma in pixels of the blur before the blurred PSNR/SSIM (> 0)");
    cmd->add_option("--regions", o->regions,
                    "N: also print the radiance ratio region by region, the box around the hair cut into N x N (0..16)");
    cmd->add_option("--min-iou", o->gates.min_iou, "Fail (exit 1) if the hair-mask IoU is below this");
    cmd->add_option("--min-blurred-psnr", o->gates.min_blurred_psnr_db, "Fail (exit 1) if the blurred PSNR (dB) is below this");
    cmd->add_option("--max-flip", o->gates.max_flip, "Fail (exit 1) if the tone-mapped mean FLIP over the hair is above this");
    cmd->add_option("--detail-range", o->gates.detail_range, "LO HI: fail (exit 1) if the detail ratio is outside [LO, HI]")->expected(2);
    cmd->add_option("--radiance-range", o->gates.radiance_range, "LO HI: fail (exit 1) if any channel's radiance ratio is outside [LO, HI]")
        ->expected(2);
    coif::cli::add_json_flag(cmd, o->json);
    coif::cli::examples(cmd, "  coif compare reference.exr render.exr\n"
                             "  coif compare reference.exr render.png --heatmap flip.png --json\n"
                             "  coif compare a.exr b.exr --mask none --exposure 1\n"
                             "  coif compare ref.exr render.exr --regions 4\n"
                             "  coif compare ref.exr render.exr --min-iou 0.9 --detail-range 0.8 1.25 --radiance-range 0.8 1.25");
    cmd->callback([o] {
        // Options first, so that a bad one writes nothing.
        o->gates.validate();
        coif::CompareOptions co;
        co.mask = coif::parse_mask_mode(o->mask);
        co.exposure = o->exposure;
        co.pixels_per_degree = o->ppd;
        co.blur_sigma = o->blur;
        co.regions = o->regions;
        coif::validate(co);
        if (!o->heatmap.empty()) coif::cli::lock_output(o->heatmap);
        const coif::Image a = coif::read_image(o->a);
        const coif::Image b = coif::read_image(o->b);
        const coif::CompareResult r = coif::compare_images(a, b, co, o->a, o->b);
        const std::vector<coif::cli::GateResult> gates = coif::cli::check_gates(o->gates, r);
        if (!r.appearance.radiance_warning.empty())
            std::fprintf(stderr, "coif compare: warning: %s\n", r.appearance.radiance_warning.c_str());
        if (!o->heatmap.empty()) {
            coif::WriteOptions wo;
            wo.description = "coif compare: per-pixel LDR-FLIP of " + o->b + " against " + o->a + " (magma-like ramp, 0 black, 1 pale yellow)";
            coif::write_image(o->heatmap, coif::error_heatmap(r.flip_tone_mapped, r.mask), wo);
        }
        const auto fail_gates = [&gates] {
            std::string failed;
            for (const auto& g : gates)
                if (!g.pass) failed += (failed.empty() ? "" : "; ") + g.name + " " + coif::format_metric(g.value, 4) + " is not " + g.bound;
            if (!failed.empty()) throw coif::Error::parameter("thresholds", failed);
        };
        if (o->json) {
            nlohmann::json doc = coif::cli::compare_json(r);
            doc["a"] = o->a;
            doc["b"] = o->b;
            doc["exposure"] = o->exposure;
            doc["pixels_per_degree"] = o->ppd;
            doc["heatmap"] = o->heatmap;
            doc["gates"] = coif::cli::gates_json(gates);
            coif::cli::print_json(doc);
            fail_gates();
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
        std::printf("FLIP observer: %.2f pixels per degree%s\n", o->ppd,
                    o->ppd == coif::kFlipPixelsPerDegree ? " (a 0.7 m wide 3840-px screen seen from 0.7 m)" : "");
        const coif::AppearanceMetrics& m = r.appearance;
        std::printf("\nappearance (B against A)\n");
        std::printf("  radiance ratio (R G B)     %s   (A %s, B %s; over %zu px that are hair in both)\n",
                    coif::cli::format_rgb(m.radiance_ratio, 3).c_str(), coif::cli::format_rgb(m.radiance_a, 4).c_str(),
                    coif::cli::format_rgb(m.radiance_b, 4).c_str(), m.pixels_both);
        std::printf("  hair-mask IoU              %s   (A %zu px, B %zu px, both %zu, either %zu)\n", coif::format_metric(m.mask_iou, 3).c_str(),
                    m.pixels_a, m.pixels_b, m.pixels_both, m.pixels_either);
        std::printf("  blurred PSNR / SSIM        %s dB / %.4f   (tone-mapped, Gaussian sigma %.3g px)\n",
                    coif::format_metric(m.blurred_psnr_db, 2).c_str(), m.blurred_ssim, m.blur_sigma);
        std::printf("  detail ratio               %s   (high-pass RMS: A %.4f, B %.4f)\n", coif::format_metric(m.detail_ratio, 3).c_str(),
                    m.detail_a, m.detail_b);
        if (m.regions.n > 0) {
            const coif::RegionRatios& g = m.regions;
            std::printf("  radiance ratio by region   the mean of R G B's ratios [pixels hair in both], %d x %d regions of the box\n"
                        "                             (%d, %d)-(%d, %d), rows from the top\n",
                        g.n, g.n, g.x0, g.y0, g.x1, g.y1);
            for (int row = 0; row < g.n; ++row) {
                std::printf("   ");
                for (int col = 0; col < g.n; ++col) {
                    const coif::RegionRatio& r = g.cells[static_cast<std::size_t>(row) * g.n + col];
                    const double mean = (r.radiance_ratio[0] + r.radiance_ratio[1] + r.radiance_ratio[2]) / 3.0;
                    std::printf(" %5s [%5zu]", coif::format_metric(mean, 2).c_str(), r.pixels);
                }
                std::printf("\n");
            }
        }
        if (!o->heatmap.empty()) std::printf("heatmap        %s\n", o->heatmap.c_str());
        if (!gates.empty()) {
            std::printf("\nthresholds\n");
            for (const auto& g : gates)
                std::printf("  %-26s %10s  %-18s %s\n", g.name.c_str(), coif::format_metric(g.value, 4).c_str(), g.bound.c_str(),
                            g.pass ? "pass" : "FAIL");
        }
        std::fflush(stdout);
        fail_gates();
    });
}

COIF_REGISTER_COMMAND(72, add_compare);

}  // namespace
