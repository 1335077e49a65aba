#include "commands.h"

#include <pbd_study.h>
#include <workbench/case_file.h>
#include <workbench/staged_directory.h>
#include <workbench/study_setup.h>

#include <iostream>
#include <memory>

namespace cli {

void add_pbd_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("pbd", "Run the PBD angle bending model (CN104268305A) on a case file");
  auto case_file = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto animate = std::make_shared<bool>(false);
  cmd->add_option("case", *case_file, "case file (TOML with a [pbd] section, see docs/case-file.md)")->required();
  cmd->add_option("-o,--output", *output, "output folder (default: out/<case name>/pbd)");
  cmd->add_flag("--animate", *animate, "also render animation.mp4 (or .gif, [pbd] animation) with ffmpeg");
  cmd->callback([&action, case_file, output, animate] {
    action = [case_file, output, animate] {
      workbench::CaseFile file(*case_file);
      auto setup = pbd_study::read_pbd_case(file);
      // A PBD-against-FEM case also describes the FEM body ([mesh], [material], [fem], ...): it is
      // checked here too, so that the one case file runs with `pbd` and with `compare` alike.
      if (file.root().has("mesh")) workbench::read_study_setup(file.root());
      check_every_section(file);
      auto study = pbd_study::load_pbd_study(file, std::move(setup));
      const std::string dir = output->empty() ? "out/" + file.path().stem().string() + "/pbd" : *output;
      workbench::StagedDirectory staged(dir);
      pbd_study::run_pbd_study(study, staged.path(), *animate, std::cerr);
      staged.commit();
      std::cerr << "pbd: wrote " << staged.target().string() << "\n";
      return 0;
    };
  });
}

}  // namespace cli
