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
  s << "load[" << load << "] (group \"" << group << "\", " << spec.force << " N " << spec.direction_name() << ", march "
    << agent::kDirectionNames[march] << "): rigid exits " << 1e6 * exits.rigid << " mm^2, free exits "
    << 1e6 * exits.free << " mm^2";
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

}  // namespace

std::vector<LoadCarry> carry_check(const AgentStudy& study) {
  const auto& grid = study.mesh.grid;
  const int widen = agent::lateral_reach(grid, study.rules, study.coefficients, study.readings);
  std::vector<LoadCarry> out;
  for (std::size_t i = 0; i < study.setup.loads.size(); ++i) {
    const auto& spec = study.setup.loads[i];
    const int dir = agent::direction(spec.axis, spec.sign > 0);
    std::map<int, std::vector<std::size_t>> by_march;  // a pull marches inward, as the transfer does
    for (const auto& f : study.mesh.face_groups.at(spec.group))
      by_march[dir == f.side ? agent::opposite(dir) : dir].push_back(f.cell);
    for (const auto& [march, cells] : by_march) {
      LoadCarry c;
      c.load = i, c.group = spec.group, c.march = march;
      std::vector<agent::EntryLoad> entries;
      for (std::size_t cell : cells) entries.push_back({cell, march, 1.0});
      agent::ColumnPlan plan;
      if (study.rules == agent::RuleSet::Columns) {
        if (const auto columns_cannot = columns_refusal(grid, entries, plan); columns_cannot.empty()) {
          c.march = plan.holding == agent::Holding::Clamp ? plan.clamp_side : agent::direction(plan.axis, false);
          c.exits.rigid = plan.rigid_area, c.route = agent::describe(plan);
        } else {
          c.why = columns_cannot;
        }
        out.push_back(c);
        continue;
      }
      c.exits = exits_ahead(grid, cells, march, widen);
      if (c.refused()) {  // where a load path by shear and bending would go: the axes with a rigid face ahead
        for (int d = 0; d < 2 * grid.dim; ++d)
          if (agent::axis_of(d) != agent::axis_of(march) && exits_ahead(grid, cells, d, widen).rigid > 0)
            c.across += std::string(c.across.empty() ? "" : ", ") + agent::kDirectionNames[d];
        c.why = std::string("no rigid face ahead of the loaded face (march ") + agent::kDirectionNames[march] +
                "); the " + agent::rule_set_name(study.rules) + " rule set passes it out through free faces";
        if (!c.across.empty()) {
          const auto columns_cannot = columns_refusal(grid, entries, plan);
          c.why += " (rigid faces lie ahead along " + c.across + ": reached by bending; " +
                   (columns_cannot.empty() ? "rule_set = \"columns\" carries it: " + agent::describe(plan)
                                           : "the columns rule set cannot: " + columns_cannot) + ")";
        }
      }
      out.push_back(c);
    }
  }
  return out;
}

}  // namespace agent_study
