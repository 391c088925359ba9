#pragma once
// Line plots of exact vs approximate terms of the SRBF lighting (000 Fig. 3), drawn into a
// coif::Image without any plotting library: axes, zero lines and polylines (solid = exact,
// dashed = approximation). Labels are not drawn; plot_description() lists them.
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "models/core/image.h"
#include "shaders/lighting.h"

namespace coif::shading {

struct PlotSeries {
    std::string label;
    std::vector<double> x, y;
    glm::vec3 color{0.0f};
    bool dashed = false;
};

struct Plot {
    std::string title, x_label, y_label;
    std::vector<PlotSeries> series;
};

// White background, axes box, y = 0 line, series scaled to the joint data range.
Image render_plot(const Plot& plot, int width, int height);
std::string plot_csv(const Plot& plot);
std::string plot_description(const std::string& name, const Plot& plot);

// The four plots of 000 Fig. 3 (file stem → plot): n_tt, n_trt, t_taylor, quadrature_integrand, for
// `params` (the T plot uses σa = 0.2, 0.6, 1.0 as in the paper whatever params.sigma_a is).
std::vector<std::pair<std::string, Plot>> fig3_plots(const HairParams& params);

}  // namespace coif::shading
