// The carry check before a run (agent_study/carry_check.h).
#include "carry_check.h"

#include <agent/columns.h>

#include <map>
#include <stdexcept>
#include <sstream>

namespace agent_study {

Exits exits_ahead(const agent::Grid& grid, const std::vector<std::size_t>& entry, int march, int widen) {
  const int a = agent::axis_of(march);
  const double area = grid.face_area(a);
  std::vector<char> seen(grid.count(), 0);
  std::vector<std::size_t> now, next;
  for (std::size_t c : entry)
    if (!seen[c]) seen[c] = 1, now.push_back(c);
  Exits out;
  while (!now.empty()) {
    next.clear();
    for (std::size_t c : now) {
      const std::size_t n = grid.neighbour(c, march);
      if (n != agent::Grid::npos && !grid.is_air(n)) {
        if (!seen[n]) seen[n] = 1, next.push_back(n);
      } else {
        (grid.boundary(march, c) == agent::Boundary::Rigid ? out.rigid : out.free) += area;
      }
    }
    // Widen through the row's agents, up to `widen` each way along each lateral axis.
    const std::size_t row = next.size();
    for (std::size_t i = 0; i < row; ++i)
      for (int b = 0; b < grid.dim; ++b) {
        if (b == a) continue;
        for (int side : {agent::direction(b, false), agent::direction(b, true)}) {
          std::size_t c = next[i];
          for (int s = 0; s < widen; ++s) {
            c = grid.neighbour(c, side);
            if (c == agent::Grid::npos || grid.is_air(c)) break;
            if (!seen[c]) seen[c] = 1, next.push_back(c);
          }
        }
      }
    now.swap(next);
  }
  return out;
}

std::string LoadCarry::describe(const AgentStudy& study) const {
  const auto& spec = study.setup.loads[load];
  std::ostringstream s;
  s << spec.key() << " (group \"" << group << "\", " << spec.force << " N " << spec.direction_name() << ", march "
    << agent::kDirectionNames[march] << "): rigid exits " << 1e6 * exits.rigid << " mm^2, free exits "
    << 1e6 * exits.free << " mm^2";
  if (study.rules == agent::RuleSet::Auto) s << ": auto chose " << agent::rule_set_name(rules);
  if (refused())
    s << ": cannot carry: " << why;
  else if (!route.empty())
    s << ": carries by " << route;
  else
    s << ": carries (rigid share of the exits " << exits.rigid / (exits.rigid + exits.free) << ")";
  return s.str();
}

namespace {

/// The column rule set's verdict on entry loads: empty and `plan` set when it carries them, else why not.
std::string columns_refusal(const agent::Grid& grid, const std::vector<agent::EntryLoad>& loads, agent::ColumnPlan& plan) {
  try {
    plan = agent::plan_columns(grid, loads);
    return "";
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

/// `c` carried by the columns: by `plan`, or refused for `why`.
void carry_by_columns(LoadCarry& c, const agent::ColumnPlan& plan, const std::string& why) {
  c.rules = agent::RuleSet::Columns;
  if (!why.empty()) {
    c.why = why;
    return;
  }
  c.march = plan.holding == agent::Holding::Clamp ? plan.clamp_side : agent::direction(plan.axis, false);
  c.exits.rigid = plan.rigid_area, c.route = agent::describe(plan);
}

/// `c` carried by a march (`rules`) that leaves the body by `exits`; refused: why, and where
/// bending would take it.
void carry_by_march(LoadCarry& c, agent::RuleSet rules, const Exits& exits, const agent::Grid& grid,
                    const std::vector<std::size_t>& cells, int widen, const std::string& columns_cannot,
                    const agent::ColumnPlan& plan, bool chosen) {
  c.rules = rules, c.exits = exits;
  if (!c.refused()) return;
  for (int d = 0; d < 2 * grid.dim; ++d)  // where a load path by shear and bending would go: the axes with a rigid face ahead
    if (agent::axis_of(d) != agent::axis_of(c.march) && exits_ahead(grid, cells, d, widen).rigid > 0)
      c.across += std::string(c.across.empty() ? "" : ", ") + agent::kDirectionNames[d];
  c.why = std::string("no rigid face ahead of the loaded face (march ") + agent::kDirectionNames[c.march] + "); the " +
          agent::rule_set_name(rules) + " rule set passes it out through free faces";
  if (!c.across.empty())
    c.why += " (rigid faces lie ahead along " + c.across + ": reached by bending; " +
             (columns_cannot.empty() ? "rule_set = \"columns\" carries it: " + agent::describe(plan)
                                     : "the columns rule set cannot: " + columns_cannot) + ")";
  else if (chosen)  // auto tried the columns too
    c.why += "; the columns rule set cannot: " + columns_cannot;
}

}  // namespace

std::vector<LoadCarry> carry_check(const AgentStudy& study, agent::RuleSet rules) {
  const auto& grid = study.mesh.grid;
  // Auto's march is the directional rule set's.
  const auto marching = rules == agent::RuleSet::Auto ? agent::RuleSet::Directional : rules;
  const int widen = marching == agent::RuleSet::Columns ? 0 : agent::lateral_reach(grid, marching, study.coefficients, study.readings);
  std::vector<LoadCarry> out;
  for (std::size_t i = 0; i < study.setup.loads.size(); ++i) {
    const auto& spec = study.setup.loads[i];
    const int dir = agent::direction(spec.axis, spec.sign > 0);
    std::map<int, std::vector<std::size_t>> by_march;  // a pull marches inward, as the transfer does
    for (const auto& f : study.mesh.face_groups.at(spec.group))
      by_march[dir == f.side ? agent::opposite(dir) : dir].push_back(f.cell);
    for (const auto& [march, cells] : by_march) {
      LoadCarry c;
      c.load = i, c.group = spec.group, c.inward = c.march = march;
      std::vector<agent::EntryLoad> entries;
      for (std::size_t cell : cells) entries.push_back({cell, march, 1.0});
      agent::ColumnPlan plan;
      const auto columns_cannot = columns_refusal(grid, entries, plan);
      const Exits ahead = marching == agent::RuleSet::Columns ? Exits{} : exits_ahead(grid, cells, march, widen);
      // Auto bends what the march would pass out more than return: the columns carry it whole.
      const bool bend = rules == agent::RuleSet::Columns ||
                        (rules == agent::RuleSet::Auto && columns_cannot.empty() && !(ahead.rigid > ahead.free));
      if (bend)
        carry_by_columns(c, plan, columns_cannot);
      else
        carry_by_march(c, marching, ahead, grid, cells, widen, columns_cannot, plan, rules == agent::RuleSet::Auto);
      out.push_back(c);
    }
  }
  return out;
}

}  // namespace agent_study
