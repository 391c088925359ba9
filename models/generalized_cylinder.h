#pragma once
// The envelope of a hair cluster: a generalized cylinder swept by an ellipse along a 3D B-spline
// (004 §3.2, eqs. 1–2):  H = Modeling(T(t), A(t), B(t), θ(t)),  t ∈ [0, 1].
//
// Parameters
//   t  relative arc length along the trajectory T (0 at the root, 1 at the tip): |dP/dt| = length()
//      on the axis. The trajectory spline has its own parameter τ; τ(t) is tabulated (kArcTable
//      nodes, cubic Hermite between them) so that t is arc length to ~1e-10 of the length.
//      A(t), B(t), θ(t) are B-splines in t directly (not in τ).
//   v  ∈ [0, 1] relative radius (0 on the axis, 1 on the envelope).
//   u  ∈ [0, 2π) phase around the ellipse, measured from its A axis toward its B axis.
//
// Frame convention (written once, used everywhere):
//   tangent  T̂(t) = unit dT/dt, root → tip.
//   normal   n(t), binormal b(t) = T̂ × n: a rotation-minimizing (parallel-transport, "Bishop")
//            frame, computed by the double-reflection method (Wang, Jüttler, Zheng, Liu 2008,
//            "Computation of rotation minimizing frames", ACM TOG 27(1)) on kFrameTable uniform
//            steps of t, and by one more double reflection from the preceding node in between. It
//            does not spin about T̂: its twist rate (dn/dt · b) is zero up to the method's
//            fourth-order error.
//   n(0)     the component of +z normal to T̂(0), normalised; if |T̂(0)·z| > 0.9, that of +x
//            instead. For hair hanging along −y, n(0) = +z (toward the face) and b(0) = −x.
//   ellipse  axes e1 = cos θ n + sin θ b (half-length A) and e2 = −sin θ n + cos θ b (half-length B):
//            θ(t) turns the ellipse in the normal plane, and it is the only spin the ellipse has.
//   surface  P(t, v, u) = T(t) + v (A(t) cos u e1(t) + B(t) sin u e2(t)).
//   Note on 004 eq. 1: read literally, x = A v cos(θ+u), y = B v sin(θ+u) only shifts the phase of
//   u along a fixed ellipse (for A ≠ B it does not turn it). The paper calls θ the "self-twisting
//   phase", and the ellipse is fitted to principal axes, so coif turns the ellipse by θ; for A = B the
//   two readings are the same surface with the same u labelling.
//
// Outward surface normal: ∂P/∂u × ∂P/∂t (for v > 0): with b = T̂ × n, the cross product in the
// other order points inward.
//
// Units: whatever the style uses (coif scenes: centimetres, y up). θ is in radians.
#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "models/bspline.h"

namespace coif {

struct Frame {
    glm::dvec3 tangent{0, 0, 1}, normal{1, 0, 0}, binormal{0, 1, 0};  // binormal = tangent × normal
};

// P(t, v, u) and its partial derivatives.
struct SurfacePoint {
    glm::dvec3 position{0}, d_dt{0}, d_dv{0}, d_du{0};
    // Outward unit normal of the surface v = const (∂P/∂u × ∂P/∂t normalised); at v = 0 the radial
    // direction of u is returned.
    glm::dvec3 normal() const;
};

// Where a point lies relative to a cylinder: the normal plane through it (t), its polar ellipse
// coordinates in that plane (v, u), its in-plane coordinates along e1, e2, and how far it lies beyond
// the root or tip plane along the tangent (axial; 0 when t is inside (0, 1)).
struct CylinderCoordinates {
    double t = 0, v = 0, u = 0;
    glm::dvec2 in_plane{0};
    double axial = 0;
    bool inside() const { return axial == 0.0 && v <= 1.0; }
};

class GeneralizedCylinder {
public:
    static constexpr int kArcTable = 1024;   // τ(t) Hermite nodes: arc-length error ~ (1/1024)^4 relative
    static constexpr int kFrameTable = 512;  // double-reflection steps along t (fourth-order accurate)

    GeneralizedCylinder() = default;
    // Throws std::invalid_argument if the trajectory is empty or has zero length, or a profile is empty.
    GeneralizedCylinder(Spline3 trajectory, Spline1 a, Spline1 b, Spline1 theta);

    const Spline3& trajectory() const { return trajectory_; }
    const Spline1& a_spline() const { return a_; }
    const Spline1& b_spline() const { return b_; }
    const Spline1& theta_spline() const { return theta_; }

    double length() const { return length_; }
    double tau(double t) const;  // spline parameter of relative arc length t

    glm::dvec3 position(double t) const;
    glm::dvec3 tangent(double t) const;
    Frame frame(double t) const;
    double a(double t) const { return a_(t); }
    double b(double t) const { return b_(t); }
    double theta(double t) const { return theta_(t); }
    // The ellipse axes e1 (length A) and e2 (length B) at t.
    std::array<glm::dvec3, 2> ellipse_axes(double t) const;

    glm::dvec3 point(double t, double v, double u) const { return surface(t, v, u).position; }
    SurfacePoint surface(double t, double v, double u) const;

    // The nearest normal plane to x (closest point on the axis, then Newton on (x − T(t))·T̂(t) = 0),
    // and x's coordinates in it. t is clamped to [0, 1]; beyond the ends `axial` is the distance.
    CylinderCoordinates locate(const glm::dvec3& x) const;
    // Euclidean distance from x to the solid envelope (0 inside), measured in x's normal plane
    // (point–ellipse distance) combined with the axial distance beyond an end.
    double distance_outside(const glm::dvec3& x) const;

private:
    glm::dvec3 unit_tangent_derivative(double t) const;  // dT̂/dt
    Frame frame_with_tangent(double t, const glm::dvec3& x, const glm::dvec3& tangent) const;

    Spline3 trajectory_;
    Spline1 a_, b_, theta_;
    double length_ = 0;
    std::vector<double> tau_of_t_, dtau_dt_;            // kArcTable + 1 nodes at t = k / kArcTable
    std::vector<glm::dvec3> node_position_;             // kFrameTable + 1 nodes
    std::vector<Frame> node_frame_;
};

// Distance from (y0, y1) to the ellipse x²/e0² + y²/e1² = 1 (Eberly, "Distance from a point to an
// ellipse", 2013: bisection on the Lagrange root; robust for every point, inside or outside).
double point_ellipse_distance(double e0, double e1, double y0, double y1);

}  // namespace coif
