// `workbench pbd`: the PBD angle bending model stepped into frames (VTU/PVD/CSV, animation).
#include "commands.h"

#include <pbd_study.h>
#include <workbench/case_file.h>
#include <workbench/staged_directory.h>

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
      auto setup = pbd_study::read_pbd_case(file);
      check_every_section(file);  // before the mesh is built: unknown keys first
      if (*check) return checked(file, "pbd");
      auto study = pbd_study::load_pbd_study(file, std::move(setup));
      const std::string dir = output_folder(*output, file, "pbd");
      workbench::StagedDirectory staged(dir, file.path());
      pbd_study::run_pbd_study(study, staged.path(), *animate, std::cerr);
      staged.commit();
      std::cerr << "pbd: wrote " << staged.target().string() << "\n";
      return 0;
    };
  });
}

}  // namespace cli
