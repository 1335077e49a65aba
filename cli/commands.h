#pragma once
// Each subcommand of the `workbench` program registers itself here; main() only dispatches.
#include <CLI/CLI.hpp>

#include <functional>

namespace cli {

/// A subcommand's action, run after parsing; returns the exit code.
using Action = std::function<int()>;

void add_agent_command(CLI::App& app, Action& action);
void add_pbd_command(CLI::App& app, Action& action);
void add_fem_command(CLI::App& app, Action& action);
void add_compare_command(CLI::App& app, Action& action);
void add_calibrate_command(CLI::App& app, Action& action);

}  // namespace cli
