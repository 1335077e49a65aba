#pragma once
// Calibration of the agent transfer coefficients against FEM (docs/calibration.md):
// bounded derivative-free minimisation (NLopt BOBYQA) from several seeded starts, run in
// parallel, of a weighted sum of relative errors of the agent fields against a reference.
#include <compare/reference.h>

#include <agent_study.h>  // a calibration case is an agent study

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace compare {

/// The coefficients a calibration can fit: the first agent::kFittedCount rows of
/// agent::kCoefficients, in that order (the seed's rule sets', then the directional one's).
constexpr std::size_t kCoefficientCount = agent::kFittedCount;
using CoefficientValues = std::array<double, kCoefficientCount>;

struct Parameter {
  std::string name;
  bool free = false;
  double start = 0, lo = 0, hi = 1;
};

/// The fields a calibration can weight: every row of compare::kFields, in its order.
constexpr std::size_t kFieldCount = std::size(kFields);
using FieldValues = std::array<double, kFieldCount>;

/// The default weights: sigma_y and the displacement 1, every other field 0 (the seed's fit).
constexpr FieldValues default_field_weights() {
  FieldValues w{};
  w[field_index("sigma_y")] = 1.0;
  w[field_index("displacement")] = 1.0;
  return w;
}

/// What the objective measures: sum over cases of weight * sum over the fields f of compare::kFields
/// compared in the case's dimension of w_f e(f)^2, e = ||agent - reference||_2 / ||reference||_2
/// over the body (every agent, every node) or over the sample lines.
struct ObjectiveWeights {
  FieldValues field = default_field_weights();  ///< per row of kFields
  bool lines = false;
  std::vector<double> depths{0.25, 0.5, 0.75};  ///< the lines across each load, when `lines`
  bool far = false;              ///< over the far field (docs/compare.md) instead of the body
  double far_distance = 0;       ///< far: what is closer to a loaded face is left out [m]; 0: 5 agent sizes
  /// The load-balance constraint (on by default): a point where a case's equilibrium deviation
  /// |rigid reaction - applied| / applied exceeds `equilibrium_ceiling[case]` is refused (objective 1e30).
  bool keep_load = true;
  /// Per case: the start's deviation + kLoadTolerance; set by calibrate().
  std::vector<double> equilibrium_ceiling;
  /// Coefficients (agent::kCoefficients) that are not fitted and come from each case's own [agent].
  std::array<bool, kCoefficientCount> held_from_case{};
};

struct CalibrationCase {
  std::string name;
  agent_study::AgentStudy study;
  GridFields reference;
  /// The reference's level as summary.json's `reference` gives it (level_json: for the converging
  /// 3D default its convergence), and Reference::limits_judgement() (empty where it converged).
  nlohmann::json reference_level;
  std::string reference_limits;
  double weight = 1.0;
};

struct CalibrationOptions {
  agent::RuleSet rules = agent::RuleSet::Conserving;
  std::array<Parameter, kCoefficientCount> parameters;  ///< in agent::kCoefficients order
  ObjectiveWeights weights;
  int starts = 8;               ///< the given start, then random points in the bounds
  std::uint64_t seed = 1;
  int max_evaluations = 400;    ///< per start
  double tolerance = 1e-6;      ///< relative change of the objective that ends a start
  int threads = 0;              ///< 0: every core
};

/// The load balance a fit may lose with keep_load (a share of the applied load): rounding only.
constexpr double kLoadTolerance = 1e-6;

struct Score {
  double objective = 0;
  /// Per row of kFields, the case's error e (0 for a field not compared in its dimension).
  FieldValues error{};
  double field(std::string_view name) const { return error[field_index(name)]; }
  double reaction_share = 0;  ///< rigid reaction / applied: the load the agents carry to a rigid face
  double equilibrium_dev = 0; ///< |rigid reaction - applied| / applied
  double reach = 0;           ///< share of agents the load reaches
  bool load_refused = false;  ///< over the case's equilibrium ceiling (keep_load)
};

/// Which cases this process scores: case i where i % size == rank, the rest by the other ranks
/// (every rank holds every case), each case on one of `threads` threads. The default, one rank and
/// one thread, scores every case here, one after the other.
struct CaseShare {
  int rank = 0, size = 1;
  int threads = 1;
};

/// The objective for one set of coefficients; `per_case` receives each case's errors. Under a share
/// of several ranks (a collective call: every rank makes it) each rank scores its cases and the
/// scores are summed over the ranks, then added in case order: the same total, bit for bit, as one
/// rank's, for any number of threads.
double objective(const std::vector<CalibrationCase>& cases, const agent::Coefficients& k, agent::RuleSet rules,
                 const ObjectiveWeights& w, std::vector<Score>* per_case = nullptr, CaseShare share = {});

struct Sensitivity {
  std::string name;
  double objective_minus, objective_plus;  ///< objective at the optimum -/+ 10 % of the range
  double curvature;                        ///< (J(-) - 2 J* + J(+)) / J*, dimensionless
  bool pinned;                             ///< the data pin it down (curvature > 1 %)
};

/// A held-out case ([[calibrate.held_out]]): scored with the start and the fitted coefficients, never fitted.
struct HeldOutScore {
  std::string name;
  int dim = 2;
  Score before, after;
};

struct CalibrationResult {
  agent::Coefficients start, best;
  double objective_start = 0, objective_best = 0;
  std::vector<Score> before, after;    ///< per case
  std::vector<double> start_objectives;  ///< best objective reached from each start
  std::vector<Sensitivity> sensitivity;  ///< per free coefficient
  long evaluations = 0;
  std::vector<HeldOutScore> held_out;    ///< per held-out case (run_calibration fills it)
};

/// Fits the free coefficients. Reproducible: the starts depend on `seed` only, and each start
/// runs the same sequence of evaluations whatever the thread count or the number of MPI ranks.
/// Under MPI (a collective call) the ranks split every evaluation's cases (CaseShare) and run the
/// starts one after another, one thread each.
CalibrationResult calibrate(const std::vector<CalibrationCase>& cases, const CalibrationOptions& options,
                            std::ostream* progress = nullptr);

/// Coefficients from a parameter vector (agent::kCoefficients order; the library's defaults for the
/// rest): poisson_decay is left to follow alpha2, the directional `directions` at its default.
agent::Coefficients coefficients_from(const CoefficientValues& values);

/// A case's coefficients: the fitted ones, with those `held` (and poisson_decay, directions,
/// gamma_relative) taken from the case's `own`; the threshold (agent::Threshold) is the case's own
/// when gamma is held, else the fitted point's (coefficients_from sets gamma: absolute).
agent::Coefficients for_case(const agent::Coefficients& fitted, const agent::Coefficients& own,
                             const std::array<bool, kCoefficientCount>& held);

}  // namespace compare
