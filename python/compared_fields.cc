// The fields as numpy arrays and dicts (python/arrays.h): workbench.compare's "fields" (the
// compared fields), workbench.run_agent's (the agent state's, by the field table agent::kStateFields).
#include "arrays.h"

#include <compare/sampling.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <string>

namespace workbench_python {

namespace {

py::dict table_dict(compare::FieldTable&& t) {
  using Kind = compare::FieldTable::Kind;
  py::dict out;
  for (auto& c : t.columns) {
    std::vector<py::ssize_t> shape{ssize(t.rows)};
    if (c.components > 1) shape.push_back(c.components);
    if (c.kind == Kind::Real) {
      out[py::str(c.name)] = take(std::move(c.values), shape);
    } else if (c.kind == Kind::Integer) {
      out[py::str(c.name)] = take(std::vector<std::int64_t>(c.values.begin(), c.values.end()), shape);
    } else {
      std::vector<std::uint8_t> flags(c.values.begin(), c.values.end());
      out[py::str(c.name)] = take(std::move(flags), shape).attr("view")("bool");  // 0 or 1: a valid bool, no copy
    }
  }
  return out;
}

py::dict diagnostics_dict(const agent::Diagnostics& d) {
  py::dict out;
  out["agents_generated"] = d.agents_generated;
  out["agent_updates"] = d.agent_updates;
  out["applied_N"] = d.applied;
  out["rigid_reaction_N"] = d.rigid_reaction;
  out["passed_out_N"] = d.passed_out;
  out["dropped_N"] = d.dropped;
  out["lost_N"] = d.lost;  // applied = rigid reaction + passed out + dropped + lost
  out["lateral_reaction_N"] = d.lateral_reaction;
  out["lateral_passed_out_N"] = d.lateral_passed_out;
  out["lateral_dropped_N"] = d.lateral_dropped;
  out["returned_rigid_N"] = d.returned_rigid;  // reading 6: returned into the body, not in the balance
  out["returned_free_N"] = d.returned_free;
  return out;
}

/// Every value of field `f` of `state`, rows x components.
template <class T>
py::array_t<T> field_array(const agent::StateField& f, const agent::AgentState& state, int dim) {
  const std::size_t rows = f.place == agent::FieldPlace::Agent ? state.generation.size()
                                                                : state.displacement.size() / std::size_t(dim);
  const int n = f.components(dim);
  std::vector<T> values(rows * std::size_t(n));
  for (std::size_t at = 0; at < rows; ++at)
    for (int k = 0; k < n; ++k) values[at * std::size_t(n) + std::size_t(k)] = T(f.read(state, at, k, dim));
  std::vector<py::ssize_t> shape{ssize(rows)};
  if (n > 1) shape.push_back(n);
  return take(std::move(values), shape);
}

}  // namespace

void add_state_fields(py::dict& out, const agent::AgentState& state, int dim) {
  for (const auto& f : agent::kStateFields) {
    if (f.integer)
      out[f.name] = field_array<std::int32_t>(f, state, dim);
    else
      out[f.name] = field_array<double>(f, state, dim);
  }
  out["diagnostics"] = diagnostics_dict(state.diagnostics);
}

py::list state_fields_list() {
  py::list out;
  for (const auto& f : agent::kStateFields) {
    py::dict d, columns;
    d["name"] = f.name;
    d["unit"] = f.unit;
    d["place"] = f.place == agent::FieldPlace::Agent ? "agent" : "node";
    d["vtu"] = f.vtu == agent::VtuLayout::Scalars ? "scalars" : f.vtu == agent::VtuLayout::Vector ? "vector" : "vector3";
    d["integer"] = f.integer;
    for (int dim : {2, 3}) {
      py::list names;
      for (int k = 0; k < f.components(dim); ++k) names.append(f.columns[k]);
      columns[py::int_(dim)] = names;
    }
    d["columns"] = columns;
    py::list compared;  // the rows of compare::kFields this field gives: the whole field, or a column
    for (const auto& c : compare::kFields)
      if (std::string(c.name) == f.name || std::find(f.columns, f.columns + f.count[1], std::string(c.name)) != f.columns + f.count[1])
        compared.append(c.name);
    d["compared"] = compared;
    out.append(d);
  }
  return out;
}

py::dict compared_fields_dict(compare::ComparedFields&& fields) {
  py::dict out, lines;
  if (fields.cells.rows > 0) out["cells"] = table_dict(std::move(fields.cells));
  if (fields.nodes.rows > 0) out["nodes"] = table_dict(std::move(fields.nodes));
  for (auto& [name, table] : fields.lines) lines[py::str(name)] = table_dict(std::move(table));
  out["lines"] = lines;
  return out;
}

}  // namespace workbench_python
