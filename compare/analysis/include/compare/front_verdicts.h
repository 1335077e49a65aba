#pragma once
// The cost-accuracy front's verdicts (docs/front.md): given each model's points (seconds, errors),
// which point is dominated by which, and how much cheaper the fast model is than the FEM of equal
// error, read log-log along the FEM's ladder as DiffEqDevTools' work-precision diagrams are read.
// Plain functions of numbers: no files, no solves.
//
//   std::vector<compare::FrontPoint> points = ...;   // agents and FEM, errors per metric
//   auto verdicts = compare::front_verdicts(points, {"far.sigma_y.rel_l2"}, {{"far.sigma_y.rel_l2", 0.006}});
//   // verdicts[i].speedup: FEM time at the agent's error / the agent's time (null outside the ladder)
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace compare {

/// One model run on the front: what it is, what it cost (min and median of its warm runs) and its
/// errors against the reference (metric name as in summary.json -> value).
struct FrontPoint {
  std::string model;     ///< "agent", "pbd" (the fast models) or "fem"
  std::string label;     ///< unique, e.g. "agent directional 2 mm", "pbd 1000 x 4", "fem Q1 4 mm"
  double size = 0;       ///< agent edge or FEM mesh size [m] (PBD: its segment length)
  int degree = 0;        ///< FEM polynomial degree (0 for agents)
  std::string rule_set;  ///< agents' rule set (empty for FEM)
  std::map<std::string, double> work;  ///< machine-independent counts (agents, packet_moves, dofs, ...)
  double seconds_min = 0, seconds_median = 0;
  std::map<std::string, double> errors;
  /// The metrics of `errors` that score a field the point's model does not compute (agents: a
  /// stress component its rule set leaves at zero): kept in the files, given no verdict, left off
  /// every front.
  std::set<std::string> not_modelled;
};

/// The verdict on one point in one metric.
struct FrontVerdict {
  std::string point, metric;
  /// The point's error is at or below the reference's own error in this metric: no verdict is
  /// given (neither dominated_by nor a speed-up).
  bool below_floor = false;
  /// The cheapest point that is at least as fast and at least as accurate (and better in one), or
  /// none: the point is on the front.
  std::optional<std::string> dominated_by;
  /// The fast models only: the FEM's time at the point's error (log-log between the two FEM points of the
  /// FEM front around it) over the point's time. None outside the FEM's range; then one bound:
  std::optional<double> speedup;
  std::optional<double> speedup_at_most;   ///< the point is less accurate than every FEM point
  std::optional<double> speedup_at_least;  ///< the point is more accurate than every FEM point
};

/// Where the FEM becomes the cheaper model for one family of the fast model in one metric.
struct FrontCrossover {
  std::string metric, model, rule_set;  ///< the family: model ("agent", "pbd") and rule set (agents)
  /// Below this error the FEM is the cheaper model (both fronts interpolated log-log); none when
  /// the two fronts share no range of errors.
  std::optional<double> fem_cheaper_below;
  std::string note;  ///< one sentence on what the number means here
};

/// The points of `points` of `model` (and `rule_set`, when not empty) that are not dominated in
/// `metric` by another of them, their error finite and above `floor`: sorted by error, largest
/// first (so by time, cheapest first).
std::vector<const FrontPoint*> family_front(const std::vector<FrontPoint>& points, const std::string& metric,
                                            const std::string& model, const std::string& rule_set, double floor);

/// The time [s] of `front` (family_front's order) at error `error`, log-log between its two points
/// around it; none outside [its smallest, its largest error].
std::optional<double> time_at_error(const std::vector<const FrontPoint*>& front, const std::string& metric,
                                    double error);

/// A verdict for every point with a finite error in every metric of `metrics`; `floors` gives the
/// reference's own error per metric (a metric not in it has floor 0).
std::vector<FrontVerdict> front_verdicts(const std::vector<FrontPoint>& points, const std::vector<std::string>& metrics,
                                         const std::map<std::string, double>& floors);

/// The crossover of every family of a fast model (each agent rule set, the PBD) with the FEM in every metric of `metrics`.
std::vector<FrontCrossover> front_crossovers(const std::vector<FrontPoint>& points,
                                             const std::vector<std::string>& metrics,
                                             const std::map<std::string, double>& floors);

}  // namespace compare
