// The [front] section: the ladders and the gate of the cost-accuracy front.
#include <schema/front_options.h>

#include <agent/coefficients.h>

#include <cmath>

namespace schema {

namespace {

void read_gate(const workbench::CaseTable& t, FrontGate& gate) {
  gate.min_speedup = t.number_map("min_speedup");
  for (const auto& [name, limit] : gate.min_speedup)
    if (!(limit > 0) || !std::isfinite(limit)) t.fail("min_speedup." + name, "a speed-up must be a finite number > 0");
  gate.on_front = t.texts("on_front", std::vector<std::string>{});
}

/// A list of whole numbers >= 1 (empty when the key is absent).
std::vector<int> counts(const workbench::CaseTable& t, const char* key) {
  std::vector<int> out;
  for (double v : t.numbers(key, std::vector<double>{}, workbench::Range::closed(1, 1e7))) {
    if (v != std::floor(v)) t.fail(key, "a count is a whole number");
    out.push_back(int(v));
  }
  return out;
}

}  // namespace

FrontOptions read_front_options(const workbench::CaseTable& root) {
  const auto t = root.table("front");
  FrontOptions o;
  o.size_parameter = t.text("size_parameter", o.size_parameter);
  const auto factors = workbench::Range{1.0 / 64, 64, false, false};
  o.agent_sizes = t.numbers("agent_sizes", o.agent_sizes, factors);
  o.fem_sizes = t.numbers("fem_sizes", o.fem_sizes, factors);
  std::vector<double> degrees(o.fem_degrees.begin(), o.fem_degrees.end());
  degrees = t.numbers("fem_degrees", degrees, workbench::Range::closed(1, 2));
  o.fem_degrees.clear();
  for (double d : degrees) {
    if (d != std::floor(d)) t.fail("fem_degrees", "a degree is 1 or 2");
    o.fem_degrees.push_back(int(d));
  }
  o.fem_max_dofs = t.number("fem_max_dofs", o.fem_max_dofs, workbench::Range::positive());
  o.rule_sets = t.texts("rule_sets", o.rule_sets);
  for (const auto& r : o.rule_sets)
    if (!agent::rule_set_named(r))
      t.fail("rule_sets", "unknown rule set \"" + r + "\"");
  o.runs = t.integer("runs", o.runs, 1, 100);
  o.pbd_substeps = counts(t, "pbd_substeps");
  o.pbd_iterations = counts(t, "pbd_iterations");
  o.cells_parameter = t.text("cells_parameter", o.cells_parameter);
  read_gate(t.table("gate"), o.gate);
  return o;
}

}  // namespace schema
