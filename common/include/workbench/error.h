#pragma once
// The one error type of the workbench: a one-line message that names the file and the thing.
#include <stdexcept>
#include <string>

namespace workbench {

/// Raised for bad input (case file, mesh, parameters). The command-line program prints
/// `workbench: error: <what()>` and exits non-zero.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace workbench
