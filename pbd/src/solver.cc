// XPBD time stepping of a Model: substeps, Gauss-Seidel sweeps by colour, residuals, and the
// substep rule of docs/pbd-model.md.
#include <pbd/solver.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

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

namespace {
int thread_id() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// Thread t's share [lo, hi) of the range [b, e) split into `threads` contiguous parts.
std::pair<long, long> share(long b, long e, int t, int threads) {
  return {b + (e - b) * t / threads, b + (e - b) * (t + 1) / threads};
}
}  // namespace

void Solver::substep(double h, const StepSettings& s) {
  const int threads = std::max(1, s.threads);
  if (threads > 1 && (owned_threads_ != threads || owned_.size() != model_.particles.size())) own_particles(threads);
  if (threads > claim_threads_) {
    claims_.reset(new Claim[2 * std::size_t(threads)]);
    claim_threads_ = threads;
  }
  const int iterations = std::max(1, s.iterations);
  // One parallel region for the whole substep (prediction, sweeps, velocities): threads are woken
  // once, and the only waits are the barriers between colours.
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    // The threads actually given (fewer than asked when OpenMP refuses more; 1 without OpenMP).
    int team = 1;
#ifdef _OPENMP
    team = omp_get_num_threads();
#endif
    const int t = thread_id();
    predict(h, s, t, team);
    if (team > 1) arm(0, t, team);
#pragma omp barrier
    for (int it = 0; it < iterations; ++it) project(h, it, iterations, t, team);
    update_velocities(h, s, t, team);
  }
}

void Solver::own_particles(int threads) {
  // Each particle goes to the thread that projects most of its constraints (the first such thread
  // on a tie), so that the prediction and velocity passes touch the particles that thread's core
  // already holds; a particle in no constraint goes by its index.
  const std::size_t n = model_.particles.size();
  std::vector<int> count(n * std::size_t(threads), 0);
  auto tally = [&](const Colouring& colouring, auto nodes) {
    for (std::size_t col = 0; col < colouring.colours(); ++col)
      for (int t = 0; t < threads; ++t) {
        const auto [lo, hi] = share(long(colouring.colour_begin[col]), long(colouring.colour_begin[col + 1]), t, threads);
        for (long k = lo; k < hi; ++k)
          for (std::size_t c = colouring.block_begin[k]; c < colouring.block_begin[k + 1]; ++c)
            for (int p : nodes(c)) ++count[std::size_t(p) * threads + t];
      }
  };
  const auto& D = model_.distances;
  const auto& A = model_.angles;
  tally(model_.distance_colouring, [&](std::size_t c) { return std::array<int, 2>{D[c].a, D[c].b}; });
  tally(model_.angle_colouring, [&](std::size_t c) { return std::array<int, 3>{A[c].best, A[c].k, A[c].i}; });
  std::vector<std::vector<int>> lists(threads);
  for (std::size_t p = 0; p < n; ++p) {
    const int* c = &count[p * threads];
    int best = int(std::max_element(c, c + threads) - c);
    if (c[best] == 0) best = int(p * threads / n);
    lists[best].push_back(int(p));
  }
  owned_.clear();
  owned_begin_.assign(1, 0);
  for (const auto& l : lists) {
    owned_.insert(owned_.end(), l.begin(), l.end());
    owned_begin_.push_back(owned_.size());
  }
  owned_threads_ = threads;
}

namespace {
/// Calls f(i) for every particle of thread t: all of them on one thread, else the thread's own
/// (Solver::own_particles), or an even split of the indices when the team is not the one they were
/// made for.
template <class F>
void for_own_particles(std::size_t n, const std::vector<int>& owned, const std::vector<std::size_t>& owned_begin,
                       int owned_threads, int t, int team, F f) {
  if (team == 1) {
    for (std::size_t i = 0; i < n; ++i) f(i);
  } else if (team == owned_threads) {
    for (std::size_t k = owned_begin[t]; k < owned_begin[t + 1]; ++k) f(std::size_t(owned[k]));
  } else {
    const auto [lo, hi] = share(0, long(n), t, team);
    for (long i = lo; i < hi; ++i) f(std::size_t(i));
  }
}
}  // namespace

void Solver::predict(double h, const StepSettings& s, int t, int team) {
  auto& P = model_.particles;
  // Prediction (seed step 3, gravity as an acceleration).
  for_own_particles(P.size(), owned_, owned_begin_, owned_threads_, t, team, [&](std::size_t i) {
    P.x_prev[i] = P.x[i];
    if (P.w[i] == 0) {
      P.v[i].setZero();
      return;
    }
    P.v[i] += h * (s.gravity + P.w[i] * s.node_force);
    P.x[i] += h * P.v[i];
  });
}

void Solver::update_velocities(double h, const StepSettings& s, int t, int team) {
  auto& P = model_.particles;
  const double keep = std::exp(-s.damping * h);
  // Velocity from the position change, then damping.
  for_own_particles(P.size(), owned_, owned_begin_, owned_threads_, t, team, [&](std::size_t i) {
    if (P.w[i] != 0) P.v[i] = (P.x[i] - P.x_prev[i]) * (keep / h);
  });
}

namespace {
constexpr std::uint64_t pack(long front, long back) { return std::uint64_t(front) | std::uint64_t(back) << 32; }
}  // namespace

// A colour's blocks are split among the threads by share(): contiguous and in geometric order, so
// each thread gets the same region of the body in every colour, sweep and step, and its particles
// stay in its core's cache (a dynamic schedule moved them between the cores at every colour: 2
// threads were 1.3-1.5x faster than 1). Each thread's share is a claim [front, back): the thread
// takes its blocks from the front and, when done, the other threads' last blocks from their backs,
// so a thread that the system deschedules for a while holds up the colour by at most a block.
// Phase g (colour g % colours of a sweep) uses the claims of parity g % 2: a thread arms its claim
// for phase g + 1 before the barrier that ends phase g, while the others may still be taking
// from phase g's.
void Solver::arm(long g, int t, int team) {
  const Colouring& dc = model_.distance_colouring;
  const Colouring& ac = model_.angle_colouring;
  const long colours = long(dc.colours() + ac.colours());
  if (colours == 0) return;
  const long q = g % colours;
  const Colouring& C = q < long(dc.colours()) ? dc : ac;
  const long col = q < long(dc.colours()) ? q : q - long(dc.colours());
  const auto [lo, hi] = share(long(C.colour_begin[col]), long(C.colour_begin[col + 1]), t, team);
  claims_[std::size_t(g % 2) * team + t].range.store(pack(lo, hi), std::memory_order_release);
}

long Solver::take(long g, int owner, int team, bool from_front) {
  auto& range = claims_[std::size_t(g % 2) * team + owner].range;
  std::uint64_t r = range.load(std::memory_order_acquire);
  for (;;) {
    const long front = long(r & 0xffffffffu), back = long(r >> 32);
    if (front >= back) return -1;
    const std::uint64_t next = from_front ? pack(front + 1, back) : pack(front, back - 1);
    if (range.compare_exchange_weak(r, next, std::memory_order_acq_rel, std::memory_order_acquire))
      return from_front ? front : back - 1;
  }
}

void Solver::project(double h, int it, int iterations, int t, int team) {
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
  const bool first = it == 0, last = it + 1 == iterations;
  // The XPBD multipliers start each substep at 0 and live only through its sweeps: the first sweep
  // does not read them (a local 0 instead) and the last does not store them, so with one iteration
  // they cost no memory traffic at all (the same arithmetic as reading a stored 0).
  auto distances = [&](long k) {
    for (long c = long(dc.block_begin[k]); c < long(dc.block_begin[k + 1]); ++c) {
      const auto& d = D[c];
      double l = first ? 0.0 : ld[c];
      project_distance(x[d.a], x[d.b], w[d.a], w[d.b], d.rest, d.compliance * inv_h2, l);
      if (!last) ld[c] = l;
    }
  };
  auto bends = [&](long k) {
    for (long c = long(ac.block_begin[k]); c < long(ac.block_begin[k + 1]); ++c) {
      const auto& a = A[c];
      double l = first ? 0.0 : la[c];
      project_angle(x[a.best], x[a.k], x[a.i], w[a.best], w[a.k], w[a.i], a.rest_cos, a.rest_sin,
                    a.compliance * inv_h2, l, axis);
      if (!last) la[c] = l;
    }
  };
  // The arrays are in colour-major block order: one thread goes through them in order, several
  // split each colour's blocks (see arm()), and as a colour's constraints share no node the results
  // do not depend on the thread count nor on which thread projects which block.
  const long colours = long(dc.colours() + ac.colours());
  auto colour = [&](const Colouring& C, long col, long g, auto blocks) {
    if (team == 1) {
      for (long k = long(C.colour_begin[col]); k < long(C.colour_begin[col + 1]); ++k) blocks(k);
      return;
    }
    for (long k; (k = take(g, t, team, true)) >= 0;) blocks(k);
    for (int u = 1; u < team; ++u)
      for (long k; (k = take(g, (t + u) % team, team, false)) >= 0;) blocks(k);
    if (!(last && g % colours == colours - 1)) arm(g + 1, t, team);
#pragma omp barrier
  };
  const long g0 = long(it) * colours;
  for (long col = 0; col < long(dc.colours()); ++col) colour(dc, col, g0 + col, distances);
  for (long col = 0; col < long(ac.colours()); ++col) colour(ac, col, g0 + long(dc.colours()) + col, bends);
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
