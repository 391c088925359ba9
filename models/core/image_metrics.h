#pragma once
// Image-quality numbers for comparing a render against a reference: PSNR, SSIM and FLIP, on linear
// and on tone-mapped pixels, averaged over a mask of hair pixels, and a false-colour error picture.
//
// Which image is which: A is the reference, B the image under test (FLIP's exposure range for linear
// images is taken from A; PSNR, SSIM and LDR-FLIP are symmetric).
//
// ── Tone-mapped ("display") pixels ──
//   The PNG tone map of models/core/image.h: c' = sRGB_OETF(clamp(c · 2^exposure, 0, 1)), so a PNG read
//   back (decoded sRGB → linear by read_image) tone-maps to exactly its own 8-bit values at exposure 0.
//
// ── Metrics (all on RGB; alpha is used only for the mask) ──
//   PSNR  10 log10(peak² / MSE), MSE over the three channels of the masked pixels. Tone-mapped: peak = 1.
//         Linear: peak = the 99th percentile over the masked pixels of A's largest channel (a linear image
//         has no natural peak; this makes the number independent of the image's overall scale, and the
//         percentile keeps a few fireflies of a noisy reference from setting it). Identical images give
//         +∞ (printed "inf").
//   SSIM  Wang, Bovik, Sheikh, Simoncelli 2004 ("Image quality assessment: from error visibility to
//         structural similarity"): 11×11 Gaussian window of σ = 1.5 px, K1 = 0.01, K2 = 0.03, dynamic
//         range L = the PSNR peak above; computed per channel on the whole image (borders clamped), the
//         per-pixel map averaged over the channels, then over the mask.
//   FLIP  LDR-FLIP of Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild 2020 ("FLIP: A
//         Difference Evaluator for Alternating Images", HPG 2020), implemented from the paper: CSF
//         pre-filtering in YCxCz, Hunt-adjusted L*a*b*, HyAB colour difference (q_c = 0.7, p_c = 0.4,
//         p_t = 0.95), edge/point feature difference (w = 0.082°, q_f = 0.5), ΔE = ΔE_c^(1 − ΔE_f); the
//         viewer sees kFlipPixelsPerDegree pixels per degree (the paper's default: a 0.7 m wide 4K
//         monitor at 0.7 m). On tone-mapped pixels this is the paper's LDR-FLIP on the sRGB images.
//         On linear pixels it is HDR-FLIP (Andersson, Nilsson, Shirley, Akenine-Möller 2021, "Visualizing
//         Errors in Rendered High Dynamic Range Images", same authors' extension to HDR): LDR-FLIP of the
//         ACES-tone-mapped images at exposures from start to stop (start puts A's brightest masked pixel
//         at 0.85 after tone mapping, stop puts A's median masked luminance there; max(2, ⌈stop − start⌉)
//         exposures), per-pixel maximum.
//
// ── Appearance metrics (docs/quality.md "Appearance metrics": why each is there) ──
//   Per-pixel PSNR/FLIP of a statistical texture against individual fibres reward blur, so these measure
//   what a person sees when fibres cannot line up pixel by pixel. Masks: M_A and M_B are each image's own
//   hair mask; "both" = M_A ∩ M_B, "either" = M_A ∪ M_B.
//   radiance ratio  per channel, R_B / R_A with R = Σ_both c·L / Σ_both c, the coverage-weighted mean hair
//                   radiance where both images show hair: for an image with alpha c = α and L = its RGB
//                   (straight alpha, as coif writes it); for an image over a uniform background c = 1 and
//                   L = pixel − background (so coverage is folded into L there). Linear pixels.
//   mask IoU        |M_A ∩ M_B| / |M_A ∪ M_B| (coverage and silhouette; undefined, NaN, when an image
//                   gives no mask of its own).
//   blurred PSNR/SSIM  PSNR and SSIM of the tone-mapped images after a Gaussian blur of σ = blur_sigma
//                   (default 2 px, cluster scale), over "either": the look at the scale of clusters, with
//                   fibre placement blurred away.
//   detail ratio    D_B / D_A with D = RMS over "both" and the three tone-mapped channels of the high-pass
//                   image − G_1px * image (σ = kDetailSigma): fibre structure; a smeared texture has < 1,
//                   a noisy one > 1.
//   FLIP            as above, at the stated pixels per degree (CompareOptions::pixels_per_degree).
//   radiance ratio by region (CompareOptions::regions = N > 0): the box around "either" cut into N × N
//                   regions of equal size (rows from the top), each region's radiance ratio as above over its
//                   pixels of "both": where in the image the hair is too bright or too dark, which one mean hides
//                   when errors of opposite sign cancel.
//
// ── Mask of hair pixels (the metrics are means over it; counts are reported) ──
//   Each image gets its own mask; the mask used is their union (a pixel that is hair in either image).
//   alpha:      the image has a 4th channel not everywhere ≥ 1 − 1e-6; hair where α > kMaskAlphaThreshold.
//   background: the four corner pixels agree (tone-mapped, within kBackgroundTolerance): that colour is
//               the background; hair where any tone-mapped channel differs from it by more than
//               kBackgroundTolerance (1.5 8-bit code values, so PNG rounding is not hair).
//   auto (default): alpha when the image has informative alpha, else background; an image with neither
//               contributes nothing; if neither image yields a mask, compare_images throws coif::Error.
//   none:       every pixel.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "models/core/image.h"
#include "models/core/units.h"

namespace coif {

// FLIP's default observer: 0.7 m wide 3840-px display seen from 0.7 m, 3840 · π/180 ≈ 67.02 px/degree.
inline constexpr double kFlipPixelsPerDegree = 3840.0 * kPi / 180.0;
// A pixel is hair when at least 5 % of it is covered (alpha masks); thin fibres cover most hair pixels
// only partly, so a 0.5 threshold would drop most of them.
inline constexpr float kMaskAlphaThreshold = 0.05f;
// 1.5 code values of an 8-bit sRGB image: tone-mapped differences at or below this are PNG rounding.
inline constexpr float kBackgroundTolerance = 1.5f / 255.0f;
// Percentile of A's masked pixels that sets the linear PSNR/SSIM peak.
inline constexpr double kLinearPeakPercentile = 0.99;
// σ of the blurred PSNR/SSIM: 2 px is about a cluster's strand spacing at 360×240 and below a cluster's width.
inline constexpr double kDefaultBlurSigma = 2.0;
// σ of the detail ratio's low-pass: 1 px keeps only what changes from pixel to pixel (fibres).
inline constexpr double kDetailSigma = 1.0;
// The most regions along each side of CompareOptions::regions: beyond it a region of a 360 × 240 render's hair holds
// too few pixels for its mean to say much.
inline constexpr int kMaxRegions = 16;

enum class MaskMode { automatic, alpha, background, none };
MaskMode parse_mask_mode(const std::string& text);  // "auto" | "alpha" | "background" | "none"

struct HairMask {
    int width = 0, height = 0;
    std::vector<std::uint8_t> inside;  // width × height, 1 = hair
    std::size_t count = 0;
    std::string rule;                  // how it was made, in words (for reports)
    // How to read a hair pixel's radiance (the radiance ratio): with `alpha`, c = α and L = RGB; otherwise
    // c = 1 and L = RGB − background (linear; 0 for mode none).
    bool alpha = false;
    float background[3] = {0, 0, 0};
};

// The mask of one image alone (see the header comment); `rule` says which rule applied, or is empty
// when none did (auto mode only). Throws coif::Error when an explicit mode cannot be applied.
HairMask image_hair_mask(const Image& image, MaskMode mode, float exposure, const std::string& name);
// Both images' own masks and their union. Throws coif::Error if the sizes differ or no mask can be made.
struct HairMasks {
    HairMask a, b, either;
};
HairMasks hair_masks(const Image& a, const Image& b, MaskMode mode, float exposure);
// The union of both images' masks (hair_masks(...).either).
HairMask hair_mask(const Image& a, const Image& b, MaskMode mode, float exposure);

// RGB planes of an image (channel-major, width × height each).
struct Planes {
    int width = 0, height = 0;
    std::vector<float> c[3];
};
Planes linear_planes(const Image& image);
// The PNG tone map of image.h applied to every channel (values in [0, 1], sRGB-encoded).
Planes tone_mapped_planes(const Image& image, float exposure);

// PSNR over the mask (+∞ when the masked pixels are identical).
double psnr(const Planes& a, const Planes& b, const HairMask& mask, double peak);
// Per-pixel SSIM (mean over the channels) with dynamic range `range`.
std::vector<float> ssim_map(const Planes& a, const Planes& b, double range);
// Per-pixel LDR-FLIP of two sRGB-encoded images with values in [0, 1] (reference, test).
std::vector<float> flip_ldr_map(const Planes& reference_srgb, const Planes& test_srgb,
                                double pixels_per_degree = kFlipPixelsPerDegree);

struct HdrFlipExposures {
    float start = 0, stop = 0;
    int count = 1;
};
HdrFlipExposures hdr_flip_exposures(const Planes& reference_linear, const HairMask& mask);
// Per-pixel HDR-FLIP of two linear images (max of LDR-FLIP over the exposures).
std::vector<float> flip_hdr_map(const Planes& reference_linear, const Planes& test_linear, const HdrFlipExposures& e,
                                double pixels_per_degree = kFlipPixelsPerDegree);

double masked_mean(const std::vector<float>& map, const HairMask& mask);

// Gaussian blur of σ pixels (taps to ±⌈3σ⌉, borders clamped) of every plane.
Planes gaussian_blur(const Planes& p, double sigma);

struct MetricSet {
    double psnr_db = 0;   // +∞ for identical pixels
    double ssim = 0;
    double flip = 0;      // mean FLIP
};

// One region of the radiance ratio by region (CompareOptions::regions).
struct RegionRatio {
    std::size_t pixels = 0;        // its pixels that are hair in both images
    double radiance_ratio[3] = {};  // B / A per channel over them (NaN where A's is 0 or there are none)
};
struct RegionRatios {
    int n = 0;                        // regions along each side; 0 = not asked for
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the box around "either", [x0, x1) × [y0, y1), pixels, y down
    std::vector<RegionRatio> cells;   // n × n, row by row from the top
};

struct AppearanceMetrics {
    std::size_t pixels_a = 0, pixels_b = 0, pixels_both = 0, pixels_either = 0;
    double mask_iou = 0;                            // NaN when an image gives no mask of its own
    double radiance_a[3] = {}, radiance_b[3] = {};  // coverage-weighted mean hair radiance over "both"
    double radiance_ratio[3] = {};                  // radiance_b / radiance_a (NaN where A's is 0)
    double blur_sigma = kDefaultBlurSigma;
    double blurred_psnr_db = 0, blurred_ssim = 0;   // tone-mapped, after the blur, over "either"
    double detail_a = 0, detail_b = 0, detail_ratio = 0;
    // Set where the radiance ratio says little: an image read over a background (no alpha) whose hair is darker than
    // the background in some pixels and brighter in others, so that in a channel the mean of pixel − background is
    // under a quarter of the mean |pixel − background| (dark hair over the default blue-grey). Empty otherwise; `coif
    // compare` prints it as a warning.
    std::string radiance_warning;
    RegionRatios regions;  // the radiance ratio by region, when asked for
};

// The appearance metrics alone, from both images, their masks and their tone-mapped planes (compare_images
// calls it). Throws coif::Error naming `names` when no pixel is hair in both images.
AppearanceMetrics appearance_metrics(const Image& a, const Image& b, const HairMasks& masks, const Planes& ta, const Planes& tb,
                                     double blur_sigma, const std::string& names, int regions = 0);

struct CompareOptions {
    MaskMode mask = MaskMode::automatic;
    float exposure = 0.0f;   // stops, for the tone-mapped metrics
    double pixels_per_degree = kFlipPixelsPerDegree;
    double blur_sigma = kDefaultBlurSigma;  // pixels, > 0
    int regions = 0;  // the radiance ratio by region over N × N regions (AppearanceMetrics::regions); 0..kMaxRegions
};

struct CompareResult {
    int width = 0, height = 0;
    HairMask mask;
    double linear_peak = 0;            // the linear PSNR/SSIM peak (99th percentile of A's max channel on the mask)
    HdrFlipExposures hdr_exposures;
    MetricSet linear;                  // on the mask
    MetricSet tone_mapped;             // on the mask
    MetricSet tone_mapped_all;         // every pixel, for reference
    std::vector<float> flip_tone_mapped;  // the LDR-FLIP map behind tone_mapped.flip (for the heatmap)
    AppearanceMetrics appearance;
};

// Throws coif::Error::parameter naming the option for a non-finite exposure, a pixels-per-degree that is not
// positive, a blur σ outside (0, 1000] or regions outside 0..kMaxRegions (compare_images calls it; a command calls it before reading images).
void validate(const CompareOptions& options);

// Compares A (reference) and B (test). Throws coif::Error (naming a_name/b_name) if the sizes differ,
// a pixel is NaN/Inf, the blur σ is not a positive number, no mask can be made, or the two images' hair
// does not overlap (no pixel is hair in both, so there is no radiance to compare).
CompareResult compare_images(const Image& a, const Image& b, const CompareOptions& options,
                             const std::string& a_name = "A", const std::string& b_name = "B");

// The radiance ratio of `test` against `unshadowed` where a light reaches (coif bench sweep --where-lit): each image
// averaged over cells of `cell` × `cell` pixels, each cell weighed by the share of the light that reaches it,
// V = Σ_c shadowed / Σ_c unshadowed over its channels, clamped to [0, 1] (0 where the unshadowed cell is black); per
// channel Σ V · test / Σ V · unshadowed. `unshadowed` and `shadowed` are the same scene's references without and with
// shadows, `test` a render lit unshadowed. An unshadowed ratio over the whole image weighs the fibres the light never
// reaches as much as those it does; this one weighs them as the shadowed image does (docs/quality.md, "Where the light
// reaches"). Throws coif::Error naming `names` if the sizes differ, a value is not finite, `cell` < 1, or no cell is
// reached.
std::array<double, 3> lit_weighted_ratio(const Image& unshadowed, const Image& shadowed, const Image& test, int cell,
                                         const std::string& names);

// The false-colour error picture: per-pixel error in [0, 1] through a magma-like ramp (black → purple →
// orange → pale yellow); pixels outside the mask are drawn at a quarter of their brightness. Returns a
// linear RGB image whose PNG (write_image's sRGB tone map at exposure 0) shows the ramp's sRGB colours.
Image error_heatmap(const std::vector<float>& error, const HairMask& mask);

// "inf" for +∞, "n/a" for NaN, else the number with `decimals` decimals.
std::string format_metric(double value, int decimals);

}  // namespace coif
