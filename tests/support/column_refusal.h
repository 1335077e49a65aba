#pragma once
// Why the column rule set refuses loads on a grid (agent::plan_columns' one sentence), or "carried".
#include <agent/columns.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace test_support {

inline std::string column_refusal(const agent::Grid& g, const std::vector<agent::EntryLoad>& loads) {
  try {
    agent::plan_columns(g, loads);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "carried";
}

}  // namespace test_support
