// `workbench agent` (the agent study: VTU per load step, CSV, summary) and `workbench voxelize` (a staircase .msh from any geometry).
#include "commands.h"

#include <agent/voxelize.h>
#include <studies/studies.h>
#include <workbench/error.h>
#include <workbench/study_setup.h>
#include <workbench/case_file.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <vector>

#include <unistd.h>

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
      if (*check) {
        return checked(file, "agent", studies::open_agent_study(file).warnings);
      }
      const auto run = studies::run_agent_study(file, output_folder(*output, file, "agent"), std::cerr);
      std::cerr << "agent: wrote " << run.folder.string() << "\n";
      return 0;
    };
  });
}

void add_voxelize_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("voxelize", "Turn a gmsh geometry of any shape into an agent grid (a staircase .msh)");
  auto geometry = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto size = std::make_shared<double>(0.0);
  auto settings = std::make_shared<std::vector<std::string>>();
  auto unit = std::make_shared<std::string>("m");
  std::vector<std::string> units;
  for (const auto& [name, metres] : workbench::mesh_units()) units.push_back(name);
  cmd->add_option("geometry", *geometry, "gmsh .geo or .msh of the body (any elements, physical groups)")->required();
  cmd->add_option("-s,--size", *size, "agent size [m]")->required();
  cmd->add_option("-p,--parameter", *settings, "a .geo parameter, NAME=VALUE (repeatable)");
  cmd->add_option("-u,--unit", *unit, "the unit of the geometry's coordinates, as [mesh] unit (the staircase is in metres)")
      ->check(CLI::IsMember(units));
  cmd->add_option("-o,--output", *output, "the staircase mesh to write (.msh; must not exist)")->required();
  cmd->callback([&action, geometry, output, size, settings, unit] {
    action = [geometry, output, size, settings, unit] {
      namespace fs = std::filesystem;
      std::map<std::string, double> parameters;
      for (const auto& s : *settings) {
        const auto eq = s.find('=');
        char* end = nullptr;
        const double value = eq == std::string::npos ? 0.0 : std::strtod(s.c_str() + eq + 1, &end);
        if (eq == std::string::npos || end == s.c_str() + eq + 1 || *end != '\0' || !std::isfinite(value))
          throw workbench::Error(*geometry + ": --parameter " + s + ": expected NAME=VALUE with a finite number");
        parameters[s.substr(0, eq)] = value;
      }
      const fs::path target(*output);
      if (target.extension() != ".msh") throw workbench::Error(*output + ": the staircase mesh must be a .msh file");
      if (fs::exists(target)) throw workbench::Error(*output + ": exists; the workbench does not overwrite a file it did not write");
      // Written beside the target and renamed into place: whole or nothing.
      const fs::path staged = target.parent_path() / ("." + target.stem().string() + ".partial-" + std::to_string(::getpid()) + ".msh");
      try {
        double metres = 1.0;
        for (const auto& [name, m] : workbench::mesh_units())
          if (name == *unit) metres = m;
        const auto mesh = agent::voxelize(*geometry, *size, parameters, staged, metres);
        fs::rename(staged, target);
        std::cerr << "voxelize: " << mesh.grid.agent_count() << " agents of " << *size << " m in a "
                  << mesh.grid.cells[0] << " x " << mesh.grid.cells[1];
        if (mesh.grid.dim == 3) std::cerr << " x " << mesh.grid.cells[2];
        std::cerr << " box; groups:";
        for (const auto& [name, faces] : mesh.face_groups) std::cerr << " " << name << " (" << faces.size() << " faces)";
        std::cerr << "\nvoxelize: wrote " << target.string() << "\n";
      } catch (const std::runtime_error& e) {
        std::error_code ignored;
        fs::remove(staged, ignored);
        // The user named the target: a failed write of the staged file is said of it.
        std::string what = e.what();
        for (auto at = what.find(staged.string()); at != std::string::npos; at = what.find(staged.string(), at))
          what.replace(at, staged.string().size(), target.string());
        throw workbench::Error(what);
      }
      return 0;
    };
  });
}

}  // namespace cli
