#pragma once
// Each subcommand of the `workbench` program registers itself here; main() only dispatches.
#include <CLI/CLI.hpp>
#include <schema/every_section.h>
#include <workbench/case_file.h>
#include <workbench/staged_directory.h>

#include <filesystem>

#include <functional>
#include <iosfwd>
#include <memory>
#include <set>
#include <string>

namespace cli {

/// Every section of a case file checked, unknown keys refused (schema/every_section.h).
using schema::check_every_section;

/// `--check`: read the case file, check every section (and, but for compare, load the model's
/// study, mesh included), write nothing.
inline constexpr const char* kCheckHelp = "only check the case file (every section) and write nothing";
/// Says the case file was checked; returns exit code 0.
int checked(const workbench::CaseFile& file, const std::string& subcommand);

/// The case file at `path`; a folder or a missing file is one line naming it.
workbench::CaseFile read_case_file(const std::string& path);
/// The case file at `path` with every section checked, as one collective step (under MPI every
/// rank reads it, and bad input ends every rank with one line). `first`, when given, reads the
/// subcommand's own sections before the check of every section.
std::unique_ptr<workbench::CaseFile> read_checked_case(const std::string& path,
                                                       const std::function<void(const workbench::CaseFile&)>& first = {});

/// Refuses (one line naming `option`) a file that could not be written later: a folder, an
/// unwritable file, or one whose nearest existing parent is not a writable folder. Writes nothing.
void check_writable_file(const std::string& path, const std::string& option);

/// The output folder: `option` (-o) when given, else out/<case name>/<subcommand>.
std::string output_folder(const std::string& option, const workbench::CaseFile& file, const std::string& subcommand);

/// A subcommand's action, run after parsing; returns the exit code.
using Action = std::function<int()>;

/// The subcommands that run distributed under mpirun (each rank runs the action; rank 0 writes);
/// main() runs every other one on rank 0 alone.
inline const std::set<std::string> kDistributed{"fem", "compare", "calibrate"};

/// The subcommands that may mesh a .geo: main() starts the mesher server for them, before MPI and
/// any thread (gmsh_session.h).
inline const std::set<std::string> kMeshing{"agent", "voxelize", "pbd", "fem", "compare", "calibrate"};

/// The output folder `dir` staged by rank 0 (a collective step: a refusal ends every rank), null on
/// the other ranks; `path` is set to the staging folder's path on every rank.
std::unique_ptr<workbench::StagedDirectory> stage_on_rank_0(const std::string& dir, const workbench::CaseFile& file,
                                                            std::filesystem::path& path);

/// Where a distributed subcommand's progress goes: standard error on rank 0, nowhere on the others.
std::ostream& progress_log();

void add_agent_command(CLI::App& app, Action& action);
void add_voxelize_command(CLI::App& app, Action& action);
void add_pbd_command(CLI::App& app, Action& action);
void add_fem_command(CLI::App& app, Action& action);
void add_compare_command(CLI::App& app, Action& action);
void add_calibrate_command(CLI::App& app, Action& action);
void add_case_command(CLI::App& app, Action& action);
void add_summarize_command(CLI::App& app, Action& action);

}  // namespace cli
