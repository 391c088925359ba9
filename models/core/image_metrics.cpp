#include "models/core/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "models/core/error.h"
#include "models/core/units.h"
#include "shaders/common.h"

namespace coif {
namespace {

// ───────────────────────── separable filtering (borders clamped, as FLIP and SSIM assume) ─────────────────────────

// out(x, y) = Σ_k kx[k] · in(x + k − r, y), then the same along y with ky.
std::vector<float> filter_separable(const std::vector<float>& in, int w, int h, const std::vector<float>& kx,
                                    const std::vector<float>& ky) {
    const int rx = static_cast<int>(kx.size() / 2), ry = static_cast<int>(ky.size() / 2);
    std::vector<float> tmp(in.size()), out(in.size());
    for (int y = 0; y < h; ++y) {
        const float* row = in.data() + static_cast<size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int k = -rx; k <= rx; ++k) s += double(kx[k + rx]) * row[std::clamp(x + k, 0, w - 1)];
            tmp[static_cast<size_t>(y) * w + x] = static_cast<float>(s);
        }
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int k = -ry; k <= ry; ++k) s += double(ky[k + ry]) * tmp[static_cast<size_t>(std::clamp(y + k, 0, h - 1)) * w + x];
            out[static_cast<size_t>(y) * w + x] = static_cast<float>(s);
        }
    }
    return out;
}

std::vector<float> gaussian_taps(int radius, double sigma) {
    std::vector<float> k(2 * radius + 1);
    double sum = 0;
    for (int i = -radius; i <= radius; ++i) sum += k[i + radius] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)));
    for (auto& v : k) v = static_cast<float>(v / sum);
    return k;
}

// ───────────────────────── colour spaces of FLIP (sRGB primaries, D65 white) ─────────────────────────

using Vec3d = std::array<double, 3>;

constexpr double kD65[3] = {0.950428545, 1.0, 1.088900371};

Vec3d linear_rgb_to_xyz(const Vec3d& c) {
    return {(10135552.0 * c[0] + 8788810.0 * c[1] + 4435075.0 * c[2]) / 24577794.0,
            (2613072.0 * c[0] + 8788810.0 * c[1] + 887015.0 * c[2]) / 12288897.0,
            (1425312.0 * c[0] + 8788810.0 * c[1] + 70074185.0 * c[2]) / 73733382.0};
}
Vec3d xyz_to_linear_rgb(const Vec3d& c) {
    return {3.241003275 * c[0] - 1.537398934 * c[1] - 0.498615861 * c[2],
            -0.969224334 * c[0] + 1.875930071 * c[1] + 0.041554224 * c[2],
            0.055639423 * c[0] - 0.204011202 * c[1] + 1.057148933 * c[2]};
}
// YCxCz: the linear (no cube root) opponent space of FLIP §3.1 (after Zhang & Wandell's S-CIELAB).
Vec3d xyz_to_ycxcz(const Vec3d& c) {
    const double x = c[0] / kD65[0], y = c[1] / kD65[1], z = c[2] / kD65[2];
    return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}
Vec3d ycxcz_to_xyz(const Vec3d& c) {
    const double y = (c[0] + 16.0) / 116.0;
    return {(y + c[1] / 500.0) * kD65[0], y * kD65[1], (y - c[2] / 200.0) * kD65[2]};
}
Vec3d xyz_to_lab(const Vec3d& c) {
    constexpr double delta = 6.0 / 29.0;
    const auto f = [&](double t) { return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0; };
    const double fx = f(c[0] / kD65[0]), fy = f(c[1] / kD65[1]), fz = f(c[2] / kD65[2]);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}
// Hunt adjustment (FLIP §3.1): chroma scaled by 0.01 L*, so dark colours differ less.
Vec3d hunt_lab(const Vec3d& linear_rgb) {
    Vec3d lab = xyz_to_lab(linear_rgb_to_xyz(linear_rgb));
    lab[1] *= 0.01 * lab[0];
    lab[2] *= 0.01 * lab[0];
    return lab;
}
double hyab(const Vec3d& a, const Vec3d& b) {
    return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}
double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }
double srgb_encode(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

// ───────────────────────── FLIP filters ─────────────────────────

// The contrast sensitivity of FLIP §3.1: per channel a sum of two Gaussians in the frequency domain,
// S(x) = Σ a_k sqrt(π/b_k) exp(−π² x² / b_k) in the spatial domain (x in degrees); (a1, b1, a2, b2):
constexpr double kCsf[3][4] = {{1.0, 0.0047, 0.0, 1e-5},     // achromatic
                               {1.0, 0.0053, 0.0, 1e-5},     // red-green
                               {34.1, 0.04, 13.5, 0.025}};   // blue-yellow
constexpr double kCsfMaxB = 0.04;

struct CsfFilter {
    // The 2D kernel normalised to unit sum is Σ_k weight[k] · taps[k](x) taps[k](y).
    std::vector<float> taps[2];
    double weight[2] = {0, 0};
    int terms = 0;
};

CsfFilter csf_filter(int channel, double ppd) {
    const int r = static_cast<int>(std::ceil(3.0 * std::sqrt(kCsfMaxB / (2.0 * kPi * kPi)) * ppd));
    const double dx = 1.0 / ppd;
    CsfFilter f;
    double total = 0;
    for (int k = 0; k < 2; ++k) {
        const double a = kCsf[channel][2 * k], b = kCsf[channel][2 * k + 1];
        if (a == 0.0) continue;
        std::vector<float> taps(2 * r + 1);
        double sum = 0;
        for (int i = -r; i <= r; ++i) sum += taps[i + r] = static_cast<float>(std::exp(-kPi * kPi * (i * dx) * (i * dx) / b));
        const double amp = a * std::sqrt(kPi / b);
        f.taps[f.terms] = std::move(taps);
        f.weight[f.terms] = amp;
        total += amp * sum * sum;
        ++f.terms;
    }
    for (int k = 0; k < f.terms; ++k) f.weight[k] /= total;
    return f;
}

std::vector<float> apply_csf(const std::vector<float>& in, int w, int h, const CsfFilter& f) {
    std::vector<float> out(in.size(), 0.0f);
    for (int k = 0; k < f.terms; ++k) {
        const std::vector<float> part = filter_separable(in, w, h, f.taps[k], f.taps[k]);
        for (size_t i = 0; i < out.size(); ++i) out[i] += static_cast<float>(f.weight[k] * part[i]);
    }
    return out;
}

// Edge (first derivative) or point (second derivative) detector of FLIP §3.2: a Gaussian of standard
// deviation 0.5 · w · ppd, w = 0.082°, differentiated along x; positive weights normalised to sum 1
// and negative ones to −1. Both factor into x taps and y taps (the y factor is the plain Gaussian).
struct FeatureFilter {
    std::vector<float> along;   // the derivative factor
    std::vector<float> across;  // the Gaussian factor, unit sum
};

FeatureFilter feature_filter(bool point, double ppd) {
    constexpr double kW = 0.082;
    const double sd = 0.5 * kW * ppd;
    const int r = static_cast<int>(std::ceil(3.0 * sd));
    FeatureFilter f;
    f.along.resize(2 * r + 1);
    f.across.resize(2 * r + 1);
    double gsum = 0, pos = 0, neg = 0;
    for (int i = -r; i <= r; ++i) {
        const double g = std::exp(-double(i) * i / (2.0 * sd * sd));
        const double d = point ? (double(i) * i / (sd * sd) - 1.0) * g : -double(i) * g;
        f.along[i + r] = static_cast<float>(d);
        f.across[i + r] = static_cast<float>(g);
        gsum += g;
        (d > 0 ? pos : neg) += d;
    }
    for (auto& v : f.along) v = static_cast<float>(v > 0 ? v / pos : v / -neg);
    for (auto& v : f.across) v = static_cast<float>(v / gsum);
    return f;
}

// |∇| of the feature response: sqrt(fx² + fy²), fx with the filter along x, fy along y.
std::vector<float> feature_magnitude(const std::vector<float>& y, int w, int h, const FeatureFilter& f) {
    const std::vector<float> fx = filter_separable(y, w, h, f.along, f.across);
    const std::vector<float> fy = filter_separable(y, w, h, f.across, f.along);
    std::vector<float> m(y.size());
    for (size_t i = 0; i < m.size(); ++i) m[i] = std::hypot(fx[i], fy[i]);
    return m;
}

// Throws coif::Error::parameter naming `what` when the sizes differ.
void check_same_size(int aw, int ah, int bw, int bh, const std::string& what) {
    if (aw != bw || ah != bh)
        throw Error::parameter(what, "sizes differ: " + std::to_string(aw) + "x" + std::to_string(ah) + " and " + std::to_string(bw) +
                                         "x" + std::to_string(bh));
}
void check_same_size(const Planes& a, const Planes& b) { check_same_size(a.width, a.height, b.width, b.height, "images"); }
// Throws coif::Error naming `name` and the first pixel that holds a NaN or an infinite value.
void check_finite(const Image& im, const std::string& name) {
    for (size_t i = 0; i < im.pixels.size(); ++i)
        if (!std::isfinite(im.pixels[i])) {
            const size_t px = i / im.channels;
            throw Error(name, "pixel (" + std::to_string(px % im.width) + ", " + std::to_string(px / im.width) + ")",
                        "NaN or infinite value");
        }
}

// ACES filmic approximation (Narkowicz 2016) with the 0.6 pre-exposure folded in, as HDR-FLIP uses it.
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
double aces(double x) {
    x = std::max(x, 0.0);
    const double num = kAces[0] * x * x + kAces[1] * x + kAces[2];
    const double den = kAces[3] * x * x + kAces[4] * x + kAces[5];
    return std::isfinite(den) ? std::clamp(num / den, 0.0, 1.0) : 1.0;
}
// The x that tone-maps to t.
double aces_inverse(double t) {
    const double c0 = (kAces[1] - kAces[4] * t) / (kAces[0] - kAces[3] * t);
    const double c1 = (kAces[2] - kAces[5] * t) / (kAces[0] - kAces[3] * t);
    return -0.5 * c0 + std::sqrt(0.25 * c0 * c0 - c1);
}

double luminance709(const Planes& p, size_t i) {
    return glm::dot(glm::dvec3(glsl::COIF_LUMINANCE), glm::dvec3(p.c[0][i], p.c[1][i], p.c[2][i]));
}

bool has_informative_alpha(const Image& image) {
    if (image.channels < 4) return false;
    for (size_t i = 3; i < image.pixels.size(); i += 4)
        if (image.pixels[i] < 1.0f - 1e-6f) return true;
    return false;
}

}  // namespace

// ───────────────────────── masks ─────────────────────────

MaskMode parse_mask_mode(const std::string& text) {
    if (text == "auto") return MaskMode::automatic;
    if (text == "alpha") return MaskMode::alpha;
    if (text == "background") return MaskMode::background;
    if (text == "none") return MaskMode::none;
    throw Error::parameter("option --mask", "'" + text + "' is not one of auto, alpha, background, none");
}

HairMask image_hair_mask(const Image& image, MaskMode mode, float exposure, const std::string& name) {
    HairMask m;
    m.width = image.width;
    m.height = image.height;
    m.inside.assign(static_cast<size_t>(image.width) * image.height, 0);
    if (mode == MaskMode::none) {
        std::fill(m.inside.begin(), m.inside.end(), 1);
        m.count = m.inside.size();
        m.rule = "every pixel";
        m.alpha = has_informative_alpha(image);
        return m;
    }
    if (mode == MaskMode::alpha || (mode == MaskMode::automatic && has_informative_alpha(image))) {
        if (image.channels < 4) throw Error(name, "mask", "--mask alpha: the image has no alpha channel");
        for (size_t i = 0; i < m.inside.size(); ++i) m.inside[i] = image.pixels[i * 4 + 3] > kMaskAlphaThreshold;
        m.rule = "alpha > " + format_metric(kMaskAlphaThreshold, 2);
        m.alpha = true;
    } else {
        const float scale = std::exp2(exposure);
        const auto tm = [&](int x, int y, int c) { return tone_map_srgb(image.at(x, y)[c], scale); };
        const int cx[4] = {0, image.width - 1, 0, image.width - 1}, cy[4] = {0, 0, image.height - 1, image.height - 1};
        float bg[3];
        for (int c = 0; c < 3; ++c) bg[c] = tm(0, 0, c);
        bool corners_agree = true;
        for (int k = 1; k < 4; ++k)
            for (int c = 0; c < 3; ++c) corners_agree = corners_agree && std::abs(tm(cx[k], cy[k], c) - bg[c]) <= kBackgroundTolerance;
        if (!corners_agree) {
            if (mode == MaskMode::background)
                throw Error(name, "mask", "--mask background: the four corner pixels differ, so there is no uniform background");
            return m;  // auto: this image says nothing
        }
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                bool hair = false;
                for (int c = 0; c < 3; ++c) hair = hair || std::abs(tm(x, y, c) - bg[c]) > kBackgroundTolerance;
                m.inside[static_cast<size_t>(y) * image.width + x] = hair;
            }
        for (int c = 0; c < 3; ++c) m.background[c] = image.at(0, 0)[c];
        char buf[160];
        std::snprintf(buf, sizeof buf, "differs from the corner background (sRGB %.3f %.3f %.3f) by > 1.5/255", bg[0], bg[1], bg[2]);
        m.rule = buf;
    }
    m.count = static_cast<size_t>(std::count(m.inside.begin(), m.inside.end(), 1));
    return m;
}

HairMasks hair_masks(const Image& a, const Image& b, MaskMode mode, float exposure) {
    check_same_size(a.width, a.height, b.width, b.height, "images");
    HairMasks masks{image_hair_mask(a, mode, exposure, "A"), image_hair_mask(b, mode, exposure, "B"), {}};
    const HairMask& ma = masks.a;
    const HairMask& mb = masks.b;
    if (ma.rule.empty() && mb.rule.empty())
        throw Error::parameter("mask", "neither image has alpha or a uniform background (equal corner pixels), so hair pixels cannot "
                                       "be told apart: use --mask none, or images with alpha");
    HairMask m = ma;
    for (size_t i = 0; i < m.inside.size(); ++i) m.inside[i] = ma.inside[i] || mb.inside[i];
    m.count = static_cast<size_t>(std::count(m.inside.begin(), m.inside.end(), 1));
    m.rule = ma.rule == mb.rule ? ma.rule + " in A or B"
                                : "A: " + (ma.rule.empty() ? std::string("none") : ma.rule) + "; B: " + (mb.rule.empty() ? std::string("none") : mb.rule);
    if (m.count == 0) throw Error::parameter("mask", "no hair pixels in either image (" + m.rule + ")");
    masks.either = std::move(m);
    return masks;
}

HairMask hair_mask(const Image& a, const Image& b, MaskMode mode, float exposure) { return hair_masks(a, b, mode, exposure).either; }

// ───────────────────────── planes ─────────────────────────

Planes linear_planes(const Image& image) {
    Planes p;
    p.width = image.width;
    p.height = image.height;
    const size_t n = static_cast<size_t>(image.width) * image.height;
    for (auto& c : p.c) c.resize(n);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) p.c[c][i] = image.pixels[i * image.channels + c];
    return p;
}

Planes tone_mapped_planes(const Image& image, float exposure) {
    Planes p = linear_planes(image);
    const float scale = std::exp2(exposure);
    for (auto& c : p.c)
        for (auto& v : c) v = tone_map_srgb(v, scale);
    return p;
}

double masked_mean(const std::vector<float>& map, const HairMask& mask) {
    double sum = 0;
    size_t n = 0;
    for (size_t i = 0; i < map.size(); ++i)
        if (mask.inside[i]) sum += map[i], ++n;
    return n ? sum / double(n) : 0.0;
}

Planes gaussian_blur(const Planes& p, double sigma) {
    const std::vector<float> g = gaussian_taps(static_cast<int>(std::ceil(3.0 * sigma)), sigma);
    Planes out = p;
    for (int c = 0; c < 3; ++c) out.c[c] = filter_separable(p.c[c], p.width, p.height, g, g);
    return out;
}

// ───────────────────────── PSNR, SSIM ─────────────────────────

namespace {

// Mean squared difference over the three channels of the pixels where inside[i] (0 when there are none).
double masked_mse(const Planes& a, const Planes& b, const std::vector<std::uint8_t>& inside) {
    double se = 0;
    size_t n = 0;
    for (size_t i = 0; i < inside.size(); ++i) {
        if (!inside[i]) continue;
        for (int c = 0; c < 3; ++c) {
            const double d = double(a.c[c][i]) - double(b.c[c][i]);
            se += d * d;
        }
        n += 3;
    }
    return n ? se / double(n) : 0.0;
}

}  // namespace

double psnr(const Planes& a, const Planes& b, const HairMask& mask, double peak) {
    check_same_size(a, b);
    const double mse = masked_mse(a, b, mask.inside);
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(peak * peak / mse);
}

std::vector<float> ssim_map(const Planes& a, const Planes& b, double range) {
    check_same_size(a, b);
    // Wang et al. 2004 §III-C: 11×11 circular-symmetric Gaussian window, σ = 1.5; K1 = 0.01, K2 = 0.03.
    const std::vector<float> g = gaussian_taps(5, 1.5);
    const double c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
    const int w = a.width, h = a.height;
    const size_t n = static_cast<size_t>(w) * h;
    std::vector<float> out(n, 0.0f);
    for (int c = 0; c < 3; ++c) {
        std::vector<float> aa(n), bb(n), ab(n);
        for (size_t i = 0; i < n; ++i) {
            aa[i] = a.c[c][i] * a.c[c][i];
            bb[i] = b.c[c][i] * b.c[c][i];
            ab[i] = a.c[c][i] * b.c[c][i];
        }
        const auto mu_a = filter_separable(a.c[c], w, h, g, g), mu_b = filter_separable(b.c[c], w, h, g, g);
        const auto s_aa = filter_separable(aa, w, h, g, g), s_bb = filter_separable(bb, w, h, g, g), s_ab = filter_separable(ab, w, h, g, g);
        for (size_t i = 0; i < n; ++i) {
            const double ma = mu_a[i], mb = mu_b[i];
            const double va = std::max(0.0, s_aa[i] - ma * ma), vb = std::max(0.0, s_bb[i] - mb * mb), cov = s_ab[i] - ma * mb;
            const double s = ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            out[i] += static_cast<float>(s / 3.0);
        }
    }
    return out;
}

// ───────────────────────── FLIP ─────────────────────────

std::vector<float> flip_ldr_map(const Planes& ref, const Planes& test, double ppd) {
    check_same_size(ref, test);
    const int w = ref.width, h = ref.height;
    const size_t n = static_cast<size_t>(w) * h;
    constexpr double kQc = 0.7, kQf = 0.5, kPc = 0.4, kPt = 0.95;

    struct Prepared {
        std::vector<float> opp[3];  // YCxCz
        std::vector<float> y;       // normalised achromatic (Y + 16)/116 = Y/Y_n, for the features
    };
    const auto prepare = [&](const Planes& p) {
        Prepared q;
        for (auto& c : q.opp) c.resize(n);
        q.y.resize(n);
        for (size_t i = 0; i < n; ++i) {
            const Vec3d lin = {srgb_decode(std::clamp(p.c[0][i], 0.0f, 1.0f)), srgb_decode(std::clamp(p.c[1][i], 0.0f, 1.0f)),
                               srgb_decode(std::clamp(p.c[2][i], 0.0f, 1.0f))};
            const Vec3d o = xyz_to_ycxcz(linear_rgb_to_xyz(lin));
            for (int c = 0; c < 3; ++c) q.opp[c][i] = static_cast<float>(o[c]);
            q.y[i] = static_cast<float>((o[0] + 16.0) / 116.0);
        }
        return q;
    };
    const Prepared r = prepare(ref), t = prepare(test);

    // Colour pipeline: CSF filtering in YCxCz, back to linear RGB clamped to the unit cube,
    // Hunt-adjusted L*a*b*, HyAB.
    std::vector<float> fr[3], ft[3];
    for (int c = 0; c < 3; ++c) {
        const CsfFilter f = csf_filter(c, ppd);
        fr[c] = apply_csf(r.opp[c], w, h, f);
        ft[c] = apply_csf(t.opp[c], w, h, f);
    }
    const double cmax = std::pow(hyab(hunt_lab({0.0, 1.0, 0.0}), hunt_lab({0.0, 0.0, 1.0})), kQc);
    const auto filtered_hunt = [](const std::vector<float>* f, size_t i) {
        Vec3d rgb = xyz_to_linear_rgb(ycxcz_to_xyz({f[0][i], f[1][i], f[2][i]}));
        for (auto& v : rgb) v = std::clamp(v, 0.0, 1.0);
        return hunt_lab(rgb);
    };

    // Feature pipeline.
    const FeatureFilter edge = feature_filter(false, ppd), point = feature_filter(true, ppd);
    const auto er = feature_magnitude(r.y, w, h, edge), et = feature_magnitude(t.y, w, h, edge);
    const auto pr = feature_magnitude(r.y, w, h, point), pt = feature_magnitude(t.y, w, h, point);

    std::vector<float> out(n);
    for (size_t i = 0; i < n; ++i) {
        const double e = std::pow(hyab(filtered_hunt(fr, i), filtered_hunt(ft, i)), kQc);
        const double pccmax = kPc * cmax;
        const double dc = e < pccmax ? (kPt / pccmax) * e : kPt + (e - pccmax) / (cmax - pccmax) * (1.0 - kPt);
        const double df_raw = std::max(std::abs(double(er[i]) - et[i]), std::abs(double(pr[i]) - pt[i]));
        const double df = std::pow(df_raw / std::sqrt(2.0), kQf);
        out[i] = static_cast<float>(std::pow(dc, 1.0 - df));
    }
    return out;
}

HdrFlipExposures hdr_flip_exposures(const Planes& ref, const HairMask& mask) {
    std::vector<double> ys;
    for (size_t i = 0; i < mask.inside.size(); ++i)
        if (mask.inside[i]) ys.push_back(std::max(0.0, luminance709(ref, i)));
    HdrFlipExposures e;
    if (ys.empty()) return e;
    const double y_hi = *std::max_element(ys.begin(), ys.end());
    if (!(y_hi > 0)) return e;
    std::nth_element(ys.begin(), ys.begin() + ys.size() / 2, ys.end());
    double y_lo = ys[ys.size() / 2];
    if (!(y_lo > 0)) y_lo = y_hi;
    // HDR-FLIP §4: t_max = t_min = 0.85 for the ACES curve.
    const double x85 = aces_inverse(0.85);
    e.start = static_cast<float>(std::log2(x85 / y_hi));
    e.stop = static_cast<float>(std::log2(x85 / y_lo));
    e.count = std::max(2, static_cast<int>(std::ceil(e.stop - e.start)));
    return e;
}

std::vector<float> flip_hdr_map(const Planes& ref, const Planes& test, const HdrFlipExposures& e, double ppd) {
    check_same_size(ref, test);
    std::vector<float> out(static_cast<size_t>(ref.width) * ref.height, 0.0f);
    const auto tone = [](const Planes& p, double scale) {
        Planes q = p;
        for (auto& c : q.c)
            for (auto& v : c) v = static_cast<float>(srgb_encode(aces(scale * v)));
        return q;
    };
    for (int k = 0; k < e.count; ++k) {
        const double exposure = e.start + (e.count > 1 ? (e.stop - e.start) * k / (e.count - 1) : 0.0);
        const double scale = std::exp2(exposure);
        const auto m = flip_ldr_map(tone(ref, scale), tone(test, scale), ppd);
        for (size_t i = 0; i < out.size(); ++i) out[i] = std::max(out[i], m[i]);
    }
    return out;
}

// ───────────────────────── appearance metrics ─────────────────────────

namespace {

// R = Σ c·L / Σ c over `both` (image_metrics.h): the coverage-weighted mean hair radiance; and Σ c·|L| / Σ c, its
// mean magnitude.
void mean_hair_radiance(const Image& im, const HairMask& how, const std::vector<std::uint8_t>& both, double out[3],
                        double magnitude[3]) {
    double sum[3] = {0, 0, 0}, abs_sum[3] = {0, 0, 0}, weight = 0;
    for (size_t i = 0; i < both.size(); ++i) {
        if (!both[i]) continue;
        const float* p = im.pixels.data() + i * im.channels;
        const double c = how.alpha ? double(p[3]) : 1.0;
        for (int k = 0; k < 3; ++k) {
            const double l = how.alpha ? double(p[k]) : double(p[k]) - how.background[k];
            sum[k] += c * l;
            abs_sum[k] += c * std::abs(l);
        }
        weight += c;
    }
    for (int k = 0; k < 3; ++k) {
        out[k] = weight > 0 ? sum[k] / weight : 0.0;
        magnitude[k] = weight > 0 ? abs_sum[k] / weight : 0.0;
    }
}

// AppearanceMetrics::radiance_warning for image `which` (its name in the message) read as `how`, its mean hair
// radiance r and mean magnitude |r|: over a background, hair darker than it in some pixels and brighter in others
// cancels in the mean, which is then a small part of the mean magnitude (under a quarter of it: a relative error in
// the pixels is then more than 4 times larger in the mean).
std::string weak_radiance(const HairMask& how, const double r[3], const double magnitude[3], const char* which) {
    if (how.alpha) return {};
    static const char* const channel[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        if (magnitude[c] > 0.0 && std::abs(r[c]) < 0.25 * magnitude[c]) {
            char text[360];
            std::snprintf(text, sizeof text,
                          "the radiance ratio says little: %s's hair is darker than its background in some pixels and "
                          "brighter in others, so in %s its mean minus the background is %.0f %% of its mean difference "
                          "from it; draw both images over black (--background 0 0 0) or with alpha",
                          which, channel[c], 100.0 * std::abs(r[c]) / magnitude[c]);
            return text;
        }
    return {};
}

// The radiance ratio by region (AppearanceMetrics::regions): the box around `either` cut into n × n, each region's
// ratio as the whole image's, over its pixels of `both`.
RegionRatios region_ratios(const Image& a, const HairMask& ma, const Image& b, const HairMask& mb, const HairMask& either,
                           const std::vector<std::uint8_t>& both, int n) {
    RegionRatios out;
    out.n = n;
    const int w = either.width, h = either.height;
    out.x0 = w;
    out.y0 = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (either.inside[static_cast<std::size_t>(y) * w + x]) {
                out.x0 = std::min(out.x0, x);
                out.x1 = std::max(out.x1, x + 1);
                out.y0 = std::min(out.y0, y);
                out.y1 = std::max(out.y1, y + 1);
            }
    out.cells.resize(static_cast<std::size_t>(n) * n);
    std::vector<std::uint8_t> cell(both.size());
    for (int row = 0; row < n; ++row)
        for (int col = 0; col < n; ++col) {
            const int ya = out.y0 + (out.y1 - out.y0) * row / n, yb = out.y0 + (out.y1 - out.y0) * (row + 1) / n;
            const int xa = out.x0 + (out.x1 - out.x0) * col / n, xb = out.x0 + (out.x1 - out.x0) * (col + 1) / n;
            std::fill(cell.begin(), cell.end(), std::uint8_t{0});
            RegionRatio& r = out.cells[static_cast<std::size_t>(row) * n + col];
            for (int y = ya; y < yb; ++y)
                for (int x = xa; x < xb; ++x) {
                    const std::size_t i = static_cast<std::size_t>(y) * w + x;
                    cell[i] = both[i];
                    r.pixels += both[i];
                }
            double ra[3], rb[3], magnitude[3];
            mean_hair_radiance(a, ma, cell, ra, magnitude);
            mean_hair_radiance(b, mb, cell, rb, magnitude);
            for (int c = 0; c < 3; ++c)
                r.radiance_ratio[c] = r.pixels > 0 && ra[c] != 0.0 ? rb[c] / ra[c] : std::numeric_limits<double>::quiet_NaN();
        }
    return out;
}

// RMS over `both` and the three channels of p − G_σ * p.
double detail_rms(const Planes& p, const std::vector<std::uint8_t>& both) {
    return std::sqrt(masked_mse(p, gaussian_blur(p, kDetailSigma), both));
}

}  // namespace

std::array<double, 3> lit_weighted_ratio(const Image& unshadowed, const Image& shadowed, const Image& test, int cell,
                                         const std::string& names) {
    if (cell < 1) throw Error::parameter("lit-weighted ratio", "the cell must be at least one pixel");
    const Image* images[3] = {&unshadowed, &shadowed, &test};
    for (const Image* im : images) {
        check_same_size(unshadowed.width, unshadowed.height, im->width, im->height, names);
        if (im->channels < 3) throw Error(names, "images", "need RGB channels");
        check_finite(*im, names);
    }
    const int cx = (unshadowed.width + cell - 1) / cell, cy = (unshadowed.height + cell - 1) / cell;
    std::array<double, 3> num{}, den{};
    for (int j = 0; j < cy; ++j)
        for (int i = 0; i < cx; ++i) {
            double sum[3][3] = {};  // image, channel
            for (int y = j * cell; y < std::min((j + 1) * cell, unshadowed.height); ++y)
                for (int x = i * cell; x < std::min((i + 1) * cell, unshadowed.width); ++x)
                    for (int k = 0; k < 3; ++k)
                        for (int c = 0; c < 3; ++c) sum[k][c] += images[k]->at(x, y)[c];
            const double lit = sum[0][0] + sum[0][1] + sum[0][2];
            if (!(lit > 0)) continue;
            const double v = std::clamp((sum[1][0] + sum[1][1] + sum[1][2]) / lit, 0.0, 1.0);
            for (int c = 0; c < 3; ++c) {
                num[c] += v * sum[2][c];
                den[c] += v * sum[0][c];
            }
        }
    std::array<double, 3> ratio{};
    for (int c = 0; c < 3; ++c) {
        if (!(den[c] > 0)) throw Error(names, "images", "the light reaches no cell of the unshadowed image");
        ratio[c] = num[c] / den[c];
    }
    return ratio;
}

AppearanceMetrics appearance_metrics(const Image& a, const Image& b, const HairMasks& masks, const Planes& ta, const Planes& tb,
                                     double blur_sigma, const std::string& names, int regions) {
    AppearanceMetrics m;
    m.blur_sigma = blur_sigma;
    const bool own_masks = !masks.a.rule.empty() && !masks.b.rule.empty();
    // An image without a mask of its own (auto mode, no alpha and no uniform background) takes the other's.
    const HairMask& ma = masks.a.rule.empty() ? masks.b : masks.a;
    const HairMask& mb = masks.b.rule.empty() ? masks.a : masks.b;
    std::vector<std::uint8_t> both(masks.either.inside.size());
    for (size_t i = 0; i < both.size(); ++i) {
        both[i] = ma.inside[i] && mb.inside[i];
        m.pixels_both += both[i];
    }
    m.pixels_a = ma.count;
    m.pixels_b = mb.count;
    m.pixels_either = masks.either.count;
    if (m.pixels_both == 0)
        throw Error(names, "hair masks", "no pixel is hair in both images (A: " + std::to_string(ma.count) + " pixels, B: " +
                                             std::to_string(mb.count) + "), so their hair radiance cannot be compared");
    m.mask_iou = own_masks ? double(m.pixels_both) / double(m.pixels_either) : std::numeric_limits<double>::quiet_NaN();
    double magnitude_a[3], magnitude_b[3];
    mean_hair_radiance(a, ma, both, m.radiance_a, magnitude_a);
    mean_hair_radiance(b, mb, both, m.radiance_b, magnitude_b);
    for (int c = 0; c < 3; ++c)
        m.radiance_ratio[c] = m.radiance_a[c] != 0.0 ? m.radiance_b[c] / m.radiance_a[c] : std::numeric_limits<double>::quiet_NaN();
    m.radiance_warning = weak_radiance(ma, m.radiance_a, magnitude_a, "A");
    if (m.radiance_warning.empty()) m.radiance_warning = weak_radiance(mb, m.radiance_b, magnitude_b, "B");
    const Planes ba = gaussian_blur(ta, blur_sigma), bb = gaussian_blur(tb, blur_sigma);
    m.blurred_psnr_db = psnr(ba, bb, masks.either, 1.0);
    m.blurred_ssim = masked_mean(ssim_map(ba, bb, 1.0), masks.either);
    m.detail_a = detail_rms(ta, both);
    m.detail_b = detail_rms(tb, both);
    m.detail_ratio = m.detail_a > 0 ? m.detail_b / m.detail_a : std::numeric_limits<double>::quiet_NaN();
    if (regions > 0) m.regions = region_ratios(a, ma, b, mb, masks.either, both, regions);
    return m;
}

// ───────────────────────── the comparison ─────────────────────────

void validate(const CompareOptions& o) {
    if (!std::isfinite(o.exposure)) throw Error::parameter("option --exposure", "must be a finite number of stops");
    if (!(o.pixels_per_degree > 0) || !std::isfinite(o.pixels_per_degree))
        throw Error::parameter("option --ppd", "must be a positive number of pixels per degree");
    if (!(o.blur_sigma > 0) || !std::isfinite(o.blur_sigma) || o.blur_sigma > 1000)
        throw Error::parameter("option --blur", "must be a blur sigma in pixels, > 0 and at most 1000");
    if (o.regions < 0 || o.regions > kMaxRegions)
        throw Error::parameter("option --regions", "must be a number of regions along each side, 0 (none) to " +
                                                       std::to_string(kMaxRegions));
}

CompareResult compare_images(const Image& a, const Image& b, const CompareOptions& o, const std::string& a_name,
                             const std::string& b_name) {
    check_same_size(a.width, a.height, b.width, b.height, a_name + ", " + b_name);
    validate(o);
    check_finite(a, a_name);
    check_finite(b, b_name);
    CompareResult r;
    r.width = a.width;
    r.height = a.height;
    HairMasks masks;
    try {
        masks = hair_masks(a, b, o.mask, o.exposure);
    } catch (const Error& e) {
        throw Error(a_name + " vs " + b_name, e.place(), e.problem());
    }
    r.mask = masks.either;
    const Planes la = linear_planes(a), lb = linear_planes(b);
    // The linear peak: the 99th percentile of A's brightest channel over the mask, so that a few
    // fireflies of a noisy reference do not set the scale.
    std::vector<float> brightest;
    for (size_t i = 0; i < r.mask.inside.size(); ++i)
        if (r.mask.inside[i]) brightest.push_back(std::max({la.c[0][i], la.c[1][i], la.c[2][i]}));
    double peak = 0;
    if (!brightest.empty()) {
        const size_t k = std::min(brightest.size() - 1, static_cast<size_t>(kLinearPeakPercentile * double(brightest.size())));
        std::nth_element(brightest.begin(), brightest.begin() + static_cast<std::ptrdiff_t>(k), brightest.end());
        peak = brightest[k];
    }
    r.linear_peak = peak > 0 ? peak : 1.0;
    r.linear.psnr_db = psnr(la, lb, r.mask, r.linear_peak);
    r.linear.ssim = masked_mean(ssim_map(la, lb, r.linear_peak), r.mask);
    r.hdr_exposures = hdr_flip_exposures(la, r.mask);
    r.linear.flip = masked_mean(flip_hdr_map(la, lb, r.hdr_exposures, o.pixels_per_degree), r.mask);

    const Planes ta = tone_mapped_planes(a, o.exposure), tb = tone_mapped_planes(b, o.exposure);
    HairMask all = r.mask;
    std::fill(all.inside.begin(), all.inside.end(), 1);
    all.count = all.inside.size();
    r.flip_tone_mapped = flip_ldr_map(ta, tb, o.pixels_per_degree);
    const std::vector<float> ssim_t = ssim_map(ta, tb, 1.0);
    r.tone_mapped.psnr_db = psnr(ta, tb, r.mask, 1.0);
    r.tone_mapped.ssim = masked_mean(ssim_t, r.mask);
    r.tone_mapped.flip = masked_mean(r.flip_tone_mapped, r.mask);
    r.tone_mapped_all.psnr_db = psnr(ta, tb, all, 1.0);
    r.tone_mapped_all.ssim = masked_mean(ssim_t, all);
    r.tone_mapped_all.flip = masked_mean(r.flip_tone_mapped, all);
    r.appearance = appearance_metrics(a, b, masks, ta, tb, o.blur_sigma, a_name + " vs " + b_name, o.regions);
    return r;
}

// ───────────────────────── heatmap ─────────────────────────

Image error_heatmap(const std::vector<float>& error, const HairMask& mask) {
    // A magma-like ramp: sRGB colours of matplotlib's magma sampled at t = 0, 1/8, ..., 1 (plus 15/16),
    // interpolated linearly in sRGB.
    static constexpr float kRamp[10][4] = {
        {0.0f, 0.001f, 0.000f, 0.014f},   {0.125f, 0.079f, 0.054f, 0.212f}, {0.25f, 0.232f, 0.060f, 0.438f},
        {0.375f, 0.390f, 0.100f, 0.502f}, {0.5f, 0.550f, 0.161f, 0.506f},   {0.625f, 0.716f, 0.215f, 0.475f},
        {0.75f, 0.869f, 0.288f, 0.409f},  {0.875f, 0.968f, 0.440f, 0.360f}, {0.9375f, 0.994f, 0.624f, 0.427f},
        {1.0f, 0.987f, 0.991f, 0.750f}};
    Image out(mask.width, mask.height, 3);
    for (size_t i = 0; i < error.size(); ++i) {
        const float t = std::clamp(std::isfinite(error[i]) ? error[i] : 1.0f, 0.0f, 1.0f);
        int k = 0;
        while (k < 8 && t > kRamp[k + 1][0]) ++k;
        const float s = (t - kRamp[k][0]) / (kRamp[k + 1][0] - kRamp[k][0]);
        for (int c = 0; c < 3; ++c) {
            float srgb = kRamp[k][c + 1] + s * (kRamp[k + 1][c + 1] - kRamp[k][c + 1]);
            if (!mask.inside[i]) srgb *= 0.25f;
            out.pixels[i * 3 + c] = srgb_to_linear(srgb);
        }
    }
    return out;
}

std::string format_metric(double value, int decimals) {
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    if (std::isnan(value)) return "n/a";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return buf;
}

}  // namespace coif
