#pragma once
// The switch between the agent model's tables and the library's transcendental functions.

namespace agent {

/// While one lives on a thread, the agent model there takes the library's functions (std::erfc:
/// agent::ExactNormalCdf) in place of its tables: the reference the tests bound the tables against
/// (tests/agent/test_normal_cdf.cc), and a way to check any result. Slower; the fields differ by
/// round-off (docs/performance.md, "Issue 38").
class ExactFunctions {
 public:
  ExactFunctions();
  ~ExactFunctions();
  ExactFunctions(const ExactFunctions&) = delete;
  ExactFunctions& operator=(const ExactFunctions&) = delete;
  /// Whether one lives on this thread.
  static bool active();

 private:
  bool outer_;  ///< active() before this one
};

}  // namespace agent
