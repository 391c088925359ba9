#pragma once
// Strands from a cluster hairstyle, so that strand renderers (coif's reference renderer, other tools)
// can render the same hair as the cluster renderer.
//
// From densities (the default): for every cluster (instances included, placed by their transforms),
// the cross-section density of each sector plane i is the polar grid of its sectors' density cells
// (layers·grid_r rings × s_u·grid_s columns; the transparent core has none), weighted by cell area.
// The number of strands crossing plane i is n_i = weight × crossings for a "strands" density source,
// and ∫ρ dA / (πλ²) otherwise (one strand's Gaussian integrates to πλ²). A cluster gets max_i n_i
// strands; strand j crosses the planes where j + ½ < n_i (so strands end where the density thins
// toward the tips). Its position on each plane comes from the same random numbers (ξ_v, ξ_u) pushed
// through that plane's inverse CDF (ring by the ring marginal, column within the ring, linear inside
// the cell), so a strand moves continuously as the density changes from plane to plane. Between
// planes (v, u) are interpolated linearly in t (u the short way round) and evaluated on the envelope
// P(t, v, u) at `points_per_hsv` segments per HSV length.
//
// From members: a "strands" density source's stored runs, each a strand through its (v, u) on its
// planes — the fitted strands as the style remembers them. Other density kinds give no strands.
#include <cstdint>
#include <memory>
#include <vector>

#include "models/hair_style.h"
#include "models/strands.h"

namespace coif {

struct StrandSampling {
    enum class From { Density, Members };
    From from = From::Density;
    int points_per_hsv = 4;   // segments between consecutive sector planes
    std::uint32_t seed = 1;
    double max_strands = 5e6;  // refuse to produce more (a hand-written density of 1e9 would)
};

// Throws coif::Error (no file) if the style would produce more than max_strands strands. `strand_cluster`, if
// given, receives each strand's cluster (an index into style.clusters).
Strands sample_strands(const HairStyle& style, const StrandSampling& options,
                       std::vector<std::uint32_t>* strand_cluster = nullptr);

// sample_strands one cluster at a time, for a caller that keeps each cluster's strands between cooks of a style being
// edited (online/scene/cook.h): sample(c) is exactly the run of strands sample_strands gives cluster c (each cluster's
// random numbers are seeded by its index), and sample_strands is these runs in cluster order. The style must outlive it.
class ClusterStrandSampler {
public:
    ClusterStrandSampler(const HairStyle& style, const StrandSampling& options);
    ~ClusterStrandSampler();
    // How many strands sample(cluster) gives: from its prototype's densities (computed once per prototype and kept), or
    // its stored runs. Callers check the sum against options.max_strands before sampling (sample_strands does).
    std::size_t count(std::size_t cluster);
    Strands sample(std::size_t cluster);

private:
    struct Planes;
    const Planes& planes(std::size_t prototype);
    const HairStyle& style_;
    StrandSampling options_;
    std::vector<std::unique_ptr<Planes>> planes_;  // by prototype index, made on first use
};
// The error sample_strands throws when a style calls for `total` strands, more than `max`.
[[noreturn]] void refuse_strand_count(double total, double max);

}  // namespace coif
