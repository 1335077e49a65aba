// `workbench fem`: the deal.II FEM reference, serial or under mpirun (collective errors).
#include "commands.h"

#include <studies/studies.h>
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
      const auto case_ptr = read_case_file_on_every_rank(*case_file);
      const workbench::CaseFile& file = *case_ptr;
      if (*check) {
        studies::check_fem_study(file);
        return checked(file, "fem");
      }
      // Every rank solves and writes its VTU piece; rank 0 owns the folder (studies.h).
      const auto run = studies::run_fem_study(file, output_folder(*output, file, "fem"), std::cerr);
      progress_log() << "fem: wrote " << run.folder.string() << "\n";
      return 0;
    };
  });
}

}  // namespace cli
