#pragma once
// The one-line error an agent study's case file gives (or "no error"), for the tests of bad input.
#include <agent_study.h>
#include <workbench/error.h>

#include <string>

#include "scratch_folder.h"

namespace test_support {

/// Loads `body` as a case file (written into the test's scratch folder) and checks its keys.
inline std::string study_error(const std::string& body) {
  try {
    workbench::CaseFile file(write_file("bad.toml", body));
    agent_study::load_agent_study(file);
    file.reject_unknown_keys();
  } catch (const workbench::Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace test_support
