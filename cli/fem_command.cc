// `workbench fem`: the deal.II FEM reference, serial or under mpirun (collective errors).
#include "commands.h"

#include <fem_reference/fem_case.h>
#include <fem_reference/mpi.h>
#include <workbench/case_file.h>

#include <iostream>
#include <memory>

namespace cli {

void add_fem_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("fem", "Run the deal.II linear-elastic FEM reference on a case file "
                                        "(serial, or distributed under mpirun)");
  auto case_file = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto check = std::make_shared<bool>(false);
  cmd->add_option("case", *case_file, "case file (TOML, see docs/case-file.md)")->required();
  cmd->add_option("-o,--output", *output, "output folder (default: out/<case name>/fem)");
  cmd->add_flag("--check", *check, kCheckHelp);
  cmd->callback([&action, case_file, output, check] {
    action = [case_file, output, check] {
      fem_reference::FemProblem problem;
      const auto case_ptr = read_checked_case(
          *case_file, [&](const workbench::CaseFile& f) { problem = fem_reference::problem_from_case(f); });
      const workbench::CaseFile& file = *case_ptr;
      if (*check) return checked(file, "fem");
      const std::string dir = output_folder(*output, file, "fem");
      // Rank 0 owns the staged folder; every rank writes its VTU piece into it. Steps that may fail
      // on rank 0 alone are collective: a failure ends every rank with the same message.
      std::filesystem::path path;
      const auto staged = stage_on_rank_0(dir, file, path);
      const auto result = fem_reference::solve_fem(problem, path, &std::cerr);
      fem_reference::mpi_on_root([&] {
        fem_reference::write_fem_csv(result, path);
        staged->commit();
        std::cerr << "fem: wrote " << staged->target().string() << "\n";
      });
      return 0;
    };
  });
}

}  // namespace cli
