#pragma once
// Each subcommand of the `workbench` program registers itself here; main() only dispatches.
// The study itself is behind each module's front door (studies/studies.h), shared with Python.
#include <CLI/CLI.hpp>
#include <workbench/case_file.h>

#include <functional>
#include <iosfwd>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace cli {

/// `--check`: read the case file and open the model's study (studies::open_<module>_study: every
/// section checked, unknown keys refused, then, for agent and pbd, the mesh), write nothing.
inline constexpr const char* kCheckHelp = "only check the case file (every section) and write nothing";
/// Says the warnings the run would give before it runs ("SUBCOMMAND: warning: ...") and that the
/// case file was checked; returns exit code 0.
int checked(const workbench::CaseFile& file, const std::string& subcommand, const std::vector<std::string>& warnings = {});

/// The case file at `path`; a folder or a missing file is one line naming it.
workbench::CaseFile read_case_file(const std::string& path);
/// The same as one collective step, for the distributed subcommands: under MPI every rank reads
/// it, and bad input ends every rank with one line.
std::unique_ptr<workbench::CaseFile> read_case_file_on_every_rank(const std::string& path);

/// Refuses (one line naming `option`) a file that could not be written later: a folder, an
/// unwritable file, or one whose nearest existing parent is not a writable folder. Writes nothing.
void check_writable_file(const std::string& path, const std::string& option);

/// The output folder: `option` (-o) when given, else out/<case name>/<subcommand>.
std::string output_folder(const std::string& option, const workbench::CaseFile& file, const std::string& subcommand);

/// A subcommand's action, run after parsing; returns the exit code.
using Action = std::function<int()>;

/// The subcommands that run distributed under mpirun (each rank runs the action; rank 0 writes);
/// main() runs every other one on rank 0 alone.
inline const std::set<std::string> kDistributed{"fem", "compare", "calibrate", "front"};

/// The subcommands that may mesh a .geo: main() starts the mesher server for them, before MPI and
/// any thread (gmsh_session.h).
inline const std::set<std::string> kMeshing{"agent", "voxelize", "pbd", "fem", "compare", "calibrate", "front"};

/// Where a distributed subcommand's progress goes: standard error on rank 0, nowhere on the others.
std::ostream& progress_log();

void add_agent_command(CLI::App& app, Action& action);
void add_voxelize_command(CLI::App& app, Action& action);
void add_pbd_command(CLI::App& app, Action& action);
void add_fem_command(CLI::App& app, Action& action);
void add_compare_command(CLI::App& app, Action& action);
void add_calibrate_command(CLI::App& app, Action& action);
void add_front_command(CLI::App& app, Action& action);
void add_case_command(CLI::App& app, Action& action);
void add_summarize_command(CLI::App& app, Action& action);

}  // namespace cli
