// `workbench compare`: a fast model against the FEM reference (metrics, figures, tolerance gate).
#include "commands.h"

#include <fem_reference/mpi.h>
#include <studies/studies.h>
#include <workbench/case_file.h>
#include <workbench/error.h>
#include <workbench/output_file.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>

namespace cli {

namespace {

/// Rank 0, once the study is written and its folder in place: the JUnit copy, the gate's lines;
/// returns the exit code.
int finish(const studies::CompareRun& run, const std::string& junit) {
  const auto& outcome = run.outcome;
  if (!junit.empty()) {
    const auto parent = std::filesystem::path(junit).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    std::ifstream report(run.folder / "junit.xml", std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>()};
    try {
      workbench::replace_file(junit, text);  // a failed write leaves an earlier report whole
    } catch (const workbench::Error& e) {
      throw workbench::Error(std::string(e.what()) + " (--junit; the output folder is complete)");
    }
  }
  std::cerr << "compare: wrote " << run.folder.string() << "\n";
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
      const auto case_ptr = read_case_file_on_every_rank(*case_file);
      const workbench::CaseFile& file = *case_ptr;
      if (*check) {
        return checked(file, "compare", studies::check_compare_study(file));
      }
      if (!junit->empty()) check_writable_file(*junit, "--junit");
      // Every rank solves the FEM and writes its VTU piece; rank 0 alone the rest and owns the
      // folder (compare_study.h, studies.h).
      const auto run = studies::run_compare_study(file, output_folder(*output, file, "compare"), progress_log());
      int code = 0;
      fem_reference::mpi_on_root([&] { code = finish(run, *junit); });
      return code;
    };
  });
}

}  // namespace cli
