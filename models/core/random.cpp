#include "models/core/random.h"

#include <algorithm>

namespace coif {

double Xoshiro256::log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * uniform()); }

double Xoshiro256::normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

std::uint64_t Xoshiro256::poisson(double mean) {
    if (!(mean > 0)) return 0;
    if (mean > 30) return static_cast<std::uint64_t>(std::max(0.0, std::round(mean + std::sqrt(mean) * normal())));
    const double limit = std::exp(-mean);
    std::uint64_t k = 0;
    double p = uniform();
    while (p > limit) {
        ++k;
        p *= uniform();
    }
    return k;
}

}  // namespace coif
