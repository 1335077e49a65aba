#pragma once
// The agent comparison's inside (compare_study.cc runs it in steps; compare_files.cc writes its
// files): its inputs, what it samples from where, and the files of step 5.
#include <compare/compare_study.h>
#include <compare/metrics.h>
#include <compare/reference.h>

#include <agent_study.h>
#include <fem_reference/fem.h>

#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace compare::agent_compare {

/// Step 1: the inputs.
struct AgentCompareInput {
  agent_study::AgentStudy study;
  fem_reference::FemProblem problem;
  std::vector<LoadFrame> loads;
  std::vector<Line> lines;  ///< each load's lines, then the user's
  NearLoad near;            ///< cells and nodes left out of the far field
  double far_distance = 0;  ///< [m]
  ReferenceOptions reference;  ///< resolved for the mesh's dimension
  /// The same-body check's, said before the run and kept in summary.json.
  std::vector<std::string> warnings;
  /// The stress components the rule set models, whether its fields include closed-form layers.
  agent::StressModel stress_model;
};

/// Step 1: reads and checks the case (`options` already read): the study, its FEM problem, the
/// loads' frames, the lines, the far field; gate names checked, unknown keys refused; with a
/// reference on another mesh, the two meshes checked to be the same body (compare/same_body.h).
AgentCompareInput read_input(const workbench::CaseFile& file, const CompareOptions& options);

// Steps 5 and 7: what a comparison samples, from where.
/// The fields compared: the agent model, the reference, the reference's second level (for its own
/// error) and, beside a true-geometry reference, FEM on the agents' staircase mesh (else null).
struct Sources {
  const GridFields* agent = nullptr;
  const GridFields* reference = nullptr;
  const GridFields* estimate = nullptr;
  const GridFields* staircase = nullptr;
};
/// One field's values in a scope, per source (empty where the source is not sampled).
struct Samples {
  std::vector<double> agent, reference, estimate, staircase;
};
/// A scope's values of each field of kFields (empty for a field not compared in the grid's dimension).
using ScopeSamples = std::array<Samples, std::size(kFields)>;
/// Step 7: the metrics of the body's cells and nodes (box order) and the far field's, every field
/// of kFields: the agent source's errors against the reference, each with the estimate's beside it
/// (air counts in neither scope).
void add_field_scopes(CompareOutcome& out, const AgentCompareInput& in, const Sources& sources, double mask);
/// Whether the metric `name` ("far.sigma_y.rel_l2") scores a field `model` models in `dim`: false
/// for a stress component its rule set leaves at zero (agent::StressModel), true for the rest.
bool models_metric(const std::string& name, const agent::StressModel& model, int dim);
/// Each source with where its samples go.
inline const std::pair<const GridFields* Sources::*, std::vector<double> Samples::*> kSources[] = {
    {&Sources::agent, &Samples::agent},
    {&Sources::reference, &Samples::reference},
    {&Sources::estimate, &Samples::estimate},
    {&Sources::staircase, &Samples::staircase}};

/// The name of a stress slot in kFields ("tau_xy").
inline std::string stress_name(int slot) {
  for (const auto& f : kFields)
    if (!f.per_node && f.slot == slot) return f.name;
  return "stress";
}

/// Per sample of `line` in the body (Line::body_samples), the piece of the body it lies on: 0 from
/// the line's start, one more after each stretch of air the line crosses (a plot breaks there).
std::vector<int> line_segments(const Line& line);

/// lines.csv: both models along every line (with each sample's segment), every field of kFields
/// component by component.
void write_lines_csv(const std::filesystem::path& file, const agent::Grid& grid, const std::vector<Line>& lines,
                     const std::vector<ScopeSamples>& samples);
/// compare.vtu, cells.csv and nodes.csv: both models per cell and per node.
void write_field_files(const std::filesystem::path& dir, const AgentCompareInput& in, const GridFields& agent,
                       const GridFields& fem, const agent_study::AgentState& state, double mask);
/// The fields of cells.csv, nodes.csv and lines.csv, in their rows' order, in memory (ComparedFields).
ComparedFields compared_fields(const AgentCompareInput& in, const GridFields& agent, const GridFields& fem,
                               const agent_study::AgentState& state, double mask, const std::vector<ScopeSamples>& samples);
/// steps.csv: the agent's sigma per cell at every load step (the animation's data).
void write_steps_csv(const std::filesystem::path& file, const agent_study::AgentStudy& study,
                     const std::vector<agent_study::AgentState>& states);
/// lines.json: each line's name, description, kind, ends and the arc lengths [m] where each of its
/// segments in the body starts and ends.
nlohmann::json lines_json(const std::vector<Line>& lines);

}  // namespace compare::agent_compare
