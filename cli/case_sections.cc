// What every subcommand does with a case file: read it, check every section, name the output folder.
#include "commands.h"

#include <agent_study.h>
#include <compare/compare_study.h>
#include <fem_reference/fem.h>
#include <pbd_study.h>
#include <workbench/study_setup.h>

#include <filesystem>
#include <iostream>

#include <unistd.h>

namespace cli {

workbench::CaseFile read_case_file(const std::string& path) {
  if (std::filesystem::is_directory(path))
    throw workbench::Error(path + ": is a folder, not a case file (give the .toml file inside it)");
  return workbench::CaseFile(path);
}

void check_writable_file(const std::string& path, const std::string& option) {
  namespace fs = std::filesystem;
  const fs::path file = fs::absolute(path).lexically_normal();
  auto refuse = [&](const std::string& why) { throw workbench::Error(path + ": " + option + ": " + why); };
  std::error_code ec;
  if (file.filename().empty() || fs::is_directory(file, ec)) refuse("is a folder, not a file");
  if (fs::exists(fs::symlink_status(file, ec))) {
    if (!fs::is_regular_file(file, ec)) refuse("exists and is not a regular file");
    if (::access(file.c_str(), W_OK) != 0) refuse("cannot be written (no permission)");
    return;
  }
  fs::path parent = file.parent_path();
  while (!fs::exists(parent, ec)) parent = parent.parent_path();
  if (!fs::is_directory(parent, ec)) refuse(parent.string() + " is not a folder");
  if (::access(parent.c_str(), W_OK | X_OK) != 0) refuse("cannot be created in " + parent.string() + " (no permission)");
}

int checked(const workbench::CaseFile& file, const std::string& subcommand) {
  std::cerr << subcommand << ": " << file.path().string() << ": checked, nothing written\n";
  return 0;
}

std::string output_folder(const std::string& option, const workbench::CaseFile& file, const std::string& subcommand) {
  return option.empty() ? "out/" + file.path().stem().string() + "/" + subcommand : option;
}

namespace {

// Every section a case file may have, each with the reader that checks it. One case file describes
// one study for every model, so every subcommand checks all of them (a section its model does not
// run is still checked, never refused as unknown).
struct Section {
  const char* names;
  void (*check)(const workbench::CaseFile& file);
};

const Section kSections[] = {
    {"mesh, material, boundary, load, steps",
     [](const workbench::CaseFile& f) {
       if (f.root().has("mesh")) workbench::read_study_setup(f.root());
     }},
    {"agent",
     [](const workbench::CaseFile& f) {
       agent::Coefficients k;
       agent::RuleSet rules;
       agent_study::read_agent_section(f.root(), k, rules);
     }},
    {"fem", [](const workbench::CaseFile& f) { fem_reference::read_fem_section(f.root()); }},
    {"compare", [](const workbench::CaseFile& f) { compare::read_compare_options(f.root()); }},
    {"pbd",
     [](const workbench::CaseFile& f) {
       if (f.root().has("pbd")) pbd_study::read_pbd_case(f);
     }},
};

}  // namespace

void check_every_section(const workbench::CaseFile& file) {
  for (const auto& section : kSections) section.check(file);
  file.reject_unknown_keys();
}

}  // namespace cli
