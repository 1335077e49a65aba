#pragma once
// What every ladder of the front shares (front.cc: the agents' and the FEM's; pbd_front.cc: the
// PBD's and the FEM strip's): a point timed, a rung run or left out with the reason. Private to
// the compare library.
#include <compare/front.h>
#include <schema/front_options.h>

#include "report.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <ostream>
#include <string>
#include <vector>

namespace compare {

/// `runs` timed calls of `work` after one warm-up (the warm-up's result is the caller's): each
/// call returns the seconds of it that are not the model's work (meshing); min and median kept.
template <class Work>
void time_runs(int runs, FrontPoint& p, Work work) {
  std::vector<double> seconds;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const double not_counted = work();
    seconds.push_back(report::seconds_since(t0) - not_counted);
  }
  std::sort(seconds.begin(), seconds.end());
  p.seconds_min = seconds.front();
  const std::size_t n = seconds.size();
  p.seconds_median = n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
}

/// Runs one ladder point, or says on the log and in `skipped` why it was left out; logs the
/// point's `headline` error.
template <class Run>
void add_point(FrontOutcome& out, std::ostream& log, const std::string& what, const std::string& headline, Run run) {
  try {
    out.points.push_back(run());
    const auto& p = out.points.back();
    log << "front: " << p.label << ": min " << 1e3 * p.seconds_min << " ms, median " << 1e3 * p.seconds_median
        << " ms, " << headline << " " << p.errors.at(headline) << "\n" << std::flush;
  } catch (const std::exception& e) {  // a rung the geometry does not allow (a mesh that fails, a patch too small)
    out.skipped.push_back(what + ": " + e.what());
    log << "front: left out " << out.skipped.back() << "\n" << std::flush;
  }
}

/// Reads and checks what run_pbd_front reads before it runs anything (the strip, its load and
/// stiffness, front.cells_parameter, the gate's names); a workbench::Error when one is wrong.
void check_pbd_front(const workbench::CaseFile& file, const schema::FrontOptions& options);

/// The front of a PBD case (compare.model = "pbd"): the PBD rod at every substeps x iterations of
/// [front], the FEM strip at every size factor and degree, against the case's FEM strip.
FrontOutcome run_pbd_front(const workbench::CaseFile& file, const schema::FrontOptions& options,
                           const std::filesystem::path& dir, std::ostream& log);

}  // namespace compare
