#pragma once
// Constraint functions of the PBD angle bending model (CN104268305A) and the distance (stretch)
// constraint, as free functions in the style of Jan Bender's PositionBasedDynamics: each takes
// positions and inverse masses and moves the positions in place (the projections return the
// multiplier's increment); nothing here owns state.
//
// Angle constraint on the seed's chain [v_best, v_k, v_i] with p1 = v_best, p2 = v_k, p3 = v_i
// (the vertex): theta = the angle between the edges p1 - p3 and p2 - p3, C = theta - theta0.
// theta is measured robustly (docs/pbd-model.md, "Reconstructed formulas"):
//  - unsigned, theta = atan2(|a x b|, a . b) in [0, pi], for 3D meshes; at an exactly straight
//    or folded chain the gradient has no direction and the projection is skipped (no NaN);
//  - signed about a fixed axis (planar meshes), theta = atan2(axis . (a x b), a . b), and
//    C = wrap(theta - theta0) into (-pi, pi]: smooth through the straight (180 degree) state.
// C is evaluated as atan2(sin(theta - theta0), cos(theta - theta0)) from the stored cos/sin of
// theta0, one atan2 per projection.
#include <pbd/particles.h>

namespace pbd {

/// Seed chain [v_best, v_k, v_i]; `rest_cos`, `rest_sin` of the rest angle theta0.
struct AngleConstraint {
  int best, k, i;
  double rest_cos, rest_sin;
  double compliance;  ///< XPBD compliance [1/(N m)] (rad^2 per J); 0 = rigid
};

struct DistanceConstraint {
  int a, b;
  double rest;        ///< rest length [m]
  double compliance;  ///< XPBD compliance [m/N]; 0 = inextensible
};

/// Value and gradients of an angle constraint. `valid` is false where the gradient has no
/// direction (unsigned form at a straight or folded chain, or a zero-length edge).
struct AngleGradient {
  double C = 0;       ///< theta - theta0, wrapped into (-pi, pi]
  Vec3 g1, g2, g3;    ///< dC/dp1, dC/dp2, dC/dp3 (g3 = -g1 - g2)
  bool valid = false;
};

/// Angle between p1 - p3 and p2 - p3 in [0, pi] (atan2 form, exact at 0 and pi).
double angle(const Vec3& p1, const Vec3& p2, const Vec3& p3);
/// Signed angle from p1 - p3 to p2 - p3 about `axis` (unit), in (-pi, pi].
double signed_angle(const Vec3& p1, const Vec3& p2, const Vec3& p3, const Vec3& axis);

/// C and its gradient; `axis` null for the unsigned form, else the unit axis of the signed form.
AngleGradient angle_constraint_gradient(const Vec3& p1, const Vec3& p2, const Vec3& p3, double theta0,
                                        const Vec3* axis);

/// One XPBD projection of an angle constraint, in place. `alpha_tilde` = compliance / h^2;
/// `lambda` is the constraint's accumulated multiplier (reset to 0 every substep). With
/// alpha_tilde = 0 this is the plain PBD projection with stiffness 1. Returns dlambda (0 when skipped).
double project_angle(Vec3& p1, Vec3& p2, Vec3& p3, double w1, double w2, double w3, double rest_cos,
                     double rest_sin, double alpha_tilde, double& lambda, const Vec3* axis);

/// One XPBD projection of a distance constraint, in place; returns dlambda.
double project_distance(Vec3& pa, Vec3& pb, double wa, double wb, double rest, double alpha_tilde, double& lambda);

}  // namespace pbd
