// `workbench front`: the cost-accuracy front of a case (compare/front.h): exit 1 if [front.gate] fails.
#include "commands.h"

#include <compare/front.h>
#include <fem_reference/mpi.h>
#include <studies/studies.h>

#include <iostream>
#include <memory>

namespace cli {

void add_front_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "front",
      "Time the agent model and the FEM at ladders of sizes against one converged reference: which is cheaper at "
      "equal error, per field (front.json, front.csv, figures, report.html; exit 1 if [front.gate] fails)");
  auto case_file = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto check = std::make_shared<bool>(false);
  cmd->add_option("case", *case_file, "case file (TOML, see docs/case-file.md, [front])")->required();
  cmd->add_option("-o,--output", *output, "output folder (default: out/<case name>/front)");
  cmd->add_flag("--check", *check, kCheckHelp);
  cmd->callback([&action, case_file, output, check] {
    action = [case_file, output, check] {
      const auto case_ptr = read_case_file_on_every_rank(*case_file);
      const workbench::CaseFile& file = *case_ptr;
      if (*check) {
        studies::open_front_study(file);
        return checked(file, "front", compare::check_front(file));
      }
      const auto run = studies::run_front_study(file, output_folder(*output, file, "front"), progress_log());
      int code = 0;
      fem_reference::mpi_on_root([&] {
        std::cerr << "front: wrote " << run.folder.string() << "\n";
        if (run.outcome.gated > 0)
          std::cerr << "front: gate: " << run.outcome.gated - run.outcome.failures.size() << " passed, "
                    << run.outcome.failures.size() << " failed\n";
        code = run.outcome.failures.empty() ? 0 : 1;
      });
      return code;
    };
  });
}

}  // namespace cli
