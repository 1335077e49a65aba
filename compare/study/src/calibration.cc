// Calibration of the agent transfer coefficients: the objective, BOBYQA from seeded starts in parallel, sensitivity.
#include <compare/calibration.h>

#include <fem_reference/mpi.h>
#include <compare/metrics.h>

#include <nlopt.hpp>

#include <algorithm>
#include <atomic>
#include <functional>
#include <cmath>
#include <exception>
#include <mutex>
#include <optional>
#include <ostream>
#include <random>
#include <string>
#include <thread>

namespace compare {

agent::Coefficients coefficients_from(const CoefficientValues& v) {
  agent::Coefficients k;
  for (std::size_t i = 0; i < kCoefficientCount; ++i) agent::kCoefficients[i].set(k, v[i]);
  return k;
}

agent::Coefficients for_case(const agent::Coefficients& fitted, const agent::Coefficients& own,
                             const std::array<bool, kCoefficientCount>& held) {
  agent::Coefficients k = fitted;
  for (std::size_t i = 0; i < kCoefficientCount; ++i)
    if (held[i]) agent::kCoefficients[i].set(k, agent::kCoefficients[i].get(own));
  k.poisson_decay = own.poisson_decay;  // a case's own value is held; unset, it follows alpha2
  // The threshold is the case's own when gamma is held from it; else the fitted point's (a
  // calibration that gives gamma, free or as a start, sets it: the absolute threshold acts).
  // gamma_relative is not fitted: always the case's own.
  static const std::size_t gamma = std::size_t(agent::find_coefficient("gamma") - agent::kCoefficients.data());
  if (held[gamma]) k.threshold = own.threshold;
  k.gamma_relative = own.gamma_relative;
  k.directional.directions = own.directional.directions;  // an integer: not fitted
  return k;
}

namespace {

double l2_error(const std::vector<double>& model, const std::vector<double>& reference) {
  return relative_errors(model, reference).rel_l2;
}

Score score_case(const CalibrationCase& c, const GridFields& agent, const ObjectiveWeights& w) {
  const auto& grid = c.study.mesh.grid;
  const int dim = grid.dim;
  // Per row of kFields the agent's and the reference's values over the scope.
  std::array<std::vector<double>, kFieldCount> a, r;
  auto add_stress = [&](const auto& value_of) {  // value_of(fields, slot)
    for (std::size_t k = 0; k < kFieldCount; ++k)
      if (kFields[k].in(dim) && !kFields[k].per_node) {
        a[k].push_back(value_of(agent, kFields[k].slot));
        r[k].push_back(value_of(c.reference, kFields[k].slot));
      }
  };
  auto add_nodes = [&](const auto& value_of) {  // value_of(fields, component)
    for (std::size_t k = 0; k < kFieldCount; ++k)
      if (kFields[k].in(dim) && kFields[k].per_node)
        for (int comp = 0; comp < dim; ++comp)
          if (kFields[k].slot < 0 || kFields[k].slot == comp) {  // -1: the displacement vector
            a[k].push_back(value_of(agent, comp));
            r[k].push_back(value_of(c.reference, comp));
          }
  };
  if (w.far || !w.lines) {  // the body, or its far field (docs/compare.md): agents and their nodes only, air left out
    NearLoad near;
    if (w.far)
      near = near_load(c.study.mesh, c.study.setup.loads, w.far_distance > 0 ? w.far_distance : 5 * grid.size[0]);
    for (std::size_t cell : agent_ids(grid))  // box order on any layout: the same sums
      if (!(w.far && near.cells[cell]))
        add_stress([&](const GridFields& f, int slot) { return f.stress[kStressSlots * cell + slot]; });
    for (std::size_t n : body_node_ids(grid))
      if (!(w.far && near.nodes[n])) add_nodes([&](const GridFields& f, int comp) { return f.u[n * dim + comp]; });
  } else {
    for (const auto& line : load_lines(grid, load_frames(c.study.mesh, c.study.setup.loads), w.depths))
      for (int i : line.body_samples) {  // a line stops at air
        const Eigen::Vector3d p = line.point(i);
        add_stress([&](const GridFields& f, int slot) { return sample_cells(grid, f.stress, kStressSlots, slot, p); });
        add_nodes([&](const GridFields& f, int comp) { return sample_nodes(grid, f.u, dim, comp, p); });
      }
  }
  // Squared errors: smooth at the optimum, which BOBYQA's quadratic models need (a plain norm is
  // V-shaped there and stalls it). A field without weight is reported, not scored.
  Score s;
  for (std::size_t k = 0; k < kFieldCount; ++k) {
    if (!kFields[k].in(dim)) continue;
    s.error[k] = l2_error(a[k], r[k]);
    if (w.field[k] > 0) s.objective += w.field[k] * s.error[k] * s.error[k];
  }
  return s;
}

}  // namespace

namespace {

/// A score as numbers, for the sum over the ranks.
constexpr int kScoreSlots = 5 + int(kFieldCount);
void pack(const Score& s, double* out) {
  const double v[5] = {s.objective, s.reaction_share, s.equilibrium_dev, s.reach, s.load_refused ? 1.0 : 0.0};
  std::copy(v, v + 5, out);
  std::copy(s.error.begin(), s.error.end(), out + 5);
}
Score unpack(const double* v) {
  Score s;
  s.objective = v[0];
  s.reaction_share = v[1];
  s.equilibrium_dev = v[2];
  s.reach = v[3];
  s.load_refused = v[4] != 0;
  std::copy(v + 5, v + kScoreSlots, s.error.begin());
  return s;
}

}  // namespace

double objective(const std::vector<CalibrationCase>& cases, const agent::Coefficients& k, agent::RuleSet rules,
                 const ObjectiveWeights& w, std::vector<Score>* per_case, CaseShare share) {
  // Each case's score in its slots, zero where another rank scores it: the sum over the ranks adds
  // only zeros to a score, so it is exact. The threads write disjoint slots.
  std::vector<double> scores(cases.size() * kScoreSlots, 0.0);
  auto score = [&](std::size_t ci) {
    const auto& c = cases[ci];
    const auto kc = for_case(k, c.study.coefficients, w.held_from_case);
    // Readings 2 and 6 refuse a factor of 1 (their transfer would not end) and stop at a cap: such
    // a point is refused like one that loses load (objective 1e30), never scored on partial results.
    std::optional<agent_study::StudyModel> model;
    std::optional<agent_study::AgentState> solved;
    try {
      model.emplace(agent_study::transfer_model(c.study, kc, rules));
      solved = agent_study::evaluate(c.study, *model, 1.0);
    } catch (const std::invalid_argument&) {
    } catch (const agent_study::TransferDidNotEnd&) {
    }
    if (!solved) {
      Score s;
      s.load_refused = true;
      s.objective = 1e30;
      pack(s, &scores[ci * kScoreSlots]);
      return;
    }
    const auto& state = *solved;
    Score s = score_case(c, agent_on_grid(c.study.mesh.grid, state), w);
    const auto& d = state.diagnostics;
    s.reaction_share = d.applied > 0 ? d.rigid_reaction / d.applied : 0.0;
    s.reach = double(d.agents_generated) / double(c.study.mesh.cell_of_element.size());
    s.equilibrium_dev = d.applied > 0 ? std::abs(d.rigid_reaction - d.applied) / d.applied : 0.0;
    if (w.keep_load && ci < w.equilibrium_ceiling.size() && s.equilibrium_dev > w.equilibrium_ceiling[ci]) {
      s.load_refused = true;
      s.objective = 1e30;
    }
    if (!std::isfinite(s.objective)) s.objective = 1e30;  // e.g. an agent field where the reference is zero
    pack(s, &scores[ci * kScoreSlots]);
  };
  std::vector<std::size_t> mine;
  for (std::size_t ci = 0; ci < cases.size(); ++ci)
    if (int(ci % std::size_t(share.size)) == share.rank) mine.push_back(ci);
  const int threads = std::max(1, std::min(share.threads, int(mine.size())));
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> failed(static_cast<std::size_t>(threads));
  auto work = [&](int t) {
    try {
      for (std::size_t i; (i = next++) < mine.size();) score(mine[i]);
    } catch (...) {
      failed[std::size_t(t)] = std::current_exception();
      next = mine.size();  // the other threads stop after their case
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
  if (share.size > 1) fem_reference::mpi_sum(scores);
  double total = 0;
  if (per_case) per_case->clear();
  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    const Score s = unpack(&scores[ci * kScoreSlots]);
    total += cases[ci].weight * s.objective;
    if (per_case) per_case->push_back(s);
  }
  return total;
}

namespace {

/// The starts: the given point, then uniform random points in the bounds (seeded).
std::vector<std::vector<double>> starting_points(const CalibrationOptions& o, const std::vector<int>& free) {
  std::vector<std::vector<double>> starts;
  std::mt19937_64 rng(o.seed);
  for (int s = 0; s < o.starts; ++s) {
    std::vector<double> x;
    for (int i : free) {
      const auto& p = o.parameters[i];
      x.push_back(s == 0 ? p.start : std::uniform_real_distribution<double>(p.lo, p.hi)(rng));
    }
    starts.push_back(x);
  }
  return starts;
}

/// The best point one start reached, and how many evaluations it took.
struct StartFit {
  double best_f = INFINITY;
  std::vector<double> best_x;
  long evaluations = 0;
};

/// Minimises J over the free coefficients from `x` with BOBYQA in the bounds (10 % of each range
/// as the first step); keeps the best point evaluated.
void minimise(std::vector<double> x, const std::vector<int>& free, const CalibrationOptions& o,
              const std::function<double(const std::vector<double>&)>& J, StartFit& fit) {
  nlopt::opt opt(nlopt::LN_BOBYQA, unsigned(free.size()));
  std::vector<double> lo, hi;
  for (int i : free) {
    lo.push_back(o.parameters[i].lo);
    hi.push_back(o.parameters[i].hi);
  }
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_maxeval(o.max_evaluations);
  opt.set_ftol_rel(o.tolerance);
  std::vector<double> step;
  for (std::size_t j = 0; j < free.size(); ++j) step.push_back(0.1 * (hi[j] - lo[j]));
  opt.set_initial_step(step);
  struct Data {
    const std::function<double(const std::vector<double>&)>& f;
    StartFit& fit;
  } data{J, fit};
  opt.set_min_objective(
      [](const std::vector<double>& x, std::vector<double>&, void* raw) {
        auto* d = static_cast<Data*>(raw);
        const double f = d->f(x);
        ++d->fit.evaluations;
        if (f < d->fit.best_f) {
          d->fit.best_f = f;
          d->fit.best_x = x;
        }
        return f;
      },
      &data);
  double f = 0;
  try {
    opt.optimize(x, f);
  } catch (const nlopt::roundoff_limited&) {
  } catch (const nlopt::forced_stop&) {
  }
}

/// The objective 10 % of each free coefficient's range either side of the optimum `v`.
void add_sensitivity(const std::vector<int>& free, const CalibrationOptions& o, const CoefficientValues& v,
                     const std::function<double(const CoefficientValues&)>& J, CalibrationResult& result) {
  for (int i : free) {
    const auto& p = o.parameters[i];
    const double h = 0.1 * (p.hi - p.lo);
    auto at = [&](double value) {
      CoefficientValues w = v;
      w[i] = std::min(p.hi, std::max(p.lo, value));
      return J(w);
    };
    Sensitivity s;
    s.name = p.name;
    s.objective_minus = at(v[i] - h);
    s.objective_plus = at(v[i] + h);
    s.curvature = (s.objective_minus - 2 * result.objective_best + s.objective_plus) / std::max(result.objective_best, 1e-300);
    s.pinned = std::abs(s.curvature) > 0.01 ||
               std::min(s.objective_minus, s.objective_plus) > result.objective_best * 1.01;
    result.sensitivity.push_back(s);
    result.evaluations += 2;
  }
}

}  // namespace

CalibrationResult calibrate(const std::vector<CalibrationCase>& cases, const CalibrationOptions& options,
                            std::ostream* progress) {
  // The load balance at the start is what every fitted point must keep (keep_load).
  CalibrationOptions o = options;
  o.weights.equilibrium_ceiling.clear();
  std::vector<int> free;
  for (std::size_t i = 0; i < kCoefficientCount; ++i)
    if (o.parameters[i].free) free.push_back(int(i));
  CoefficientValues start_values{};
  for (std::size_t i = 0; i < kCoefficientCount; ++i) start_values[i] = o.parameters[i].start;

  auto full = [&](const std::vector<double>& x) {
    CoefficientValues v = start_values;
    for (std::size_t j = 0; j < free.size(); ++j) v[free[j]] = x[j];
    return v;
  };
  // Under MPI the ranks share every evaluation's cases; each start's evaluations are then
  // collective, in the same order on every rank, so the starts run one after another, one thread
  // each. On one rank the starts run on `threads` threads and each evaluation's cases on the cores
  // the starts leave (one start on two cores: its cases two at a time); the evaluations outside
  // the starts take every core.
  const int size = fem_reference::mpi_size();
  const int wanted = size > 1 ? 1 : o.threads > 0 ? o.threads : std::max(1, int(std::thread::hardware_concurrency()));
  const int threads = std::max(1, std::min<int>(wanted, o.starts));
  const CaseShare share{fem_reference::mpi_rank(), size, wanted};
  const CaseShare start_share{share.rank, size, std::max(1, wanted / threads)};
  auto J = [&](const CoefficientValues& v, const CaseShare& on) {
    return objective(cases, coefficients_from(v), o.rules, o.weights, nullptr, on);
  };
  const auto starts = starting_points(o, free);

  CalibrationResult result;
  result.start = coefficients_from(start_values);
  result.objective_start = objective(cases, result.start, o.rules, o.weights, &result.before, share);
  if (o.weights.keep_load)
    for (const auto& s : result.before) o.weights.equilibrium_ceiling.push_back(s.equilibrium_dev + kLoadTolerance);
  std::vector<StartFit> fits(starts.size());
  for (std::size_t s = 0; s < starts.size(); ++s) fits[s].best_x = starts[s];
  std::atomic<int> next{0}, done{0};
  std::mutex log_mutex;

  auto run_start = [&](int s) {
    if (free.empty()) {
      fits[s].best_f = J(full(starts[s]), start_share);
      fits[s].evaluations = 1;
      return;
    }
    minimise(starts[s], free, o, [&](const std::vector<double>& y) { return J(full(y), start_share); }, fits[s]);
    if (progress) {
      std::lock_guard<std::mutex> lock(log_mutex);
      *progress << "calibrate: start " << ++done << "/" << starts.size() << " (#" << s + 1 << "): objective "
                << fits[s].best_f << " after " << fits[s].evaluations << " evaluations\n"
                << std::flush;
    }
  };

  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (int s; (s = next++) < int(starts.size());) run_start(s);
    });
  for (auto& th : pool) th.join();

  // The best start (ties to the lowest index, so the thread count cannot change the answer).
  int best = 0;
  for (std::size_t s = 1; s < starts.size(); ++s)
    if (fits[s].best_f < fits[best].best_f) best = int(s);
  for (const auto& fit : fits) {
    result.start_objectives.push_back(fit.best_f);
    result.evaluations += fit.evaluations;
  }
  CoefficientValues v = full(fits[best].best_x);
  // Never worse than the start.
  if (!(fits[best].best_f <= result.objective_start)) v = start_values;
  result.best = coefficients_from(v);
  result.objective_best = objective(cases, result.best, o.rules, o.weights, &result.after, share);
  add_sensitivity(free, o, v, [&](const CoefficientValues& w) { return J(w, share); }, result);
  return result;
}

}  // namespace compare
