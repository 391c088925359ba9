#include "db/plot.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "db/satf.h"
#include "models/core/error.h"
#include "models/core/units.h"

namespace coif {

namespace {

void dot(Image& img, int x, int y, const std::array<float, 3>& c) {
    for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
            const int px = x + dx, py = y + dy;
            if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
            float* p = img.at(px, py);
            p[0] = c[0];
            p[1] = c[1];
            p[2] = c[2];
        }
}

// A polyline through the samples (sample j at x = (j + ½)/n of the panel), drawn column by column.
void curve(Image& img, int top, const std::vector<float>& v, const std::array<float, 3>& c) {
    const int n = static_cast<int>(v.size()), w = kPlotPanelWidth, h = kPlotPanelHeight - 8;
    int prev_y = -1;
    for (int px = 0; px < w; ++px) {
        const double f = std::clamp((px + 0.5) / w * n - 0.5, 0.0, n - 1.0);
        const int j = std::min(static_cast<int>(f), n - 2 < 0 ? 0 : n - 2);
        const double t = n > 1 ? f - j : 0.0;
        const double y = n > 1 ? (1 - t) * v[static_cast<std::size_t>(j)] + t * v[static_cast<std::size_t>(j + 1)] : v[0];
        const int py = top + 4 + static_cast<int>(std::lround((1.0 - std::clamp(y, 0.0, 1.0)) * h));
        if (prev_y >= 0)
            for (int yy = std::min(prev_y, py); yy <= std::max(prev_y, py); ++yy) dot(img, px, yy, c);
        else
            dot(img, px, py, c);
        prev_y = py;
    }
}

}  // namespace

Image plot_record(const HrirDatabase& db, std::size_t record) {
    if (record >= db.size())
        throw Error(db.path(), "record " + std::to_string(record), "out of range (the database holds " + std::to_string(db.size()) + ")");
    const AngleGrids& g = db.params().grids;
    const std::vector<float> rec = db.record(record);
    const std::array<double, 4> views{0.0, 45.0, 135.0, 180.0};
    Image img(kPlotPanelWidth, kPlotPanelHeight * static_cast<int>(views.size()), 3, 0.02f);
    const auto X = static_cast<std::size_t>(g.hrir_length);
    std::vector<float> re(X), alpha(X);
    for (std::size_t p = 0; p < views.size(); ++p) {
        const int top = static_cast<int>(p) * kPlotPanelHeight;
        for (int x = 0; x < kPlotPanelWidth; ++x) {
            dot(img, x, top + 4, {0.25f, 0.25f, 0.25f});
            dot(img, x, top + kPlotPanelHeight - 4, {0.25f, 0.25f, 0.25f});
        }
        const double tv = radians(views[p]);
        const std::array<double, 3> lights{tv, tv + kPi / 2, 0.0};
        const std::array<std::array<float, 3>, 3> colours{{{1.0f, 0.2f, 0.2f}, {0.2f, 1.0f, 0.2f}, {0.3f, 0.5f, 1.0f}}};
        for (std::size_t l = 0; l < lights.size(); ++l) {
            evaluate_record(g, rec, tv, lights[l], re, alpha);
            curve(img, top, re, colours[l]);
        }
        curve(img, top, alpha, {1.0f, 1.0f, 1.0f});
    }
    return img;
}

}  // namespace coif
