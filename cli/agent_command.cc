#include "commands.h"

#include <agent_study.h>
#include <workbench/case_file.h>
#include <workbench/staged_directory.h>

#include <iostream>
#include <memory>

namespace cli {

void add_agent_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("agent", "Run the agent load-transfer method (WO2001052193) on a case file");
  auto case_file = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto check = std::make_shared<bool>(false);
  cmd->add_option("case", *case_file, "case file (TOML, see docs/case-file.md)")->required();
  cmd->add_option("-o,--output", *output, "output folder (default: out/<case name>/agent)");
  cmd->add_flag("--check", *check, kCheckHelp);
  cmd->callback([&action, case_file, output, check] {
    action = [case_file, output, check] {
      workbench::CaseFile file = read_case_file(*case_file);
      const auto study = agent_study::load_agent_study(file);
      check_every_section(file);
      if (*check) return checked(file, "agent");
      const std::string dir = output_folder(*output, file, "agent");
      workbench::StagedDirectory staged(dir, file.path());
      agent_study::write_agent_outputs(study, staged.path(), std::cerr);
      staged.commit();
      std::cerr << "agent: wrote " << staged.target().string() << "\n";
      return 0;
    };
  });
}

}  // namespace cli
