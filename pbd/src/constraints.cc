// The PBD constraint functions: angle (the seed's, robust atan2 form) and distance projections.
#include <pbd/constraints.h>

#include <cmath>

namespace pbd {

namespace {
constexpr double kTinySquaredLength = 1e-300;
/// Below this |sin theta| the unsigned form has no gradient direction.
constexpr double kMinSin = 1e-12;
/// atan2(y, x), fast where the angle is small (|y| < 0.1 x: the deviation from the rest angle in
/// almost every projection): the Taylor series of atan(t) to t^15, whose truncation error is below
/// t^17 / 17 < 6e-18 |t|; elsewhere std::atan2.
inline double small_atan2(double y, double x) {
  if (x > 0 && std::abs(y) < 0.1 * x) {
    const double t = y / x, t2 = t * t;
    double p = -1.0 / 15;
    p = p * t2 + 1.0 / 13;
    p = p * t2 - 1.0 / 11;
    p = p * t2 + 1.0 / 9;
    p = p * t2 - 1.0 / 7;
    p = p * t2 + 1.0 / 5;
    p = p * t2 - 1.0 / 3;
    return t + t * t2 * p;
  }
  return std::atan2(y, x);
}

/// The angle at p3 between the edges to p1 and p2: unit edges ua, ub, their inverse lengths, the
/// cosine c, and the sine s about the rotation axis n (the fixed axis: signed; else unsigned,
/// s = |ua x ub|, n = ua x ub / s, left zero below kMinSin where it has no direction).
struct AngleFrame {
  Vec3 ua, ub, n;
  double inv_la = 0, inv_lb = 0, c = 0, s = 0;
};

/// false where an edge is degenerate (no frame).
inline bool angle_frame(const Vec3& p1, const Vec3& p2, const Vec3& p3, const Vec3* axis, AngleFrame& f) {
  const Vec3 a = p1 - p3, b = p2 - p3;
  const double la2 = a.squaredNorm(), lb2 = b.squaredNorm();
  if (!(la2 > kTinySquaredLength) || !(lb2 > kTinySquaredLength)) return false;
  f.inv_la = 1.0 / std::sqrt(la2);
  f.inv_lb = 1.0 / std::sqrt(lb2);
  f.ua = a * f.inv_la;
  f.ub = b * f.inv_lb;
  const Vec3 cr = f.ua.cross(f.ub);
  f.c = f.ua.dot(f.ub);
  if (axis) {
    f.n = *axis;
    f.s = f.n.dot(cr);
  } else {
    f.s = cr.norm();
    f.n = f.s < kMinSin ? Vec3::Zero() : Vec3(cr * (1.0 / f.s));
  }
  return true;
}
}  // namespace

double angle(const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const Vec3 a = p1 - p3, b = p2 - p3;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

double signed_angle(const Vec3& p1, const Vec3& p2, const Vec3& p3, const Vec3& axis) {
  const Vec3 a = p1 - p3, b = p2 - p3;
  return std::atan2(axis.dot(a.cross(b)), a.dot(b));
}

AngleGradient angle_constraint_gradient(const Vec3& p1, const Vec3& p2, const Vec3& p3, double theta0,
                                        const Vec3* axis) {
  AngleGradient g;
  AngleFrame f;
  if (!angle_frame(p1, p2, p3, axis, f)) return g;
  if (!axis && f.s < kMinSin) {
    g.C = std::atan2(f.s, f.c) - theta0;
    return g;
  }
  const double rc = std::cos(theta0), rs = std::sin(theta0);
  g.C = std::atan2(f.s * rc - f.c * rs, f.c * rc + f.s * rs);
  g.g1 = -f.n.cross(f.ua) * f.inv_la;
  g.g2 = f.n.cross(f.ub) * f.inv_lb;
  g.g3 = -g.g1 - g.g2;
  g.valid = true;
  return g;
}

double project_angle(Vec3& p1, Vec3& p2, Vec3& p3, double w1, double w2, double w3, double rest_cos,
                     double rest_sin, double alpha_tilde, double& lambda, const Vec3* axis) {
  AngleFrame f;
  if (!angle_frame(p1, p2, p3, axis, f) || (!axis && f.s < kMinSin)) return 0;
  const Vec3 &ua = f.ua, &ub = f.ub, &n = f.n;
  const double inv_la = f.inv_la, inv_lb = f.inv_lb, c = f.c, s = f.s;
  // Gradients g1 = -(n x ua) / la, g2 = (n x ub) / lb with n the unit rotation axis (cr / |cr|
  // unsigned, the fixed axis signed); n is perpendicular to ua and ub, so |g1|^2 = 1/la^2,
  // |g2|^2 = 1/lb^2 and g1 . g2 = -c / (la lb): the denominator needs no gradient products.
  const double C = small_atan2(s * rest_cos - c * rest_sin, c * rest_cos + s * rest_sin);
  const double ia2 = inv_la * inv_la, ib2 = inv_lb * inv_lb;
  const double den = (w1 + w3) * ia2 + (w2 + w3) * ib2 - 2 * w3 * c * inv_la * inv_lb + alpha_tilde;
  if (!(den > 0)) return 0;
  const double dl = (-C - alpha_tilde * lambda) / den;
  lambda += dl;
  const Vec3 g1 = -n.cross(ua) * inv_la;
  const Vec3 g2 = n.cross(ub) * inv_lb;
  p1 += (w1 * dl) * g1;
  p2 += (w2 * dl) * g2;
  p3 -= (w3 * dl) * (g1 + g2);
  return dl;
}

double project_distance(Vec3& pa, Vec3& pb, double wa, double wb, double rest, double alpha_tilde, double& lambda) {
  const Vec3 d = pa - pb;
  const double l2 = d.squaredNorm();
  if (!(l2 > kTinySquaredLength)) return 0;
  const double l = std::sqrt(l2);
  const Vec3 n = d * (1.0 / l);
  const double den = wa + wb + alpha_tilde;
  if (!(den > 0)) return 0;
  const double dl = (-(l - rest) - alpha_tilde * lambda) / den;
  lambda += dl;
  pa += (wa * dl) * n;
  pb -= (wb * dl) * n;
  return dl;
}

}  // namespace pbd
