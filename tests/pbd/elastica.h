#pragma once
// Reference solutions for a cantilever (clamped at s = 0, horizontal, free at s = L) under a dead
// distributed load q per unit length acting in -y:
//  - Euler-Bernoulli (small deflection): tip deflection q L^4 / (8 E I);
//  - the large-deflection elastica, by a shooting method: with theta(s) the tangent angle,
//    E I theta'' = q (L - s) cos(theta), theta(0) = 0, theta'(L) = 0 (moment-free tip);
//    x' = cos(theta), y' = sin(theta). The unknown theta'(0) is found by bisection on the
//    tip moment, each trial integrated with classical RK4.
#include <cmath>
#include <functional>

namespace pbd_test {

struct ElasticaTip {
  double x, y;        ///< tip position (clamp at the origin)
  double curvature0;  ///< theta'(0)
};

inline double euler_bernoulli_tip(double q, double L, double EI) { return q * L * L * L * L / (8 * EI); }

/// Integrates the elastica with curvature theta'(0) = k0; returns theta'(L) and the tip.
inline double elastica_shoot(double k0, double q, double L, double EI, int steps, double* xt = nullptr,
                             double* yt = nullptr) {
  // state: theta, kappa, x, y
  double st[4] = {0, k0, 0, 0};
  const double h = L / steps;
  auto f = [&](double s, const double* y, double* dy) {
    dy[0] = y[1];
    dy[1] = q * (L - s) * std::cos(y[0]) / EI;
    dy[2] = std::cos(y[0]);
    dy[3] = std::sin(y[0]);
  };
  double k1[4], k2[4], k3[4], k4[4], t[4];
  for (int i = 0; i < steps; ++i) {
    const double s = i * h;
    f(s, st, k1);
    for (int j = 0; j < 4; ++j) t[j] = st[j] + 0.5 * h * k1[j];
    f(s + 0.5 * h, t, k2);
    for (int j = 0; j < 4; ++j) t[j] = st[j] + 0.5 * h * k2[j];
    f(s + 0.5 * h, t, k3);
    for (int j = 0; j < 4; ++j) t[j] = st[j] + h * k3[j];
    f(s + h, t, k4);
    for (int j = 0; j < 4; ++j) st[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
  }
  if (xt) *xt = st[2];
  if (yt) *yt = st[3];
  return st[1];
}

/// Tip of the elastica; bisection on k0 in [-q L^2 / (2 E I), 0] (the small-deflection
/// curvature bounds the magnitude, since cos(theta) <= 1).
inline ElasticaTip elastica_tip(double q, double L, double EI, int steps = 4000) {
  double lo = -q * L * L / (2 * EI) * 1.0000001, hi = 0;
  // theta'(L) is increasing in k0 here: at k0 = lo it is <= 0, at k0 = 0 it is >= 0.
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (elastica_shoot(mid, q, L, EI, steps) < 0) lo = mid;
    else hi = mid;
  }
  ElasticaTip tip{};
  tip.curvature0 = 0.5 * (lo + hi);
  elastica_shoot(tip.curvature0, q, L, EI, steps, &tip.x, &tip.y);
  return tip;
}

}  // namespace pbd_test
