#include "commands.h"

#include <agent_study.h>
#include <compare/compare_study.h>
#include <fem_reference/fem.h>

namespace cli {

void check_every_section(const workbench::CaseFile& file) {
  const auto root = file.root();
  agent::Coefficients k;
  agent::RuleSet rules;
  agent_study::read_agent_section(root, k, rules);
  fem_reference::read_fem_section(root);
  compare::read_compare_options(root);
  file.reject_unknown_keys();
}

}  // namespace cli
