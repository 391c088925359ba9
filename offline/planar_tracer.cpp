#include "offline/planar_tracer.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "models/core/json_field.h"
#include "models/core/units.h"

namespace coif {

namespace {

constexpr double kSmoothingCutoff = 3.0;  // the smoothing kernel is cut at 3 widths: exp(−9) ≈ 1e-4
constexpr double kNegligibleAlpha = 1e-9;

int wrap(int i, int n) {
    i %= n;
    return i < 0 ? i + n : i;
}

// Path of the eye ray inside the slab: its length and where it starts (see the header).
struct Path {
    glm::dvec2 start{0}, dir{0};
    double length = 0;
};

// The eye ray through (x, H) along −dir(θ).
Path slab_path(double x, double H, double theta, double cap) {
    Path p;
    p.dir = {-std::sin(theta), -std::cos(theta)};
    const double c = std::cos(theta);
    const double max_len = cap * H;
    p.length = std::abs(c) * max_len > H ? H / std::abs(c) : max_len;
    p.start = {x, H};
    if (c < 0) p.start -= p.dir * p.length;  // back view: enter at r = 0 (or the cap), end at (x, H)
    return p;
}

}  // namespace

nlohmann::json to_json(const TracerParams& p) {
    return {{"kappa_per_lambda", p.kappa},     {"kd", p.kd},
            {"ks", p.ks},                      {"phong_exponent", p.exponent},
            {"light_attenuation", p.light_attenuation},
            {"smoothing_ratio", p.smoothing_ratio},
            {"step_per_cell", p.step_per_cell}, {"grazing_cap_depths", p.grazing_cap},
            {"gradient_floor", p.gradient_floor}, {"gradient_rho0", p.gradient_rho0},
            {"opaque_alpha", kOpaqueAlpha}};
}

TracerParams tracer_params_from_json(const nlohmann::json& j) {
    const char* w = "JSON /tracer";
    TracerParams p;
    p.kappa = json_field<double>(j, "kappa_per_lambda", w);
    p.kd = json_field<double>(j, "kd", w);
    p.ks = json_field<double>(j, "ks", w);
    p.exponent = json_field<double>(j, "phong_exponent", w);
    p.light_attenuation = json_field<bool>(j, "light_attenuation", w);
    p.smoothing_ratio = json_field<double>(j, "smoothing_ratio", w);
    p.step_per_cell = json_field<double>(j, "step_per_cell", w);
    p.grazing_cap = json_field<double>(j, "grazing_cap_depths", w);
    p.gradient_floor = json_field<double>(j, "gradient_floor", w);
    p.gradient_rho0 = json_field<double>(j, "gradient_rho0", w);
    if (!(p.kappa >= 0 && p.exponent >= 1 && p.smoothing_ratio >= 0 && p.step_per_cell > 0 && p.step_per_cell <= 4 &&
          p.grazing_cap >= 1 && p.gradient_floor >= 0 && p.gradient_rho0 > 0))
        throw Error({}, w, "a tracer parameter is out of range");
    return p;
}

nlohmann::json to_json(const AngleGrids& g) {
    return {{"views", g.views},
            {"hrir_length", g.hrir_length},
            {"fourier_order", g.fourier_order},
            {"light_samples", g.light_samples},
            {"view_azimuths", "theta_v_i = 2 pi i / views, from +r towards +s"},
            {"layout", "alpha[views][hrir_length], then re[views][2K+1][hrir_length]; c=0: a0, c=2k-1: a_k, c=2k: b_k"}};
}

AngleGrids angle_grids_from_json(const nlohmann::json& j) {
    const char* w = "JSON /grids";
    AngleGrids g;
    g.views = json_field<int>(j, "views", w);
    g.hrir_length = json_field<int>(j, "hrir_length", w);
    g.fourier_order = json_field<int>(j, "fourier_order", w);
    g.light_samples = json_field<int>(j, "light_samples", w);
    if (g.views < 4 || g.views > 1024 || g.hrir_length < 2 || g.hrir_length > 4096 || g.fourier_order < 0 ||
        g.fourier_order > 64 || g.light_samples < g.coefficients() || g.light_samples > 4096)
        throw Error({}, w, "an angular grid is out of range (views 4–1024, hrir_length 2–4096, fourier_order 0–64, "
                           "light_samples ≥ 2K+1)");
    return g;
}

double phong_specular_average(double p) {
    return std::exp(std::lgamma((p + 1) / 2) - std::lgamma(p / 2 + 1)) / (2 * std::sqrt(kPi));
}

PlanarTracer::PlanarTracer(const SectorDensity& density, const TracerParams& params) : d_(density), p_(params) {
    if (d_.n_s < 1 || d_.n_r < 1 || !(d_.width > 0) || !(d_.depth > 0) ||
        d_.rho.size() != static_cast<std::size_t>(d_.n_s) * d_.n_r)
        throw Error::parameter("sector density", "empty or inconsistent grid");
    hs_ = d_.width / d_.n_s;
    hr_ = d_.depth / d_.n_r;
    step_ = p_.step_per_cell * std::min(hs_, hr_);
    specular_average_ = phong_specular_average(p_.exponent);
    grad_s_.resize(d_.rho.size());
    grad_r_.resize(d_.rho.size());
    for (int r = 0; r < d_.n_r; ++r)
        for (int s = 0; s < d_.n_s; ++s) {
            const std::size_t i = static_cast<std::size_t>(r) * d_.n_s + s;
            grad_s_[i] = static_cast<float>((d_.at(wrap(s + 1, d_.n_s), r) - d_.at(wrap(s - 1, d_.n_s), r)) / (2 * hs_));
            if (d_.n_r == 1) grad_r_[i] = 0;
            else if (r == 0) grad_r_[i] = static_cast<float>((d_.at(s, 1) - d_.at(s, 0)) / hr_);
            else if (r == d_.n_r - 1) grad_r_[i] = static_cast<float>((d_.at(s, r) - d_.at(s, r - 1)) / hr_);
            else grad_r_[i] = static_cast<float>((d_.at(s, r + 1) - d_.at(s, r - 1)) / (2 * hr_));
        }
}

double PlanarTracer::bilinear(const std::vector<float>& g, double s, double r) const {
    const double fs = s / hs_ - 0.5;
    const double fs0 = std::floor(fs);
    const double ts = fs - fs0;
    const int s0 = wrap(static_cast<int>(fs0), d_.n_s), s1 = wrap(s0 + 1, d_.n_s);
    const auto row = [&](int r) {
        const std::size_t o = static_cast<std::size_t>(r) * d_.n_s;
        return (1 - ts) * g[o + s0] + ts * g[o + s1];
    };
    if (d_.n_r == 1) return row(0);
    const double fr = std::clamp(r / hr_ - 0.5, 0.0, static_cast<double>(d_.n_r - 1));
    const int r0 = std::min(static_cast<int>(fr), d_.n_r - 2);
    const double tr = fr - r0;
    return (1 - tr) * row(r0) + tr * row(r0 + 1);
}

double PlanarTracer::density(double s, double r) const { return bilinear(d_.rho, s, r); }

glm::dvec2 PlanarTracer::gradient(double s, double r) const { return {bilinear(grad_s_, s, r), bilinear(grad_r_, s, r)}; }

double PlanarTracer::transmittance_to_light(double s, double r, double theta_l) const {
    const glm::dvec2 l{std::sin(theta_l), std::cos(theta_l)};
    const double max_len = p_.grazing_cap * d_.depth;
    const double room = l.y > 0 ? d_.depth - r : r;  // distance to the boundary the light comes through
    const double len = std::abs(l.y) * max_len > room ? room / std::abs(l.y) : max_len;
    if (len <= 0) return 1.0;
    const int n = std::max(1, static_cast<int>(std::ceil(len / step_)));
    const double dt = len / n;
    double tau = 0;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) * dt;
        tau += density(s + l.x * t, r + l.y * t);
    }
    return std::exp(-p_.kappa * tau * dt);
}

std::vector<float> PlanarTracer::transmittance_grid(double theta_l) const {
    std::vector<float> t(d_.rho.size());
    for (int r = 0; r < d_.n_r; ++r)
        for (int s = 0; s < d_.n_s; ++s)
            t[static_cast<std::size_t>(r) * d_.n_s + s] =
                static_cast<float>(transmittance_to_light((s + 0.5) * hs_, (r + 0.5) * hr_, theta_l));
    return t;
}

void PlanarTracer::smooth(std::span<float> v, int n_rays) const {
    // Periodic convolution with exp(−x²/w²), w = smoothing_ratio · λ (λ = 1), normalised discretely.
    const double w = p_.smoothing_ratio;
    const double delta = d_.width / n_rays;
    if (!(w > 0) || w < 0.25 * delta) return;  // narrower than a quarter ray spacing: nothing to smooth
    const int reach = std::min(n_rays / 2, static_cast<int>(std::ceil(kSmoothingCutoff * w / delta)));
    std::vector<double> kernel(static_cast<std::size_t>(2 * reach + 1));
    double sum = 0;
    for (int i = -reach; i <= reach; ++i) {
        const double x = i * delta / w;
        kernel[static_cast<std::size_t>(i + reach)] = std::exp(-x * x);
        sum += kernel[static_cast<std::size_t>(i + reach)];
    }
    // With n_rays even and reach = n_rays/2 the two ends of the kernel land on the same ray: fine,
    // the normalisation keeps the total weight 1.
    const std::vector<float> in(v.begin(), v.end());
    for (int q = 0; q < n_rays; ++q) {
        double acc = 0;
        for (int i = -reach; i <= reach; ++i) acc += kernel[static_cast<std::size_t>(i + reach)] * in[static_cast<std::size_t>(wrap(q + i, n_rays))];
        v[static_cast<std::size_t>(q)] = static_cast<float>(acc / sum);
    }
}

void PlanarTracer::trace_view(double theta_v, std::span<const double> theta_l, int hrir_length, std::span<float> alpha,
                              std::span<float> re) const {
    trace_view_impl(theta_v, theta_l, hrir_length, alpha, re, nullptr);
}

void PlanarTracer::trace_view_impl(double theta_v, std::span<const double> theta_l, int X, std::span<float> alpha,
                                   std::span<float> re, const std::vector<std::vector<float>>* shadows) const {
    const std::size_t n_l = theta_l.size();
    if (X < 1 || alpha.size() != static_cast<std::size_t>(X) || re.size() != n_l * X)
        throw Error::parameter("trace_view", "output spans do not match hrir_length × light count");
    std::vector<std::vector<float>> own_shadows;
    if (p_.light_attenuation && !shadows) {
        for (double tl : theta_l) own_shadows.push_back(transmittance_grid(tl));
        shadows = &own_shadows;
    }
    const int m = std::max(1, (d_.n_s + X - 1) / X);  // rays per HRIR sample: at least one per grid cell
    const int n_rays = X * m;
    const glm::dvec2 v{std::sin(theta_v), std::cos(theta_v)};
    std::vector<glm::dvec2> l(n_l);
    for (std::size_t j = 0; j < n_l; ++j) l[j] = {std::sin(theta_l[j]), std::cos(theta_l[j])};
    const double average = p_.kd / kPi + p_.ks * specular_average_;

    std::vector<float> ray_alpha(static_cast<std::size_t>(n_rays)), ray_re(n_l * n_rays);
    std::vector<double> acc_re(n_l);
    for (int q = 0; q < n_rays; ++q) {
        const Path path = slab_path((q + 0.5) * d_.width / n_rays, d_.depth, theta_v, p_.grazing_cap);
        const int n = std::max(1, static_cast<int>(std::ceil(path.length / step_)));
        const double dt = path.length / n;
        double a_hat = 0;
        std::fill(acc_re.begin(), acc_re.end(), 0.0);
        for (int k = 0; k < n && a_hat < kOpaqueAlpha; ++k) {
            const glm::dvec2 x = path.start + path.dir * ((k + 0.5) * dt);
            const double rho = density(x.x, x.y);
            const double a = 1.0 - std::exp(-p_.kappa * std::max(rho, 0.0) * dt);
            if (a < kNegligibleAlpha) continue;
            const double w = a * (1.0 - a_hat);
            const glm::dvec2 g = gradient(x.x, x.y);
            const double g2 = glm::dot(g, g);
            const double floor = p_.gradient_floor * (std::max(rho, 0.0) + p_.gradient_rho0);
            const double b = g2 / (g2 + floor * floor);  // trust in the normal
            const glm::dvec2 nrm = g2 > 0 ? -g / std::sqrt(g2) : glm::dvec2(0, 1);
            for (std::size_t j = 0; j < n_l; ++j) {
                const double nl = glm::dot(nrm, l[j]);
                double phong = 0;
                if (nl > 0) {
                    const double rv = glm::dot(2 * nl * nrm - l[j], v);
                    phong = p_.kd * nl + (rv > 0 ? p_.ks * std::pow(rv, p_.exponent) : 0.0);
                }
                double re_k = b * phong + (1 - b) * average;
                if (shadows) re_k *= bilinear((*shadows)[j], x.x, x.y);
                acc_re[j] += w * re_k;
            }
            a_hat += w;
        }
        ray_alpha[static_cast<std::size_t>(q)] = static_cast<float>(a_hat);
        for (std::size_t j = 0; j < n_l; ++j) ray_re[j * n_rays + q] = static_cast<float>(acc_re[j]);
    }
    // Smooth at ray resolution, then average each sample's box of m rays.
    const auto finish = [&](std::span<float> rays, std::span<float> out) {
        smooth(rays, n_rays);
        for (int j = 0; j < X; ++j) {
            double acc = 0;
            for (int i = 0; i < m; ++i) acc += rays[static_cast<std::size_t>(j * m + i)];
            out[static_cast<std::size_t>(j)] = static_cast<float>(acc / m);
        }
    };
    finish(ray_alpha, alpha);
    for (std::size_t j = 0; j < n_l; ++j)
        finish(std::span<float>(ray_re).subspan(j * n_rays, static_cast<std::size_t>(n_rays)), re.subspan(j * X, static_cast<std::size_t>(X)));
}

std::vector<float> PlanarTracer::trace_record(const AngleGrids& g) const {
    std::vector<float> rec(g.record_values(), 0.0f);
    const int X = g.hrir_length, N = g.light_samples, C = g.coefficients();
    std::vector<double> theta_l(static_cast<std::size_t>(N));
    for (int j = 0; j < N; ++j) theta_l[static_cast<std::size_t>(j)] = kTwoPi * j / N;
    std::vector<std::vector<float>> shadows;
    if (p_.light_attenuation)
        for (double tl : theta_l) shadows.push_back(transmittance_grid(tl));
    std::vector<float> re(static_cast<std::size_t>(N) * X);
    for (int i = 0; i < g.views; ++i) {
        const double theta_v = kTwoPi * i / g.views;
        trace_view_impl(theta_v, theta_l, X, std::span<float>(rec).subspan(g.alpha_offset(i), static_cast<std::size_t>(X)),
                        re, p_.light_attenuation ? &shadows : nullptr);
        // Projection on the Fourier basis (exact for orders below N − K, see AngleGrids).
        for (int c = 0; c < C; ++c) {
            const int k = (c + 1) / 2;
            const bool is_sin = c > 0 && c % 2 == 0;
            const double norm = c == 0 ? 1.0 / N : 2.0 / N;
            float* out = rec.data() + g.re_offset(i, c);
            for (int x = 0; x < X; ++x) {
                double acc = 0;
                for (int j = 0; j < N; ++j) {
                    const double a = k * theta_l[static_cast<std::size_t>(j)];
                    acc += re[static_cast<std::size_t>(j) * X + x] * (is_sin ? std::sin(a) : std::cos(a));
                }
                out[x] = static_cast<float>(norm * acc);
            }
        }
    }
    return rec;
}

}  // namespace coif
