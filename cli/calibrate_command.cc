// `workbench calibrate`: fits the agent transfer coefficients against the FEM reference.
#include "commands.h"

#include <compare/calibration_study.h>
#include <fem_reference/mpi.h>
#include <workbench/case_file.h>

#include <iostream>
#include <memory>

namespace cli {

void add_calibrate_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("calibrate", "Fit the agent transfer coefficients against FEM (docs/calibration.md)");
  auto case_file = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  cmd->add_option("calibration", *case_file, "calibration file (TOML, see docs/calibration.md)")->required();
  cmd->add_option("-o,--output", *output, "output folder (default: out/<file name>/calibrate)");
  cmd->callback([&action, case_file, output] {
    action = [case_file, output] {
      workbench::CaseFile file = read_case_file(*case_file);
      const std::string dir = output_folder(*output, file, "calibrate");
      // Under MPI every rank solves the references and scores its share of the cases; rank 0
      // owns the folder and writes (compare/calibration_study.h).
      std::filesystem::path path;
      const auto staged = stage_on_rank_0(dir, file, path);
      compare::run_calibration(file, path, progress_log());
      fem_reference::mpi_on_root([&] {
        staged->commit();
        std::cerr << "calibrate: wrote " << staged->target().string() << "\n";
      });
      return 0;
    };
  });
}

}  // namespace cli
