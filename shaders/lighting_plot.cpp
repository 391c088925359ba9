#include "shaders/lighting_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "models/core/units.h"
#include "shaders/lighting.h"
#include "shaders/marschner_reference.h"

namespace coif::shading {

namespace {

const glm::vec3 kColors[] = {{0.85f, 0.1f, 0.1f}, {0.1f, 0.45f, 0.85f}, {0.1f, 0.65f, 0.2f}, {0.7f, 0.4f, 0.0f},
                             {0.5f, 0.1f, 0.7f}, {0.2f, 0.2f, 0.2f}};

void put(Image& img, int x, int y, glm::vec3 c) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    float* p = img.at(x, y);
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
}

void line(Image& img, double x0, double y0, double x1, double y1, glm::vec3 c, bool dashed, double& dash_phase) {
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, int(std::ceil(len * 2.0)));
    for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps;
        dash_phase += len / steps;
        if (dashed && std::fmod(dash_phase, 14.0) > 8.0) continue;
        const int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (std::abs(dx) + std::abs(dy) <= 1) put(img, x + dx, y + dy, c);
    }
}

}  // namespace

Image render_plot(const Plot& plot, int width, int height) {
    Image img(width, height, 3, 1.0f);
    double x0 = 1e300, x1 = -1e300, y0 = 0.0, y1 = -1e300;
    for (const auto& s : plot.series)
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (!std::isfinite(s.y[i])) continue;
            x0 = std::min(x0, s.x[i]);
            x1 = std::max(x1, s.x[i]);
            y0 = std::min(y0, s.y[i]);
            y1 = std::max(y1, s.y[i]);
        }
    if (!(x1 > x0)) x1 = x0 + 1.0;
    if (!(y1 > y0)) y1 = y0 + 1.0;
    y1 += 0.05 * (y1 - y0);
    const int ml = 40, mr = 20, mt = 20, mb = 40;
    const auto px = [&](double x) { return ml + (x - x0) / (x1 - x0) * (width - ml - mr); };
    const auto py = [&](double y) { return height - mb - (y - y0) / (y1 - y0) * (height - mt - mb); };
    double phase = 0.0;
    const glm::vec3 grey(0.6f), black(0.0f);
    line(img, px(x0), py(0.0), px(x1), py(0.0), grey, false, phase);
    line(img, px(x0), py(y0), px(x1), py(y0), black, false, phase);
    line(img, px(x0), py(y0), px(x0), py(y1), black, false, phase);
    for (int k = 0; k <= 10; ++k) {  // ticks at tenths of each range
        const double tx = px(x0 + k * (x1 - x0) / 10), ty = py(y0 + k * (y1 - y0) / 10);
        line(img, tx, py(y0), tx, py(y0) + 6, black, false, phase);
        line(img, px(x0), ty, px(x0) - 6, ty, black, false, phase);
    }
    for (const auto& s : plot.series) {
        phase = 0.0;
        for (size_t i = 1; i < s.x.size(); ++i) {
            if (!std::isfinite(s.y[i - 1]) || !std::isfinite(s.y[i])) continue;
            line(img, px(s.x[i - 1]), py(std::min(s.y[i - 1], y1)), px(s.x[i]), py(std::min(s.y[i], y1)), s.color, s.dashed,
                 phase);
        }
    }
    return img;
}

std::string plot_csv(const Plot& plot) {
    std::ostringstream out;
    out << "series,x,y\n";
    for (const auto& s : plot.series)
        for (size_t i = 0; i < s.x.size(); ++i) out << '"' << s.label << "\"," << s.x[i] << ',' << s.y[i] << '\n';
    return out.str();
}

std::string plot_description(const std::string& name, const Plot& plot) {
    std::ostringstream out;
    double x0 = 1e300, x1 = -1e300, y0 = 0.0, y1 = -1e300;
    for (const auto& s : plot.series)
        for (size_t i = 0; i < s.x.size(); ++i)
            if (std::isfinite(s.y[i])) {
                x0 = std::min(x0, s.x[i]);
                x1 = std::max(x1, s.x[i]);
                y0 = std::min(y0, s.y[i]);
                y1 = std::max(y1, s.y[i]);
            }
    out << name << ".png: " << plot.title << "\n  x: " << plot.x_label << " from " << x0 << " to " << x1 << "\n  y: "
        << plot.y_label << " from " << y0 << " to " << y1 << "\n";
    for (const auto& s : plot.series) {
        char rgb[64];
        std::snprintf(rgb, sizeof rgb, "rgb(%d,%d,%d)", int(255 * s.color.r), int(255 * s.color.g), int(255 * s.color.b));
        out << "  " << (s.dashed ? "dashed " : "solid  ") << rgb << "  " << s.label << "\n";
    }
    return out.str();
}

std::vector<std::pair<std::string, Plot>> fig3_plots(const HairParams& params) {
    using namespace glsl;
    validate(params, "lighting plot");
    const HairParams p = params;
    const LightingConfig cfg = default_config(4);
    LutBinding bind(global_lighting_tables().set());
    vec4 f0123, f45;
    srbf_point_setup(p, cfg, f0123, f45);
    const double thetas[] = {0.0, kPi / 6.0, kPi / 3.0};
    const char* theta_names[] = {"theta_d = 0", "theta_d = pi/6", "theta_d = pi/3"};
    std::vector<std::pair<std::string, Plot>> plots;
    constexpr int n = 361;

    for (int lobe : {LOBE_TT, LOBE_TRT}) {
        Plot plot;
        plot.title = lobe == LOBE_TT ? "N_TT: exact vs one circular Gaussian (000 eq. 16), red channel"
                                     : "N_TRT: exact (smoothed by w_c) vs three/one circular Gaussians (000 eq. 20)";
        plot.x_label = "phi (rad)";
        plot.y_label = "N (1/rad)";
        for (int t = 0; t < 3; ++t) {
            PlotSeries exact{std::string("exact, ") + theta_names[t], {}, {}, kColors[t], false};
            PlotSeries fit{std::string("approximation, ") + theta_names[t], {}, {}, kColors[t], true};
            for (int i = 0; i < n; ++i) {
                const double phi = -kPi + 2.0 * kPi * i / (n - 1);
                exact.x.push_back(phi);
                exact.y.push_back(reference::N_exact(lobe, p, p.eta, thetas[t], phi).x);
                fit.x.push_back(phi);
                fit.y.push_back(N_fit_value(lobe, p, cfg, f0123, f45, float(thetas[t]), float(phi)).x);
            }
            plot.series.push_back(exact);
            plot.series.push_back(fit);
        }
        plots.emplace_back(lobe == LOBE_TT ? "n_tt" : "n_trt", plot);
    }
    {
        Plot plot;
        plot.title = "T(sigma_a', h) at theta_d = 0: exact vs 4th-order Taylor (000 eq. 18, dashed) and our interpolation (dotted-dashed)";
        plot.x_label = "h";
        plot.y_label = "T";
        const double sigmas[] = {0.2, 0.6, 1.0};
        for (int s = 0; s < 3; ++s) {
            const vec3 sp = sigma_a_prime(vec3(float(sigmas[s])), p.eta, 0.0f);
            const float eta_p = eta_prime(p.eta, 0.0f);
            vec3 a0, a2, a4, b0, b2, b4;
            taylor_T(sp, eta_p, a0, a2, a4);
            interp_T(sp, eta_p, b0, b2, b4);
            char label[64];
            std::snprintf(label, sizeof label, "sigma_a = %.1f", sigmas[s]);
            PlotSeries exact{std::string("exact, ") + label, {}, {}, kColors[s], false};
            PlotSeries taylor{std::string("Taylor, ") + label, {}, {}, kColors[s], true};
            PlotSeries interp{std::string("interpolated, ") + label, {}, {}, kColors[s] * 0.6f, true};
            for (int i = 0; i < n; ++i) {
                const float h = float(-1.0 + 2.0 * i / (n - 1));
                exact.x.push_back(h);
                exact.y.push_back(attenuation_T(sp, h, eta_p).x);
                taylor.x.push_back(h);
                taylor.y.push_back(a0.x + a2.x * h * h + a4.x * h * h * h * h);
                interp.x.push_back(h);
                interp.y.push_back(b0.x + b2.x * h * h + b4.x * h * h * h * h);
            }
            plot.series.push_back(exact);
            plot.series.push_back(taylor);
            plot.series.push_back(interp);
        }
        plots.emplace_back("t_taylor", plot);
    }
    {
        Plot plot;
        plot.title = "N_t(lambda' = 0.5) cos^2(theta_i) / cos^2(theta_d), theta_o = 0: the smooth factor of the linear quadrature";
        plot.x_label = "theta_i (rad)";
        plot.y_label = "value";
        const struct {
            int lobe;
            double dphi;
            const char* name;
        } cases[] = {{LOBE_R, 0.0, "R, phi_o - phi_j = 0"}, {LOBE_R, kPi, "R, phi_o - phi_j = pi"},
                     {LOBE_TT, kPi, "TT, phi_o - phi_j = pi"}, {LOBE_TRT, 0.0, "TRT, phi_o - phi_j = 0"}};
        int color = 0;
        for (const auto& c : cases) {
            PlotSeries exact{std::string("exact, ") + c.name, {}, {}, kColors[color], false};
            PlotSeries approx{std::string("approximation, ") + c.name, {}, {}, kColors[color], true};
            ++color;
            for (int i = 1; i < 120; ++i) {
                const double ti = -0.5 * kPi + kPi * i / 120.0;
                const double td = 0.5 * (0.0 - ti);
                const double w = std::cos(ti) * std::cos(ti) / (std::cos(td) * std::cos(td));
                exact.x.push_back(ti);
                exact.y.push_back(w * reference::inner_exact(c.lobe, p, p.eta, td, 0.5, c.dphi).x);
                approx.x.push_back(ti);
                approx.y.push_back(w * srbf_N_inner(c.lobe, p, cfg, f0123, f45, float(td), 0.5f, float(c.dphi), 1.0f).x);
            }
            plot.series.push_back(exact);
            plot.series.push_back(approx);
        }
        plots.emplace_back("quadrature_integrand", plot);
    }
    return plots;
}

}  // namespace coif::shading
