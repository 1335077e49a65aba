#pragma once
// Each subcommand of the `workbench` program registers itself here; main() only dispatches.
#include <CLI/CLI.hpp>
#include <workbench/case_file.h>

#include <functional>

namespace cli {

/// A case file describes one study for every model, so each subcommand reads (and so checks) the
/// [agent], [fem] and [compare] sections too, then rejects whatever no module knows.
void check_every_section(const workbench::CaseFile& file);

/// A subcommand's action, run after parsing; returns the exit code.
using Action = std::function<int()>;

void add_agent_command(CLI::App& app, Action& action);
void add_voxelize_command(CLI::App& app, Action& action);
void add_pbd_command(CLI::App& app, Action& action);
void add_fem_command(CLI::App& app, Action& action);
void add_compare_command(CLI::App& app, Action& action);
void add_calibrate_command(CLI::App& app, Action& action);

}  // namespace cli
