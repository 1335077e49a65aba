#pragma once
// The agent model as a workbench study: case file -> mesh -> load steps -> VTU/PVD/CSV.
#include <agent/fields.h>
#include <agent/load_transfer.h>
#include <agent/mesh_import.h>
#include <agent/state.h>
#include <agent/stress_components.h>
#include <workbench/case_file.h>
#include <workbench/error.h>
#include <workbench/study_setup.h>
#include <workbench/vtk_output.h>

#include <filesystem>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace agent_study {

struct AgentStudy {
  std::filesystem::path case_file;  ///< for messages
  workbench::StudySetup setup;
  agent::ImportedMesh mesh;  ///< grid with the rigid groups set
  agent::Coefficients coefficients;
  agent::RuleSet rules = agent::RuleSet::Patent;
  agent::Readings readings;  ///< [agent] readings
  /// One per loaded face, at the full load, marching inward: a pull has the inward direction and a
  /// negative force (evaluate() carries it as a push and negates).
  std::vector<agent::EntryLoad> loads;
  std::vector<std::size_t> load_of;  ///< per entry load: its load (index in setup.loads)
  /// Per entry load: the rule set that carries it (`rules`; under "auto" the one chosen for its load)
  std::vector<agent::RuleSet> load_rules;
  /// Said before the run and kept in agent_summary.json (a body of implausible size: mesh.unit).
  std::vector<std::string> warnings;
  /// Under "auto": per load, the rule set chosen and why, one line each (the log, agent_summary.json).
  std::vector<std::string> choices;
};

/// `rule_set` of a table (one of the names of agent::kRuleSets), `fallback` when absent.
agent::RuleSet read_rule_set(const workbench::CaseTable& t, agent::RuleSet fallback);
/// Reads the [agent] section (docs/case-file.md) into coefficients (every row of
/// agent::kCoefficients) and a rule set.
void read_agent_section(const workbench::CaseTable& root, agent::Coefficients& k, agent::RuleSet& rules);

/// The case-file name of each reading (docs/case-file.md) and the flag it sets.
const std::vector<std::pair<std::string, bool agent::Readings::*>>& reading_names();
/// Every coefficient in effect (each row of agent::kCoefficients), by name, in table order: what
/// summaries and the Python module report.
std::vector<std::pair<std::string, double>> coefficient_values(const agent::Coefficients& k);

/// The names of the readings set in `r`, in reading_names() order.
std::vector<std::string> names_of(const agent::Readings& r);

/// Reads the key `readings` of table `t` ([agent] or [calibrate], docs/case-file.md): the names
/// of the seed readings to apply.
agent::Readings read_readings(const workbench::CaseTable& t, agent::RuleSet rules);

/// Fails at `t`.readings when a stress reading meets loads in more than one direction.
void check_readings_fit_loads(const AgentStudy& study, const workbench::CaseTable& t);

/// Reads the common setup and [agent], builds the mesh and the entry loads. Does not reject
/// unknown keys: the caller does, once every module has read its sections. A mesh this process
/// imported before from the same file (the same bytes) and parameters is copied, not meshed
/// again (load steps, calibration trial points and Python calls that change only loads or
/// coefficients reuse the grid); a .geo that reads other files is meshed every time.
AgentStudy load_agent_study(const workbench::CaseFile& file);

/// The meshes this process has imported (meshed or read, not copied from an earlier import).
std::size_t mesh_imports();

/// Everything the agent model gives for one load state (agent/state.h).
using AgentState = agent::AgentState;

/// The cyclic transfer (readings 2 and 6) stopped at its cap: the case's coefficients keep too
/// much load in transit. Bad input (a workbench::Error naming the case file and agent.gamma); a
/// calibration refuses such a point instead.
struct TransferDidNotEnd : workbench::Error {
  using workbench::Error::Error;
};

/// The study's agent model: one agent::LoadTransfer per rule set that carries some of its loads
/// (one, unless the rule set is "auto"), and which loads each carries.
struct StudyModel {
  std::vector<agent::LoadTransfer> parts;
  std::vector<agent::RuleSet> load_rules;  ///< per entry load (AgentStudy::loads): its part's rule set
};

/// The study's agent model: its grid, material and readings with coefficients `k` under `rules`
/// (a calibration's trial point), by default the study's own. Throws std::invalid_argument for
/// coefficients the rule set refuses (under "auto": those the directional rule set reads).
StudyModel transfer_model(const AgentStudy& study, const agent::Coefficients& k, agent::RuleSet rules);
inline StudyModel transfer_model(const AgentStudy& study) { return transfer_model(study, study.coefficients, study.rules); }

/// The stress components the study's model models and whether its fields include a closed-form
/// layer: its rule set's, under "auto" the union over the rule sets it chose (each under its loads).
agent::StressModel stress_model(const AgentStudy& study);

/// The magnitude of the load entering the body at `factor` [N]: the sum over the entry loads,
/// pushes and pulls alike. At factor 1 (the full load) it is the relative threshold's base
/// (Coefficients::gamma_for) at every load step.
double entering_load(const AgentStudy& study, double factor);

/// agent::solve_state of the study's loads scaled by `factor` (a load step) under its stress
/// readings; throws TransferDidNotEnd at the cyclic transfer's cap.
/// Under "auto" each part carries its own loads and their states superpose (agent::superpose).
AgentState evaluate(const AgentStudy& study, StudyModel& model, double factor);

/// A run whose rigid faces return less than this share of the applied load warns (on the log and
/// in agent_summary.json): the method's answer stands, but a model that loses load says so.
constexpr double kWarnBelowReactionShare = 0.9;

/// The load-balance warnings of one solve: empty when at least `min_share` of the applied load
/// reaches a rigid face; otherwise one sentence saying where the rest went.
std::vector<std::string> load_balance_warnings(const agent::Diagnostics& d, double min_share = kWarnBelowReactionShare);

/// The resultant of the entry loads scaled by `factor`, per axis [N] (loads in different
/// directions do not add up to their sum of magnitudes, Diagnostics::applied).
Eigen::Vector3d load_vector(const AgentStudy& study, double factor);

/// Writes agent_step_NNN.vtu per step, agent.pvd, agent_cells.csv and agent_nodes.csv (full
/// load), agent_diagnostics.csv (per step) and agent_summary.json (the full load's balance and
/// warnings) into `dir`, reporting progress and warnings on `log`. Returns the state at each step
/// (the last is the full load), so that nobody solves them again.
std::vector<AgentState> write_agent_outputs(const AgentStudy& study, const std::filesystem::path& dir, std::ostream& log);

/// The grid as an output mesh: all nodes, cells in the mesh's element order.
workbench::OutputMesh output_mesh(const AgentStudy& study);

}  // namespace agent_study
