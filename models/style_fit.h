#pragma once
// Fitting a cluster hairstyle (models/hair_style.h) to real strands (.hair/.data), and measuring how
// well it fits.
//
// Method (deterministic for a given seed):
//  1. Orientation: the strands are rotated so that they hang along −y (coif's y-up convention),
//     by hang_axis_rotation() of models/strands.h: identity for y-up models such as harolongo.data,
//     −x → −y for the CT2Hair-derived Bangs/Curly files. No scaling: the style keeps the file's units.
//     The rotation is recorded in the style's "source".
//  2. Clustering by root position and shape: k-means (k-means++ seeding) on each strand resampled
//     at kShapeSamples points of relative arc length, the root counted kRootWeight times.
//  3. Trajectory T(t): least-squares cubic B-spline through the cluster's representative curve, the
//     mean of its members at equal absolute arc length from the root (members that end early drop
//     out of the mean), so T runs to the longest member's tip.
//  4. A, B, θ: on 2·s_t + 1 normal planes, the members' crossings (the crossing nearest the axis)
//     are expressed in the frame (n, b); their second-moment matrix about the axis gives the
//     principal axes (θ) and spreads σ1, σ2; A = k σ1, B = k σ2 with k the `coverage` quantile of
//     the crossings' normalised radius, so that that share of crossings lies inside. θ is unwrapped
//     (with A/B swapped at quarter turns) to turn continuously. A, B are floored at the Gaussian
//     width λ. Least-squares B-splines then give A(t), B(t), θ(t).
//     λ (layout.gaussian_width, the file's units) is, unless given, the median distance from each
//     root to its nearest neighbouring root: a kernel width that makes neighbouring strands' density
//     overlap. A sector is (1 − v_core)/L of its cluster's half-axis deep (0.2 with the defaults), so
//     a cluster at the floor is 0.2 λ deep whatever λ is; the HRIR database covers sectors 1.25–13 λ
//     deep (offline/sector_generator.h), which at the automatic λ takes half-axes ≳ 6 root spacings
//     (≳ 100 strands in a cross-section). Sparse files (the 100-strand Bangs/Curly guide sets) reach it only with
//     few clusters and a λ well below their strand spacing (docs/db.md "Coverage").
//  5. Density: each member's crossings of the s_t + 1 sector planes, as (v, u) runs ("strands"
//     density source); with store_every = n only every n-th member is stored, weight n.
//  6. Macro-clusters: clusters are visited by decreasing member count; each is compared with the
//     prototypes found so far after a least-squares similarity alignment (Umeyama 1991) of their
//     trajectories; if the RMS distance between the aligned envelope descriptors (axis points and
//     ellipse axis end points at 9 values of t) is below macro_tolerance × the cluster's mean radius,
//     it becomes an instance of that prototype (sharing its geometry and density).
//
// Strays (StrayReport): how far a cluster's envelope reaches where none of its strands are. Its outer
// surface v = 1 is sampled on the (t, u) grid of 2·s_t + 1 rings × kStraySamplesU (placed as drawn); each sample's
// distance to the nearest point of the cluster's own member strands, in units of the cluster's mean radius
// √(A B) (× the placement's scale). An envelope that follows its strands keeps this near 1 (the ellipse holds
// `coverage` of the crossings, so its rim is about one radius from the strands on the far side); a cluster
// that sticks out where no hair is has samples several radii from any strand.
//
// Fitting error (FitError): every strand point is located in its own cluster's final envelope
// (instances through their similarity transform): the share of points inside, the RMS distance
// of the outside points to the envelope, and the share of strands assigned (members of a cluster
// that cross at least one of its sector planes, i.e. whose crossings feed its density).
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "models/hair_style.h"
#include "models/strands.h"

namespace coif {

inline constexpr int kShapeSamples = 16;   // points per strand in the clustering feature
inline constexpr double kRootWeight = 2.0;  // the root counted twice: clusters are compact at the scalp
// A given Gaussian width must lie within [kMinGaussianWidthOverExtent, 1] × the diagonal of the strands'
// bounding box: wider than the whole model or a millionth of it is a units mistake (and below ~1e-150
// the 1/λ² of the density overflows).
inline constexpr double kMinGaussianWidthOverExtent = 1e-6;

struct FitOptions {
    int clusters = 64;
    DiskLayout layout;                // gaussian_width 0: automatic (the median root spacing); else see
                                      // check_gaussian_width
    int trajectory_control_points = 8;
    int profile_control_points = 6;   // A, B, θ
    double coverage = 0.98;           // share of crossings inside the ellipse at each fitting plane
    double macro_tolerance = 0.25;    // fraction of the mean radius; 0 disables macro-clusters
    int kmeans_iterations = 40;
    std::uint32_t seed = 1;
    int store_every = 1;              // keep every n-th member's crossings (strand_weight n)
    bool orient_y_up = true;
    bool progress = true;             // coif::Progress on stderr
};

struct FitError {
    std::size_t strands = 0, assigned = 0;
    std::size_t points = 0, inside = 0;
    double rms_outside = 0;  // world units (the file's)
    double max_outside = 0;
    double inside_fraction() const { return points ? static_cast<double>(inside) / points : 0.0; }
    double assigned_share() const { return strands ? static_cast<double>(assigned) / strands : 0.0; }
};

inline constexpr int kStraySamplesU = 16;

struct StrayReport {
    double worst = 0;                  // the largest sample distance over every cluster, in cluster radii
    std::size_t worst_cluster = 0;     // where it is
    double worst_t = 0;
    double median_cluster = 0;         // the median over clusters of each cluster's largest
    std::size_t clusters = 0;          // clusters measured (those with member strands)
};

// The strays of `style` for `strands` in the style's coordinates with strand_cluster as in fitting_error.
StrayReport stray_distances(const HairStyle& style, const Strands& strands, const std::vector<int>& strand_cluster);

struct FitReport {
    FitError error;
    StrayReport stray;
    std::vector<int> strand_cluster;   // cluster of every input strand (−1: none)
    std::vector<char> strand_crosses;  // 1 where the strand crosses ≥ 1 sector plane of its cluster
    glm::dmat3 rotation{1.0};          // applied to the file's coordinates
    double seconds_clustering = 0, seconds_fitting = 0, seconds_error = 0;
    std::size_t requested_clusters = 0;
};

// Throws coif::Error::parameter(place, …) unless `width` is a usable Gaussian width λ for `strands`:
// finite, > 0 and within [kMinGaussianWidthOverExtent, 1] × the diagonal of their bounding box.
void check_gaussian_width(double width, const Strands& strands, const std::string& place);

// Fits a style to `strands` (file coordinates); fills `report` if given. Throws coif::Error for a
// layout.gaussian_width other than 0 that check_gaussian_width refuses.
HairStyle fit_style(const Strands& strands, const FitOptions& options, FitReport* report = nullptr);

// The median distance from each root to its nearest neighbouring root (the automatic λ above; 1 for fewer than two
// roots, 1e-3 when they coincide).
double median_root_spacing(const std::vector<glm::dvec3>& roots);

// The fitting error of `style` for `strands` already rotated into the style's coordinates, with
// strand_cluster[i] the cluster index of strand i (−1: none; its points count as outside, at no
// measured distance) and strand_crosses[i] whether it feeds its cluster's density (assigned).
FitError fitting_error(const HairStyle& style, const Strands& strands, const std::vector<int>& strand_cluster,
                       const std::vector<char>& strand_crosses, bool progress = false);

}  // namespace coif
