// workbench: the command-line front door of the deformation-model workbench.
//
//   workbench agent cases/seed_plate.toml            agent load-transfer study (VTU/PVD/CSV)
//   workbench fem cases/seed_plate.toml              deal.II FEM reference (mpirun -np N for MPI)
//   workbench compare cases/seed_plate.toml          both on one mesh: metrics, Figures 8-11, gate
//   workbench calibrate cases/calibrate_plate.toml   fit alpha1..3, beta (gamma) against FEM
//   workbench front cases/seed_plate_directional.toml  cost against error: agent and FEM ladders, verdicts
//   workbench pbd cases/pbd_strip.toml --animate     PBD angle bending frames (VTU/PVD/CSV, MP4)
//   workbench case set CASE KEY=VALUE -o NEW.toml    a derived case file (sweeps)
//   workbench summarize DIR... -o table.csv          many output folders' summaries as one table
//   workbench <subcommand> --help                    the options of each subcommand
//
// Under mpirun, fem, compare and calibrate run distributed (the FEM over the ranks, the rest on
// rank 0), front refuses more than one rank (it times each model on one core); every other
// subcommand runs once, on rank 0 (docs/scaling.md). Every rank ends with the
// same exit code, and every line is printed once.
//
// Every error is one line "workbench: error: <file>: <what>"; bad input (command line included)
// exits 2. Output folders appear whole or not at all and never replace a folder the workbench did
// not write; SIGINT/SIGTERM end the run cleanly with 130/143 (docs/reliability.md).
#include "commands.h"

#include <fem_reference/mpi.h>
#include <workbench/error.h>
#include <gmsh_session.h>
#include <workbench/interruption.h>

#include <csignal>
#include <iostream>

int main(int argc, char** argv) {
  // The subcommands that may mesh a .geo start the mesher server first: a fork, before MPI and any
  // thread (gmsh_session.h); it saves the mesher program's start (loading gmsh's libraries again).
  const bool meshes = argc > 1 && cli::kMeshing.count(argv[1]);
  if (meshes) workbench::start_geo_mesher_server();
  fem_reference::configure_singleton_mpi();      // it sets the environment
  workbench::handle_interruptions("workbench");  // before any thread starts
  if (meshes) workbench::register_geo_mesher_server();
  // A file-size limit (`ulimit -f`) makes a write fail with EFBIG, reported as a failed write
  // (workbench/output_file.h), instead of killing the process; the scripts inherit it.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"Fast deformation models (agent load transfer, PBD angle bending) against a deal.II FEM reference"};
  app.require_subcommand(1);
  cli::Action action;
  cli::add_agent_command(app, action);
  cli::add_voxelize_command(app, action);
  cli::add_pbd_command(app, action);
  cli::add_fem_command(app, action);
  cli::add_compare_command(app, action);
  cli::add_front_command(app, action);
  cli::add_calibrate_command(app, action);
  cli::add_case_command(app, action);
  cli::add_summarize_command(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "workbench: error: command line: " << e.what() << " (see workbench --help)\n";
    return 2;
  }
  const std::string subcommand = app.get_subcommands().front()->get_name();
  try {
    if (!fem_reference::started_by_launcher() || fem_reference::mpi_size() == 1) return action();
    // More than one rank: every rank leaves with rank 0's exit code.
    int code = 0;
    if (cli::kDistributed.count(subcommand)) {
      code = action();
    } else {
      if (fem_reference::mpi_rank() == 0)
        std::cerr << subcommand << ": " << fem_reference::mpi_size() << " ranks: runs once, on rank 0 (not distributed)\n";
      fem_reference::mpi_on_root([&] { code = action(); });
    }
    return std::stoi(fem_reference::mpi_broadcast(std::to_string(code)));
  } catch (const fem_reference::CollectiveError& e) {  // every rank has it: printed once
    if (!fem_reference::started_by_launcher() || fem_reference::mpi_rank() == 0) std::cerr << "workbench: error: " << e.what() << "\n";
    return 2;
  } catch (const workbench::Error& e) {
    std::cerr << "workbench: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "workbench: error: " << e.what() << "\n";
    return 3;
  }
}
