#pragma once
// Saying before a run whether the rule set can carry each load to a rigid face (docs/agent-model.md,
// "The carry check"; research: bench/research/carry_check.py). The patent, conserving and
// directional rule sets march from the loaded face inward: a load whose rigid faces do not lie ahead
// of it (a cantilever, a bracket clamped at its side) is passed out through free faces whatever the
// coefficients. The columns rule set carries a load by bending to a clamp or two supports beside
// it (agent/columns.h), or cannot at all (then the study refuses the case before the run).
#include "agent_study.h"

#include <string>
#include <vector>

namespace agent_study {

/// Where a march from `entry` agents along `march` can leave the body: the rows ahead are swept,
/// each row's reached set widened by `widen` agents (the rule set's agent::lateral_reach) each way along every lateral axis through the
/// agents of that row; a face across the march where the body ends ahead of a reached agent is an
/// exit, rigid (a reaction) or free (passed out). Areas [m^2]. One pass over the reachable rows.
struct Exits {
  double rigid = 0, free = 0;
};
Exits exits_ahead(const agent::Grid& grid, const std::vector<std::size_t>& entry, int march, int widen);

/// One load of the case (a [[load]] table, or one axis component of a vector direction) on the
/// faces it enters by in one direction, checked.
struct LoadCarry {
  std::size_t load = 0;  ///< index in setup.loads (LoadSpec::key() names the [[load]] table)
  std::string group;
  int inward = 0;  ///< the direction its entry loads march in (agent::EntryLoad::dir)
  /// The rule set that carries it: the study's, or under "auto" the one chosen (columns where the
  /// directional march leaves by free faces more than rigid ones and the columns can carry it)
  agent::RuleSet rules = agent::RuleSet::Directional;
  /// The direction the rule set marches: the loaded face's inward normal; the columns rule set:
  /// along the beam axis toward the clamp (supports: toward the first, -x or -y)
  int march = 0;
  /// The rigid and free faces the march leaves by; the columns: the clamp's or the supports' (free 0)
  Exits exits;
  /// When refused: the directions across the march along which rigid faces lie ahead ("-x"), else "".
  std::string across;
  std::string route;  ///< the columns rule set: how it carries the load ("bending: columns along x ...")
  std::string why;    ///< when refused: why, in one sentence
  /// The rule set cannot carry it: no rigid face ahead of the loaded face (the columns: none beside it).
  bool refused() const { return !(exits.rigid > 0); }
  /// "load[0] (group "tip", 2 N, march -y): rigid exits 0 mm^2, free 22 mm^2: ..." (one line).
  std::string describe(const AgentStudy& study) const;
};

/// Every load of the study (setup.loads) under `rules`, in case order: for "auto", the choice of
/// each load's rule set.
std::vector<LoadCarry> carry_check(const AgentStudy& study, agent::RuleSet rules);
inline std::vector<LoadCarry> carry_check(const AgentStudy& study) { return carry_check(study, study.rules); }

}  // namespace agent_study
