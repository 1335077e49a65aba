// `workbench compare`: a fast model against the FEM reference (metrics, figures, tolerance gate).
#include "commands.h"

#include <compare/compare_study.h>
#include <fem_reference/mpi.h>
#include <workbench/case_file.h>
#include <workbench/output_file.h>
#include <workbench/staged_directory.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>

namespace cli {

namespace {

/// Rank 0, once the study is written: the folder moved into place, the JUnit copy, the gate's
/// lines; returns the exit code.
int finish(workbench::StagedDirectory& staged, const compare::CompareOutcome& outcome, const std::string& junit) {
  staged.commit();
  if (!junit.empty()) {
    const auto parent = std::filesystem::path(junit).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    std::ifstream report(staged.target() / "junit.xml", std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>()};
    try {
      workbench::replace_file(junit, text);  // a failed write leaves an earlier report whole
    } catch (const workbench::Error& e) {
      throw workbench::Error(std::string(e.what()) + " (--junit; the output folder is complete)");
    }
  }
  std::cerr << "compare: wrote " << staged.target().string() << "\n";
  for (const auto& f : outcome.failures) std::cerr << "compare: gate: " << f.describe() << "\n";
  if (outcome.gated > 0)
    std::cerr << "compare: gate: " << outcome.gated - outcome.failures.size() << " passed, "
              << outcome.failures.size() << " failed\n";
  return outcome.failures.empty() ? 0 : 1;
}

}  // namespace

void add_compare_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "compare",
      "Run a fast model ([compare] model: the agent method, or the PBD rod) and the FEM reference on one case and "
      "compare them (exit 1 if the gate fails)");
  auto case_file = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto check = std::make_shared<bool>(false);
  auto junit = std::make_shared<std::string>();
  cmd->add_option("case", *case_file, "case file (TOML, see docs/case-file.md)")->required();
  cmd->add_option("-o,--output", *output, "output folder (default: out/<case name>/compare)");
  cmd->add_flag("--check", *check, kCheckHelp);
  cmd->add_option("--junit", *junit, "also copy the gate's JUnit XML report to this file");
  cmd->callback([&action, case_file, output, check, junit] {
    action = [case_file, output, check, junit] {
      const auto case_ptr = read_checked_case(*case_file);
      const workbench::CaseFile& file = *case_ptr;
      if (*check) return checked(file, "compare");
      if (!junit->empty()) check_writable_file(*junit, "--junit");
      const std::string dir = output_folder(*output, file, "compare");
      // Rank 0 owns the staged folder; every rank solves the FEM and writes its VTU piece into it,
      // rank 0 alone the rest (compare_study.h).
      std::filesystem::path path;
      const auto staged = stage_on_rank_0(dir, file, path);
      const auto outcome = compare::run_compare(file, path, progress_log());
      int code = 0;
      fem_reference::mpi_on_root([&] { code = finish(*staged, outcome, *junit); });
      return code;
    };
  });
}

}  // namespace cli
