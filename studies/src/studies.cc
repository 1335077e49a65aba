// The front doors (studies.h): check, read, stage, run, write, commit, in that order for every module.
#include <studies/studies.h>

#include <compare/calibration_study.h>
#include <fem_reference/fem_case.h>
#include <fem_reference/mpi.h>
#include <schema/every_section.h>
#include <workbench/staged_directory.h>
#include <workbench/study_setup.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <ostream>
#include <utility>

namespace studies {

namespace fs = std::filesystem;

namespace {

/// The output folder of a one-rank study: staged, written by `write(staging path)`, moved into
/// place whole; returns the target.
template <class Write>
fs::path write_staged(const fs::path& folder, const workbench::CaseFile& file, Write write) {
  workbench::StagedDirectory staged(folder, file.path());
  write(staged.path());
  staged.commit();
  return staged.target();
}

/// The output folder of a distributed study: rank 0 stages it (a collective step: a refusal ends
/// every rank), every rank runs `write(staging path)` (each writes its VTU piece into it), rank 0
/// moves it into place; returns the target on rank 0, empty on the others.
template <class Write>
fs::path write_staged_on_rank_0(const fs::path& folder, const workbench::CaseFile& file, Write write) {
  const bool root = fem_reference::mpi_rank() == 0;
  std::unique_ptr<workbench::StagedDirectory> staged;
  fem_reference::mpi_collective([&] {
    if (root) staged = std::make_unique<workbench::StagedDirectory>(folder, file.path());
  });
  write(fs::path(fem_reference::mpi_broadcast(root ? staged->path().string() : std::string())));
  fs::path target;
  fem_reference::mpi_on_root([&] {
    staged->commit();
    target = staged->target();
  });
  return target;
}

/// The longest side of the FEM mesh's bounding box [m].
double longest_side(const fem_reference::FemResult& r) {
  double longest = 0;
  for (int a = 0; a < 3; ++a) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (std::size_t n = 0; n < r.node_count(); ++n) {
      lo = std::min(lo, r.node_points[3 * n + a]);
      hi = std::max(hi, r.node_points[3 * n + a]);
    }
    longest = std::max(longest, hi - lo);
  }
  return longest;
}

}  // namespace

agent_study::AgentStudy open_agent_study(const workbench::CaseFile& file) {
  schema::check_every_section(file);
  return agent_study::load_agent_study(file);
}

AgentRun run_agent_study(const workbench::CaseFile& file, const fs::path& folder, std::ostream& log) {
  AgentRun run{open_agent_study(file), {}, {}};
  run.folder = write_staged(folder, file, [&](const fs::path& dir) { run.steps = agent_study::write_agent_outputs(run.study, dir, log); });
  return run;
}

fem_reference::FemProblem open_fem_study(const workbench::CaseFile& file) {
  fem_reference::FemProblem problem;
  fem_reference::mpi_collective([&] {
    schema::check_every_section(file);
    problem = fem_reference::problem_from_case(file);
  });
  return problem;
}

void check_fem_study(const workbench::CaseFile& file) { fem_reference::check_fem_problem(open_fem_study(file)); }

FemRun run_fem_study(const workbench::CaseFile& file, const fs::path& folder, std::ostream& log) {
  const auto problem = open_fem_study(file);
  FemRun run;
  run.folder = write_staged_on_rank_0(folder, file, [&](const fs::path& dir) {
    run.result = fem_reference::solve_fem(problem, dir, &log);
    fem_reference::mpi_on_root([&] {
      if (const auto w = workbench::body_size_warning(problem.mesh_file, problem.mesh_unit, longest_side(run.result));
          !w.empty())
        log << "fem: warning: " << w << "\n";
      fem_reference::write_fem_csv(run.result, dir);
    });
  });
  return run;
}

pbd_study::PbdStudy open_pbd_study(const workbench::CaseFile& file) {
  schema::check_every_section(file);
  return pbd_study::load_pbd_study(file, pbd_study::read_pbd_case(file));
}

fs::path run_pbd_study(const workbench::CaseFile& file, const fs::path& folder, bool animate, std::ostream& log) {
  auto study = open_pbd_study(file);
  return write_staged(folder, file, [&](const fs::path& dir) { pbd_study::write_pbd_outputs(study, dir, animate, log); });
}

void open_compare_study(const workbench::CaseFile& file) {
  fem_reference::mpi_collective([&] { schema::check_every_section(file); });
}

std::vector<std::string> check_compare_study(const workbench::CaseFile& file) {
  open_compare_study(file);
  return compare::check_compare(file);
}

CompareRun run_compare_study(const workbench::CaseFile& file, const fs::path& folder, std::ostream& log) {
  open_compare_study(file);
  CompareRun run;
  run.folder = write_staged_on_rank_0(folder, file, [&](const fs::path& dir) { run.outcome = compare::run_compare(file, dir, log); });
  return run;
}

void open_front_study(const workbench::CaseFile& file) {
  compare::require_one_rank(file);
  schema::check_every_section(file);
}

FrontRun run_front_study(const workbench::CaseFile& file, const fs::path& folder, std::ostream& log) {
  open_front_study(file);
  FrontRun run;
  run.folder = write_staged_on_rank_0(folder, file, [&](const fs::path& dir) { run.outcome = compare::run_front(file, dir, log); });
  return run;
}

CalibrateRun run_calibrate_study(const workbench::CaseFile& file, const fs::path& folder, std::ostream& log) {
  CalibrateRun run;
  run.folder = write_staged_on_rank_0(folder, file, [&](const fs::path& dir) { run.result = compare::run_calibration(file, dir, log); });
  return run;
}

}  // namespace studies
