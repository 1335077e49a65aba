#pragma once
// A case's load ([[load]], docs/case-file.md) as plain data: what code that only uses loads (the
// comparison's analysis) includes, without the case-file reader (workbench/study_setup.h reads it).
#include <cstddef>
#include <string>

namespace workbench {

/// A load on the outer faces of a physical group: total `force` [N] along axis `axis` with
/// sign `sign` (direction "-y" is axis 1, sign -1), shared over the faces by area. A [[load]]
/// whose direction is a vector is one LoadSpec per axis it has a component along (linearity:
/// every model superposes them), each with its share of the force.
struct LoadSpec {
  std::string group;
  int axis = 1;
  int sign = -1;
  double force = 0;
  std::size_t entry = 0;  ///< the case's [[load]] table it comes from: messages say "load[entry]"
  std::string key() const { return "load[" + std::to_string(entry) + "]"; }
  /// "-y", "+x", ...: the case file's `direction`.
  std::string direction_name() const { return std::string(sign < 0 ? "-" : "+") + char('x' + axis); }
};

}  // namespace workbench
