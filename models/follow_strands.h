#pragma once
// Follow strands: a sparse set of guide strands filled into a head of hair, as AMD TressFX does with its follow hairs
// (`coif style import --strands-per-guide N`). A TressFX .tfx holds guide strands only, and the CT-scanned
// Curly_100/Bangs_100 hold 100 strands: fitted as they are, their clusters hold a few strands each, far sparser than
// any sector of the HRIR database (`coif db coverage`), so the shells look up records of far denser hair.
//
// Each guide is kept and gets N − 1 followers. A follower is its guide moved by one offset o, drawn uniformly from the
// disc of radius r in the plane perpendicular to the guide's first segment, and widened toward the tip as TressFX widens
// it: point k of n is guide point k + (1 + tip_separation · k / n) o. TressFX draws o from a square of half-side r; a
// disc fills round the guide evenly. r defaults to the median distance between neighbouring roots, so that the
// followers of neighbouring guides meet. Deterministic for a seed.
#include <cstdint>
#include <vector>

#include "models/strands.h"

namespace coif {

struct FollowOptions {
    int strands_per_guide = 1;   // the guide and its followers, 1 … kMaxStrandsPerGuide (1: the guides alone)
    double radius = 0;           // r, the file's units; 0: the median root spacing
    double tip_separation = 1;   // how much wider the followers spread at the tip than at the root, ≥ 0 (TressFX's factor)
    std::uint64_t seed = 1;
};
inline constexpr int kMaxStrandsPerGuide = 256;

// Throws coif::Error::parameter (naming the option) for a count outside 1 … kMaxStrandsPerGuide, a radius or tip
// separation that is negative or not finite, or a result beyond kMaxStrands / kMaxPoints.
void validate(const FollowOptions& o, const Strands& guides);

// The guides, each followed by its followers (guide i's strands are i·N … i·N + N − 1), with their per-point thickness,
// transparency and colour copied from the guide. `guide_of`, if given, receives each strand's guide. `radius_used`, if
// given, receives r.
Strands follow_strands(const Strands& guides, const FollowOptions& o, std::vector<std::uint32_t>* guide_of = nullptr,
                       double* radius_used = nullptr);

}  // namespace coif
