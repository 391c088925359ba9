#pragma once
// The project's random generators, in one place. Every one is fully specified (the same numbers on
// every platform and compiler) and seeded only from integers the caller passes, never from time or
// a shared stream, so images, fits and databases are reproducible from their seeds:
//
//   Rng (std::mt19937_64)  general use: style fitting, strand export, environment fits, benchmarks.
//                          The engine is specified by the standard; the std:: distributions are not
//                          (libstdc++'s are what the committed figures were made with), so new code
//                          should prefer uniform01() below.
//   Pcg32                  the reference path tracer: one small stream per pixel, (seed, stream).
//   Xoshiro256             the HRIR database's sector generator: 53-bit doubles, normal, Poisson.
//   splitmix64             the 64-bit mix behind seeds (hashing a sector index, a pixel's stream).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include "models/core/units.h"

namespace coif {

// ---- seeds ------------------------------------------------------------------------------------

// 2^64 / φ (the golden ratio): splitmix64's increment, also used to spread per-stream seeds.
inline constexpr std::uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;

// splitmix64 (Steele, Lea, Flood 2014): mix(x + γ), a bijective 64-bit hash.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
    x += kGoldenGamma;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// The splitmix64 generator itself: returns splitmix64(state) and advances state by γ.
constexpr std::uint64_t splitmix64_next(std::uint64_t& state) {
    const std::uint64_t value = splitmix64(state);
    state += kGoldenGamma;
    return value;
}

// ---- Rng: std::mt19937_64 -----------------------------------------------------------------------

using Rng = std::mt19937_64;

// The seed of stream `stream` (a cluster, a job) of a run seeded with `seed`: seed·γ + stream.
constexpr std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream) { return seed * kGoldenGamma + stream; }

inline Rng seeded_rng(std::uint64_t seed) { return Rng(seed); }
inline Rng seeded_rng(std::uint64_t seed, std::uint64_t stream) { return Rng(stream_seed(seed, stream)); }

// A portable uniform double in [0, 1): the top 53 bits of one draw.
inline double uniform01(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// ---- Pcg32 ------------------------------------------------------------------------------------

// PCG32 (O'Neill 2014, XSH RR), seeded through splitmix64 so that neighbouring stream indices (pixels)
// give unrelated streams.
class Pcg32 {
public:
    Pcg32(std::uint64_t seed, std::uint64_t stream) {
        std::uint64_t s = seed ^ (stream * 0xD1B54A32D192ED03ull);
        state_ = splitmix64_next(s);
        inc_ = splitmix64_next(s) | 1u;
    }
    std::uint32_t next() {
        const std::uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<std::uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
    }
    // Uniform in [0, 1), 24 bits.
    float uniform() { return static_cast<float>(next() >> 8) * 0x1p-24f; }
    // Box–Muller, one value per call.
    float normal() {
        const float u1 = std::max(uniform(), 1e-12f), u2 = uniform();
        return std::sqrt(-2.0f * std::log(u1)) * std::cos(kTwoPiF * u2);
    }

private:
    std::uint64_t state_ = 0, inc_ = 1;
};

// ---- Xoshiro256 -------------------------------------------------------------------------------

// xoshiro256** (Blackman, Vigna 2018), its state filled by splitmix64 from one seed. Integer arithmetic
// plus std::log, std::sqrt, std::cos (normal, poisson): byte-identical wherever the C library is.
class Xoshiro256 {
public:
    explicit Xoshiro256(std::uint64_t seed) {
        for (auto& s : s_) {
            seed = splitmix64(seed);
            s = seed;
        }
    }
    std::uint64_t next() {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1), 53 bits
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    double log_uniform(double lo, double hi);  // log-uniform on [lo, hi], lo > 0
    double normal();                           // Box–Muller, one value per call
    std::uint64_t poisson(double mean);        // Knuth for mean ≤ 30, rounded normal above

private:
    static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::array<std::uint64_t, 4> s_{};
};

}  // namespace coif
