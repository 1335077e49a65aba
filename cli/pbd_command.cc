// `workbench pbd`: the PBD angle bending model stepped into frames (VTU/PVD/CSV, animation).
#include "commands.h"

#include <studies/studies.h>
#include <workbench/case_file.h>

#include <iostream>
#include <memory>

namespace cli {

void add_pbd_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("pbd", "Run the PBD angle bending model (CN104268305A) on a case file");
  auto case_file = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto check = std::make_shared<bool>(false);
  auto animate = std::make_shared<bool>(false);
  cmd->add_option("case", *case_file, "case file (TOML with a [pbd] section, see docs/case-file.md)")->required();
  cmd->add_option("-o,--output", *output, "output folder (default: out/<case name>/pbd)");
  cmd->add_flag("--check", *check, kCheckHelp);
  cmd->add_flag("--animate", *animate, "also render animation.mp4 (or .gif, [pbd] animation) with ffmpeg");
  cmd->callback([&action, case_file, output, check, animate] {
    action = [case_file, output, check, animate] {
      workbench::CaseFile file = read_case_file(*case_file);
      if (*check) {
        studies::open_pbd_study(file);
        return checked(file, "pbd");
      }
      const auto folder = studies::run_pbd_study(file, output_folder(*output, file, "pbd"), *animate, std::cerr);
      std::cerr << "pbd: wrote " << folder.string() << "\n";
      return 0;
    };
  });
}

}  // namespace cli
