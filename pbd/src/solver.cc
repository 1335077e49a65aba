// XPBD time stepping of a Model: substeps, Gauss-Seidel sweeps by colour, residuals, and the
// substep rule of docs/pbd-model.md.
#include <pbd/solver.h>

#include <algorithm>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pbd {

Solver::Solver(Model& model)
    : model_(model), lambda_distance_(model.distances.size(), 0.0), lambda_angle_(model.angles.size(), 0.0) {}

bool Solver::parallel_available() {
#ifdef _OPENMP
  return true;
#else
  return false;
#endif
}

void Solver::step(const StepSettings& s) {
  const int substeps = std::max(1, s.substeps);
  const double h = s.dt / substeps;
  for (int k = 0; k < substeps; ++k) substep(h, s);
}

void Solver::substep(double h, const StepSettings& s) {
  const int threads = std::max(1, s.threads);
  // One parallel region for the whole substep (prediction, sweeps, velocities): threads are woken
  // once, and the only waits are the barriers between colours.
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    predict(h, s);
    const int iterations = std::max(1, s.iterations);
    for (int it = 0; it < iterations; ++it) project(h, it == 0, it + 1 == iterations);
    update_velocities(h, s);
  }
}

void Solver::predict(double h, const StepSettings& s) {
  auto& P = model_.particles;
  const long n = long(P.size());
  // Prediction (seed step 3, gravity as an acceleration).
#pragma omp for schedule(static)
  for (long i = 0; i < n; ++i) {
    P.x_prev[i] = P.x[i];
    if (P.w[i] == 0) {
      P.v[i].setZero();
      continue;
    }
    P.v[i] += h * (s.gravity + P.w[i] * s.node_force);
    P.x[i] += h * P.v[i];
  }
}

void Solver::update_velocities(double h, const StepSettings& s) {
  auto& P = model_.particles;
  const long n = long(P.size());
  const double keep = std::exp(-s.damping * h);
  // Velocity from the position change, then damping.
#pragma omp for schedule(static)
  for (long i = 0; i < n; ++i)
    if (P.w[i] != 0) P.v[i] = (P.x[i] - P.x_prev[i]) * (keep / h);
}

void Solver::project(double h, bool first, bool last) {
  auto& P = model_.particles;
  Vec3* x = P.x.data();
  const double* w = P.w.data();
  const double inv_h2 = 1.0 / (h * h);
  const Vec3* axis = model_.axis_ptr();
  const DistanceConstraint* D = model_.distances.data();
  const AngleConstraint* A = model_.angles.data();
  const Colouring& dc = model_.distance_colouring;
  const Colouring& ac = model_.angle_colouring;
  double* ld = lambda_distance_.data();
  double* la = lambda_angle_.data();
  // The XPBD multipliers start each substep at 0 and live only through its sweeps: the first sweep
  // does not read them (a local 0 instead) and the last does not store them, so with one iteration
  // they cost no memory traffic at all (the same arithmetic as reading a stored 0).
  auto distance = [&](long c) {
    const auto& d = D[c];
    double l = first ? 0.0 : ld[c];
    project_distance(x[d.a], x[d.b], w[d.a], w[d.b], d.rest, d.compliance * inv_h2, l);
    if (!last) ld[c] = l;
  };
  auto bend = [&](long c) {
    const auto& a = A[c];
    double l = first ? 0.0 : la[c];
    project_angle(x[a.best], x[a.k], x[a.i], w[a.best], w[a.k], w[a.i], a.rest_cos, a.rest_sin,
                  a.compliance * inv_h2, l, axis);
    if (!last) la[c] = l;
  };
  // The arrays are in colour-major block order: one thread goes through them in order, several
  // split each colour's blocks, and as a colour's constraints share no node the results do not
  // depend on the thread count. The split is static: a colour's blocks are in geometric order, so
  // each thread gets the same region of the body in every colour, sweep and step, and its
  // particles stay in its core's cache instead of moving between the cores at every colour.
  for (std::size_t col = 0; col < dc.colours(); ++col) {
    const long b = long(dc.colour_begin[col]), e = long(dc.colour_begin[col + 1]);
#pragma omp for schedule(static)
    for (long k = b; k < e; ++k)
      for (long c = long(dc.block_begin[k]); c < long(dc.block_begin[k + 1]); ++c) distance(c);
  }
  for (std::size_t col = 0; col < ac.colours(); ++col) {
    const long b = long(ac.colour_begin[col]), e = long(ac.colour_begin[col + 1]);
#pragma omp for schedule(static)
    for (long k = b; k < e; ++k)
      for (long c = long(ac.block_begin[k]); c < long(ac.block_begin[k + 1]); ++c) bend(c);
  }
}

Residuals Solver::residuals() const {
  Residuals r;
  const auto& x = model_.particles.x;
  for (const auto& d : model_.distances) {
    const double stretch = std::abs((x[d.a] - x[d.b]).norm() - d.rest) / d.rest;
    r.distance = std::max(r.distance, stretch);
    if (d.compliance == 0) r.inextensible_stretch = std::max(r.inextensible_stretch, stretch);
  }
  const Vec3* axis = model_.axis_ptr();
  for (const auto& a : model_.angles) {
    const double theta0 = std::atan2(a.rest_sin, a.rest_cos);
    const auto g = angle_constraint_gradient(x[a.best], x[a.k], x[a.i], theta0, axis);
    r.angle = std::max(r.angle, std::abs(g.C));
    if (a.compliance == 0) r.rigid_angle = std::max(r.rigid_angle, std::abs(g.C));
  }
  return r;
}

bool Residuals::exceeds_tolerance() const {
  // Written so that a NaN residual counts as exceeding.
  return !(inextensible_stretch <= kStretchTolerance) || !(rigid_angle <= kAngleTolerance);
}

int substeps_for_accuracy(const Model& model, double dt, double accuracy, int max_substeps) {
  const auto& P = model.particles;
  double h2 = INFINITY;  // the largest admissible substep, squared
  for (const auto& a : model.angles) {
    if (!(a.compliance > 0)) continue;
    const double w = std::max({P.w[a.best], P.w[a.k], P.w[a.i]});
    if (!(w > 0)) continue;
    const double l = std::min((P.x[a.best] - P.x[a.i]).norm(), (P.x[a.k] - P.x[a.i]).norm());
    h2 = std::min(h2, accuracy * l * l * a.compliance / (6 * w));
  }
  if (!std::isfinite(h2)) return 1;
  const double substeps = std::ceil(dt / std::sqrt(h2));
  if (!(substeps < max_substeps)) return max_substeps;  // also for a NaN
  return std::max(1, int(substeps));
}

}  // namespace pbd
