// `workbench calibrate`: fits the agent transfer coefficients against the FEM reference.
#include "commands.h"

#include <studies/studies.h>
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
      const auto case_ptr = read_case_file_on_every_rank(*case_file);
      const workbench::CaseFile& file = *case_ptr;
      // Under MPI every rank solves the references and scores its share of the cases; rank 0
      // owns the folder and writes (compare/calibration_study.h, studies.h).
      const auto run = studies::run_calibrate_study(file, output_folder(*output, file, "calibrate"), progress_log());
      progress_log() << "calibrate: wrote " << run.folder.string() << "\n";
      return 0;
    };
  });
}

}  // namespace cli
