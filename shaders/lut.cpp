#include "shaders/lut.h"

#include <algorithm>
#include <cmath>

namespace coif::shading {

namespace {
thread_local const LutSet* t_bound = nullptr;
thread_local std::uint64_t t_fetches = 0;
}  // namespace

glm::vec4 LutImage::sample(glm::vec2 uv) const {
    if (width <= 0 || height <= 0) return glm::vec4(0.0f);
    // GL_LINEAR: texel coordinates with centres at integers after subtracting 0.5.
    const float px = uv.x * float(width) - 0.5f;
    const float py = uv.y * float(height) - 0.5f;
    const float fx = std::floor(px), fy = std::floor(py);
    const float tx = px - fx, ty = py - fy;
    const auto clamp_x = [&](int i) { return std::clamp(i, 0, width - 1); };
    const auto clamp_y = [&](int j) { return std::clamp(j, 0, height - 1); };
    const int x0 = clamp_x(int(fx)), x1 = clamp_x(int(fx) + 1);
    const int y0 = clamp_y(int(fy)), y1 = clamp_y(int(fy) + 1);
    const glm::vec4 a = glm::mix(at(x0, y0), at(x1, y0), tx);
    const glm::vec4 b = glm::mix(at(x0, y1), at(x1, y1), tx);
    return glm::mix(a, b, ty);
}

LutBinding::LutBinding(const LutSet& set) : previous_(t_bound) {
    if (previous_) merged_ = *previous_;
    for (int i = 0; i < kLutCount; ++i)
        if (set.images[i]) merged_.images[i] = set.images[i];
    t_bound = &merged_;
}

LutBinding::~LutBinding() { t_bound = previous_; }

glm::vec4 lut_fetch(Lut id, glm::vec2 uv) {
    ++t_fetches;
    if (!t_bound) return glm::vec4(0.0f);
    const LutImage* image = t_bound->images[static_cast<int>(id)];
    return image ? image->sample(uv) : glm::vec4(0.0f);
}

std::uint64_t lut_fetch_count() { return t_fetches; }

}  // namespace coif::shading
