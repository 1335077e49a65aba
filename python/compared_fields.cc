// workbench.compare's "fields": the compared fields as numpy arrays (python/arrays.h).
#include "arrays.h"

#include <cstdint>

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

}  // namespace

py::dict compared_fields_dict(compare::ComparedFields&& fields) {
  py::dict out, lines;
  if (fields.cells.rows > 0) out["cells"] = table_dict(std::move(fields.cells));
  if (fields.nodes.rows > 0) out["nodes"] = table_dict(std::move(fields.nodes));
  for (auto& [name, table] : fields.lines) lines[py::str(name)] = table_dict(std::move(table));
  out["lines"] = lines;
  return out;
}

}  // namespace workbench_python
