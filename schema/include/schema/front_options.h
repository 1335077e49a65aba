#pragma once
// The [front] section of a case file, read and checked: the ladders of the cost-accuracy front
// (`workbench front`, docs/front.md). Part of the case schema (schema/every_section.h).
#include <workbench/case_file.h>

#include <map>
#include <string>
#include <vector>

namespace schema {

/// [front.gate]: what the agent point at the case's own size must show for CI.
struct FrontGate {
  /// metric -> least speed-up over the FEM of equal error (a bound counts when it settles it).
  std::map<std::string, double> min_speedup;
  /// Metrics in which that point must not be dominated by another point of the front.
  std::vector<std::string> on_front;
};

/// The [front] table of a case file.
struct FrontOptions {
  /// The mesh parameter ([mesh.parameters]) that sets the agents' edge and the FEM's element size.
  std::string size_parameter = "h";
  std::vector<double> agent_sizes{4, 2, 1, 0.5};  ///< the agents' ladder, multiples of the case's size
  std::vector<double> fem_sizes{4, 2, 1, 0.5};    ///< the FEM's ladder, multiples of the case's size
  std::vector<int> fem_degrees{1, 2};
  /// FEM points estimated to have more DoFs than this are left out (and said so).
  double fem_max_dofs = 400000;
  /// Rule sets besides the case's own (agent::kRuleSets names).
  std::vector<std::string> rule_sets;
  int runs = 3;  ///< timed warm runs per point, after one warm-up run
  /// PBD cases (compare.model = "pbd"): the PBD ladder, every substeps x iterations pair; empty:
  /// the case's substeps times 1/8, 1/4, 1/2, 1, 2 and iterations 1, 2, 4, 8 with the case's own.
  std::vector<int> pbd_substeps, pbd_iterations;
  /// PBD cases: the FEM strip's mesh parameter counting its cells along the strip; the FEM rung at
  /// fem_sizes factor f sets it to the case's value / f (rounded).
  std::string cells_parameter = "nx";
  FrontGate gate;
};

/// Reads [front] (every key optional).
FrontOptions read_front_options(const workbench::CaseTable& root);

}  // namespace schema
