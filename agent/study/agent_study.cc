// The agent model as a workbench study: case file -> grid and loads -> VTU/PVD/CSV/JSON output.
#include "agent_study.h"

#include "carry_check.h"

#include <workbench/csv_file.h>
#include <workbench/error.h>
#include <workbench/output_file.h>
#include <workbench/vtk_output.h>

#include <agent/voxelize.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <list>
#include <map>
#include <mutex>
#include <ostream>
#include <sstream>

namespace agent_study {

namespace fs = std::filesystem;
using workbench::Error;
using workbench::Range;

namespace {

/// The meshes this process imported, by file (its path and bytes) and parameters: a study opened
/// again on the same mesh (a Python call with other loads or coefficients, a front's or a
/// calibration's case read again) copies its grid from here instead of meshing again, a tenth of
/// a 2 mm seed plate's call. A file that may read others (a .geo's Merge, Include, ...) is
/// imported every time: its own bytes do not say what it reads. The last kMeshCacheSize imports
/// are kept, none larger than kMeshCacheBytes.
class MeshCache {
 public:
  agent::ImportedMesh get(const workbench::StudySetup& setup) {
    const auto& file = setup.mesh_file;
    const auto& parameters = setup.mesh_parameters;
    std::string bytes = read_bytes(file);
    const bool keep = !reads_other_files(bytes);
    const std::array<double, 2> how{setup.mesh_unit, setup.agent_size};
    if (keep) {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (it->file == file && it->parameters == parameters && it->how == how && it->bytes == bytes) {
          entries_.splice(entries_.begin(), entries_, it);  // most recent first
          return it->mesh;
        }
    }
    // With [mesh] agent_size the file is the true geometry, voxelized here (agent/voxelize.h).
    auto mesh = setup.agent_size > 0 ? agent::voxelize(file, setup.agent_size, parameters, {}, setup.mesh_unit)
                                     : agent::import_mesh(file, parameters, setup.mesh_unit);
    const std::lock_guard<std::mutex> lock(mutex_);
    ++imports_;
    if (!keep || bytes_of(mesh) + bytes.size() > kMeshCacheBytes) return mesh;
    entries_.push_front({file, parameters, how, std::move(bytes), mesh});
    if (entries_.size() > kMeshCacheSize) entries_.pop_back();
    return mesh;
  }
  std::size_t imports() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return imports_;
  }

 private:
  static constexpr std::size_t kMeshCacheSize = 4;
  static constexpr std::size_t kMeshCacheBytes = std::size_t(64) << 20;
  struct Entry {
    fs::path file;
    std::map<std::string, double> parameters;
    std::array<double, 2> how;  ///< the unit and the agent size
    std::string bytes;
    agent::ImportedMesh mesh;
  };
  static std::string read_bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // gmsh's commands that read another file (a .geo's; a .msh names none of them)
  static bool reads_other_files(const std::string& bytes) {
    for (const char* command : {"Merge", "Include", "ShapeFromFile", "Import"})
      if (bytes.find(command) != std::string::npos) return true;
    return false;
  }
  static std::size_t bytes_of(const agent::ImportedMesh& m) {
    std::size_t faces = 0;
    for (const auto& [name, group] : m.face_groups) faces += group.size();
    return m.grid.flags.size() + m.grid.tiles.memory_bytes() + sizeof(std::size_t) * m.cell_of_element.size() +
           sizeof(agent::BoundaryFace) * faces;
  }
  std::mutex mutex_;
  std::list<Entry> entries_;
  std::size_t imports_ = 0;
};

MeshCache& mesh_cache() {
  static MeshCache cache;
  return cache;
}

/// Keys whose unit changed: refused with the new key, so that an old case is not read in the wrong unit.
void refuse_renamed_keys(const workbench::CaseTable& t) {
  t.refuse_renamed("diffusion", "diffusion_length", "in metres: diffusion [mm] / 1000");
}
}  // namespace

agent::RuleSet read_rule_set(const workbench::CaseTable& t, agent::RuleSet fallback) {
  std::vector<std::string> names;
  for (agent::RuleSet r : agent::kRuleSets) names.push_back(agent::rule_set_name(r));
  return *agent::rule_set_named(t.text("rule_set", agent::rule_set_name(fallback), names));
}

void read_agent_section(const workbench::CaseTable& root, agent::Coefficients& k, agent::RuleSet& rules) {
  const auto t = root.table("agent");
  rules = read_rule_set(t, agent::RuleSet::Auto);  // a case that names none: the rule set that carries each load
  // Every coefficient from the one table (agent/coefficients.h), at the library's defaults.
  const agent::CoefficientSpec* named_threshold = nullptr;
  for (const auto& c : agent::kCoefficients) {
    if (c.optional && !t.has(c.name)) continue;  // unset: poisson_decay follows alpha2
    if (c.choices) {  // a named choice (paths): the name in the file, its index in the table
      const std::vector<std::string> names(c.choices, c.choices + c.choice_count);
      const auto name = t.text(c.name, names[std::size_t(c.default_value())], names);
      c.set(k, double(std::find(names.begin(), names.end(), name) - names.begin()));
      continue;
    }
    if (c.acts) {  // a threshold's key selects its kind: only a named one is read
      if (!t.has(c.name)) continue;
      if (named_threshold)
        t.fail(c.name, std::string("name one threshold: ") + named_threshold->name + " is given too (" +
                           named_threshold->name + " or " + c.name + ", docs/case-file.md)");
      named_threshold = &c;
    }
    if (c.integer) {
      c.set(k, t.integer(c.name, int(c.default_value()), int(c.min), int(c.max)));
      continue;
    }
    const double v = t.number(c.name, c.optional ? std::nullopt : std::optional<double>(c.default_value()),
                              Range{c.min, c.max, c.min_open, c.max_open});
    c.set(k, v);
  }
  refuse_renamed_keys(t);
  try {
    agent::check_coefficients(k, rules);  // what a rule set needs beyond the ranges
  } catch (const agent::CoefficientError& e) {
    t.fail(e.key, e.problem);
  }
}

const std::vector<std::pair<std::string, bool agent::Readings::*>>& reading_names() {
  static const std::vector<std::pair<std::string, bool agent::Readings::*>> names = {
      {"non_compounding_entry", &agent::Readings::non_compounding_entry},
      {"entering_face_stress", &agent::Readings::entering_face_stress},
      {"lateral_strain_stress", &agent::Readings::lateral_strain_stress},
      {"every_agent_all_operations", &agent::Readings::every_agent_all_operations},
      {"boundaries_return", &agent::Readings::boundaries_return}};
  return names;
}

std::vector<std::pair<std::string, double>> coefficient_values(const agent::Coefficients& k) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& c : agent::kCoefficients) out.emplace_back(c.name, c.get(k));
  return out;
}

std::vector<std::string> names_of(const agent::Readings& r) {
  std::vector<std::string> out;
  for (const auto& [name, member] : reading_names())
    if (r.*member) out.push_back(name);
  return out;
}

agent::Readings read_readings(const workbench::CaseTable& t, agent::RuleSet rules) {
  agent::Readings r;
  const auto& names = reading_names();
  for (const auto& name : t.texts("readings", std::vector<std::string>{})) {
    const auto it = std::find_if(names.begin(), names.end(), [&](const auto& n) { return name == n.first; });
    if (it == names.end())
      t.fail("readings", "unknown reading \"" + name +
                             "\" (known: non_compounding_entry, entering_face_stress, lateral_strain_stress, "
                             "every_agent_all_operations, boundaries_return)");
    r.*(it->second) = true;
  }
  if (r.non_compounding_entry && rules != agent::RuleSet::Patent)
    t.fail("readings", "non_compounding_entry is a reading of the patent rule set");
  if (r.cyclic() && rules != agent::RuleSet::Patent)
    t.fail("readings", "every_agent_all_operations and boundaries_return are readings of the patent rule set");
  if (r.any() && rules == agent::RuleSet::Columns)
    t.fail("readings", "entering_face_stress and lateral_strain_stress read face forces: the columns rule set gives its stresses itself");
  if (r.any() && rules == agent::RuleSet::Auto)
    t.fail("readings", "the auto rule set chooses directional or columns per load: the readings are the patent and "
                       "directional rule sets' (name one of them)");
  return r;
}

void check_readings_fit_loads(const AgentStudy& study, const workbench::CaseTable& t) {
  const bool stress_readings = study.readings.entering_face_stress || study.readings.lateral_strain_stress;
  for (const auto& l : study.loads)
    if (stress_readings && l.dir != study.loads.front().dir)
      t.fail("readings", "entering_face_stress and lateral_strain_stress need every load in one direction");
}

namespace {

/// Per entry load of `study`, the rule set `carry` gives its load and marching direction.
std::vector<agent::RuleSet> rules_per_entry_load(const AgentStudy& study, const std::vector<LoadCarry>& carry) {
  std::vector<agent::RuleSet> out(study.loads.size(), study.rules);
  for (const auto& c : carry)
    for (std::size_t k = 0; k < study.loads.size(); ++k)
      if (study.load_of[k] == c.load && study.loads[k].dir == c.inward) out[k] = c.rules;
  return out;
}

/// Under "auto": each load's rule set (carry_check); a load no rule set carries is refused.
void choose_rule_sets(AgentStudy& study) {
  const auto carry = carry_check(study);
  for (const auto& c : carry) {
    if (c.refused())
      throw Error(study.case_file.string() + ": " + study.setup.loads[c.load].key() +
                  ": no rule set carries it (agent.rule_set = \"auto\"): " + c.why);
    study.choices.push_back(c.describe(study));
  }
  study.load_rules = rules_per_entry_load(study, carry);
}

/// The entry loads whose rule set is `r` (`rules`: per entry load).
std::vector<agent::EntryLoad> loads_carried_by(const AgentStudy& study, const std::vector<agent::RuleSet>& rules,
                                               agent::RuleSet r) {
  std::vector<agent::EntryLoad> out;
  for (std::size_t k = 0; k < study.loads.size(); ++k)
    if (rules[k] == r) out.push_back(study.loads[k]);
  return out;
}

}  // namespace

AgentStudy load_agent_study(const workbench::CaseFile& file) {
  AgentStudy study;
  study.case_file = file.path();
  const auto root = file.root();
  study.setup = workbench::read_study_setup(root);
  read_agent_section(root, study.coefficients, study.rules);
  study.readings = read_readings(root.table("agent"), study.rules);
  try {
    study.mesh = mesh_cache().get(study.setup);
  } catch (const std::runtime_error& e) {
    throw Error(e.what());
  }
  double longest = 0;  // the box's longest side [m]
  for (int a = 0; a < study.mesh.grid.dim; ++a)
    longest = std::max(longest, study.mesh.grid.plane(a, study.mesh.grid.cells[a]) - study.mesh.grid.plane(a, 0));
  if (auto w = workbench::body_size_warning(study.setup.mesh_file, study.setup.mesh_unit, longest); !w.empty()) study.warnings.push_back(w);
  std::vector<std::string> groups;
  for (const auto& [name, faces] : study.mesh.face_groups) groups.push_back(name);
  workbench::check_groups_exist(file, study.setup, groups);

  if (study.setup.loads.empty())
    root.fail("load", "missing (the agent method needs at least one [[load]] table with group, direction and force)");
  if (!study.setup.roller_groups.empty())
    root.table("boundary").fail("rollers", "the agent method knows rigid and free faces only (rollers are FEM-only)");
  auto& grid = study.mesh.grid;
  grid.thickness = study.setup.thickness;
  bool any_rigid = false;
  for (const auto& g : study.setup.rigid_groups) {
    grid.set_boundary(study.mesh.face_groups.at(g), agent::Boundary::Rigid);
    any_rigid = any_rigid || !study.mesh.face_groups.at(g).empty();
  }
  if (!any_rigid)
    root.table("boundary").fail("rigid", "no rigid faces: the agent method needs a rigid boundary to return the load");
  for (std::size_t i = 0; i < study.setup.loads.size(); ++i) {
    const auto& spec = study.setup.loads[i];
    const std::string key = spec.key();
    if (spec.axis >= grid.dim)
      throw Error(file.path().string() + ": " + key + ".direction: " + spec.direction_name() + " is not an axis of a " +
                  std::to_string(grid.dim) + "D mesh");
    const auto& faces = study.mesh.face_groups.at(spec.group);
    if (faces.empty()) throw Error(file.path().string() + ": " + key + ".group: group '" + spec.group + "' has no faces");
    double area = 0;
    for (const auto& f : faces) area += grid.face_area(agent::axis_of(f.side));
    // A load along a face's normal marches inward (docs/agent-model.md, "Tension"): a push with its
    // force, a pull with the force negated (evaluate() carries it as the push and negates). A load
    // along the face (tangential) marches in its own direction.
    const int dir = agent::direction(spec.axis, spec.sign > 0);
    for (const auto& f : faces) {
      const double share = spec.force * grid.face_area(agent::axis_of(f.side)) / area;
      const bool pull = dir == f.side;  // the load points out of the body through its face
      study.loads.push_back({f.cell, pull ? agent::opposite(dir) : dir, pull ? -share : share});
      study.load_of.push_back(i);
    }
  }
  study.load_rules.assign(study.loads.size(), study.rules);
  if (study.rules == agent::RuleSet::Auto) choose_rule_sets(study);
  check_readings_fit_loads(study, root.table("agent"));
  if (study.rules == agent::RuleSet::Columns) {  // what the columns cannot carry is refused before the run
    try {
      agent::plan_columns(grid, study.loads);
    } catch (const std::invalid_argument& e) {
      root.table("agent").fail("rule_set", std::string("the columns rule set cannot carry the loads: ") + e.what());
    }
  }
  if (study.readings.cyclic()) {  // the cyclic transfer must end: gamma > 0, every factor below 1
    auto k = study.coefficients;
    k.gamma = k.gamma_for(entering_load(study, 1.0));  // the threshold the transfer drops loads by
    try {
      agent::check_cyclic(grid, {study.setup.young, study.setup.poisson}, k);
    } catch (const std::invalid_argument& e) {
      root.table("agent").fail(k.gamma > 0                                         ? "readings"
                               : k.threshold == agent::Threshold::Absolute ? "gamma"
                                                                            : "gamma_relative",
                               e.what());
    }
  }
  return study;
}

std::size_t mesh_imports() { return mesh_cache().imports(); }

double entering_load(const AgentStudy& study, double factor) {
  double sum = 0;
  for (const auto& l : study.loads) sum += std::abs(factor * l.force);
  return sum;
}

AgentState evaluate(const AgentStudy& study, StudyModel& model, double factor) {
  try {
    if (model.parts.size() == 1) return agent::solve_state(model.parts[0], study.loads, study.readings, factor);
    AgentState total;
    for (auto& part : model.parts)
      agent::superpose(total, agent::solve_state(part, loads_carried_by(study, model.load_rules, part.rules()),
                                                 study.readings, factor));
    return total;
  } catch (const agent::CyclicCapReached& e) {  // the case's coefficients, not a bug: bad input
    throw TransferDidNotEnd(study.case_file.string() + ": agent.gamma: " + e.what() +
                            "; raise gamma or lower alpha2, alpha3, poisson_decay (readings every_agent_all_operations, "
                            "boundaries_return: docs/agent-model.md)");
  }
}

workbench::OutputMesh output_mesh(const AgentStudy& study) {
  const auto& grid = study.mesh.grid;
  workbench::OutputMesh mesh;
  mesh.points.reserve(grid.node_count() * 3);
  for (std::size_t node = 0; node < grid.node_count(); ++node) {  // one point per node id (box order when dense)
    const auto n = grid.node_coords(node);  // a tiled grid's ids beyond the box: unused points, as air's
    const Eigen::Vector3d x = grid.node_position(n[0], n[1], n[2]);
    mesh.points.insert(mesh.points.end(), {x[0], x[1], x[2]});
  }
  for (std::size_t cell : study.mesh.cell_of_element) {
    const auto c = grid.coords(cell);
    auto n = [&](int di, int dj, int dk) { return (long long)grid.node_index(c[0] + di, c[1] + dj, c[2] + dk); };
    if (grid.dim == 2)
      mesh.add_cell(9, {n(0, 0, 0), n(1, 0, 0), n(1, 1, 0), n(0, 1, 0)});
    else
      mesh.add_cell(12, {n(0, 0, 0), n(1, 0, 0), n(1, 1, 0), n(0, 1, 0), n(0, 0, 1), n(1, 0, 1), n(1, 1, 1), n(0, 1, 1)});
  }
  return mesh;
}

namespace {

using agent::FieldPlace;
using agent::kStateFields;
using agent::StateField;
using agent::VtuLayout;

/// A field's VTU arrays, empty: one per component (Scalars) or one of named components.
void add_vtu_arrays(const StateField& f, int dim, std::vector<workbench::Field>& out) {
  const std::string unit = std::string(" [") + f.unit + "]";
  if (f.vtu == VtuLayout::Scalars) {
    for (int k = 0; k < f.components(dim); ++k) out.push_back({f.columns[k] + unit, 1, {}, {}, {}});
    return;
  }
  const int n = f.vtu == VtuLayout::Vector3 ? 3 : f.components(dim);
  std::vector<std::string> labels;
  for (int k = 0; k < n; ++k) labels.emplace_back(agent::vtu_label(f.columns[k]));
  out.push_back({f.name + unit, n, {}, labels, {}});
}

/// The VTU arrays of every field at `place`, in table order; `ids`: the agents (mesh element
/// order) or nodes to write.
std::vector<workbench::Field> vtu_fields(const AgentState& s, int dim, FieldPlace place, const std::vector<std::size_t>& ids) {
  std::vector<workbench::Field> fields;
  for (const auto& f : kStateFields) {
    if (f.place != place) continue;
    const std::size_t first = fields.size();
    add_vtu_arrays(f, dim, fields);
    const int n = f.components(dim);
    for (std::size_t at : ids)
      for (int k = 0; k < (f.vtu == VtuLayout::Vector3 ? 3 : n); ++k) {
        const double v = k < n ? f.read(s, at, k, dim) : 0.0;
        fields[f.vtu == VtuLayout::Scalars ? first + std::size_t(k) : first].values.push_back(v);
      }
  }
  return fields;
}

void check_finite(const std::vector<double>& v, const std::string& what) {
  for (double x : v)
    if (!std::isfinite(x)) throw Error("agent model produced a non-finite " + what);
}

/// Components [from, to) of every stress record finite.
void check_finite(const std::vector<workbench::SymmetricTensor>& v, int from, int to, const std::string& what) {
  for (const auto& r : v)
    for (int k = from; k < to; ++k)
      if (!std::isfinite(r[k])) throw Error("agent model produced a non-finite " + what);
}

using workbench::open_csv;

/// The CSV header's columns of every field at `place`, in table order.
void write_csv_header(workbench::CsvFile& out, int dim, FieldPlace place) {
  for (const auto& f : kStateFields)
    if (f.place == place)
      for (int k = 0; k < f.components(dim); ++k)
        out << ',' << f.columns[k] << (f.integer ? std::string() : std::string(" [") + f.unit + "]");
}

/// The CSV values of every field at `place` for agent or node `at`.
void write_csv_values(workbench::CsvFile& out, const AgentState& s, int dim, FieldPlace place, std::size_t at) {
  for (const auto& f : kStateFields)
    if (f.place == place)
      for (int k = 0; k < f.components(dim); ++k) {
        const double v = f.read(s, at, k, dim);
        if (f.integer)
          out << ',' << std::int64_t(v);
        else
          out << ',' << v;
      }
}

void write_cells_csv(const fs::path& file, const AgentStudy& study, const AgentState& s) {
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim;
  auto out = open_csv(file);
  out << "cell,x [m],y [m]" << (dim == 3 ? ",z [m]" : "");
  write_csv_header(out, dim, FieldPlace::Agent);
  out << '\n';
  for (std::size_t e = 0; e < study.mesh.cell_of_element.size(); ++e) {
    const std::size_t cell = study.mesh.cell_of_element[e];
    const Eigen::Vector3d x = grid.centre(cell);
    out << e;
    for (int a = 0; a < dim; ++a) out << ',' << x[a];
    write_csv_values(out, s, dim, FieldPlace::Agent, cell);
    out << '\n';
  }
  out.close();
}

void write_nodes_csv(const fs::path& file, const AgentStudy& study, const AgentState& s,
                     const workbench::OutputMesh& mesh) {
  const int dim = study.mesh.grid.dim;
  // Only the nodes of agents: a node of the box that touches air alone has no displacement.
  std::vector<char> of_agent(mesh.point_count(), 0);
  for (long long p : mesh.connectivity) of_agent[std::size_t(p)] = 1;
  auto out = open_csv(file);
  out << "node,x [m],y [m]" << (dim == 3 ? ",z [m]" : "");
  write_csv_header(out, dim, FieldPlace::Node);
  out << "\n";
  for (std::size_t node = 0; node < mesh.point_count(); ++node) {
    if (!of_agent[node]) continue;
    out << node;
    for (int a = 0; a < dim; ++a) out << ',' << mesh.points[3 * node + a];
    write_csv_values(out, s, dim, FieldPlace::Node, node);
    out << '\n';
  }
  out.close();
}

}  // namespace

std::vector<std::string> load_balance_warnings(const agent::Diagnostics& d, double min_share) {
  if (!(d.applied > 0) || d.rigid_reaction >= min_share * d.applied) return {};
  std::ostringstream s;
  s << "only " << 100 * d.rigid_reaction / d.applied << " % of the applied load " << d.applied
    << " N reaches a rigid face (warning below " << 100 * min_share << " %): passed out " << d.passed_out
    << " N, dropped under gamma " << d.dropped << " N, lost through the transfer coefficients " << d.lost << " N";
  if (d.returned_rigid + d.returned_free > 0)  // reading 6: nothing leaves the body
    s << " (boundaries_return: rigid faces returned " << d.returned_rigid << " N into the body, free faces "
      << d.returned_free << " N)";
  return {s.str()};
}

Eigen::Vector3d load_vector(const AgentStudy& study, double factor) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& l : study.loads) sum[agent::axis_of(l.dir)] += (agent::is_positive(l.dir) ? 1 : -1) * factor * l.force;
  return sum;
}

namespace {

void write_summary(const fs::path& file, const AgentStudy& study, const agent::Diagnostics& d,
                   const std::vector<std::string>& warnings) {
  const int dim = study.mesh.grid.dim;
  const Eigen::Vector3d v = load_vector(study, 1.0);
  nlohmann::json j;
  j["rule_set"] = agent::rule_set_name(study.rules);
  if (study.rules == agent::RuleSet::Auto) j["rule_set_choices"] = study.choices;
  j["readings"] = names_of(study.readings);
  for (const auto& [name, value] : coefficient_values(study.coefficients)) j["coefficients"][name] = value;
  j["threshold"] = {{"kind", agent::threshold_name(study.coefficients.threshold)},
                    {"gamma_in_effect", study.coefficients.gamma_for(entering_load(study, 1.0))}};
  j["load_vector"] = std::vector<double>(v.data(), v.data() + dim);
  j["load_balance"] = {{"applied", d.applied}, {"rigid_reaction", d.rigid_reaction}, {"passed_out", d.passed_out},
                       {"dropped", d.dropped}, {"lost", d.lost}, {"reaction_share", d.applied > 0 ? d.rigid_reaction / d.applied : 0.0},
                       {"warn_below_reaction_share", kWarnBelowReactionShare}};
  j["lateral"] = {{"reaction", d.lateral_reaction}, {"passed_out", d.lateral_passed_out}, {"dropped", d.lateral_dropped}};
  j["returned"] = {{"rigid", d.returned_rigid}, {"free", d.returned_free}};  // reading 6, in the body
  j["agents"] = study.mesh.cell_of_element.size();
  j["agents_generated"] = d.agents_generated;
  j["agent_updates"] = d.agent_updates;
  j["packet_moves"] = d.packet_moves;
  j["warnings"] = warnings;
  workbench::write_file(file, j.dump(2) + "\n");
}

}  // namespace

StudyModel transfer_model(const AgentStudy& study, const agent::Coefficients& k, agent::RuleSet rules) {
  const agent::Material material{study.setup.young, study.setup.poisson};
  StudyModel model;
  if (rules != agent::RuleSet::Auto) {
    model.parts.emplace_back(study.mesh.grid, material, k, rules, study.readings);
    model.load_rules.assign(study.loads.size(), rules);
    return model;
  }
  agent::check_coefficients(k, rules);  // auto's, whichever rule sets its loads take
  // A calibration of "auto" on a case that names another rule set chooses as the case would have.
  model.load_rules = study.rules == agent::RuleSet::Auto ? study.load_rules
                                                         : rules_per_entry_load(study, carry_check(study, rules));
  for (const auto r : agent::kRuleSets)
    if (std::find(model.load_rules.begin(), model.load_rules.end(), r) != model.load_rules.end())
      model.parts.emplace_back(study.mesh.grid, material, k, r, study.readings);
  return model;
}

agent::StressModel stress_model(const AgentStudy& study) {
  agent::StressModel model;
  for (const auto r : agent::kRuleSets) {
    const auto loads = loads_carried_by(study, study.load_rules, r);
    if (!loads.empty())
      model = model | agent::stress_model(study.mesh.grid, r, study.coefficients, study.readings, loads);
  }
  return model;
}

std::vector<AgentState> write_agent_outputs(const AgentStudy& study, const fs::path& dir, std::ostream& log) {
  auto model = transfer_model(study);
  const auto mesh = output_mesh(study);
  const int steps = study.setup.steps;
  std::vector<std::pair<double, std::string>> series;
  auto diagnostics = open_csv(dir / "agent_diagnostics.csv");
  diagnostics << "step,load_factor [-],agents_generated,agent_updates,applied [N],rigid_reaction [N],passed_out [N],"
                 "dropped [N],lost [N],lateral_reaction [N],lateral_passed_out [N],lateral_dropped [N]\n";
  std::vector<std::size_t> node_ids(study.mesh.grid.node_count());  // every point of the output mesh
  for (std::size_t n = 0; n < node_ids.size(); ++n) node_ids[n] = n;
  std::vector<AgentState> states;
  for (const auto& c : study.choices) log << "agent: " << c << "\n";
  for (int k = 1; k <= steps; ++k) {
    const double factor = double(k) / steps;
    states.push_back(evaluate(study, model, factor));
    const auto& state = states.back();
    check_finite(state.face_forces, "face force");
    check_finite(state.stress, workbench::kXX, workbench::kXY, "stress");
    check_finite(state.stress, workbench::kXY, workbench::kVoigtCount, "shear stress");
    check_finite(state.displacement, "displacement");
    char name[64];
    std::snprintf(name, sizeof name, "agent_step_%03d.vtu", k);
    workbench::write_vtu(dir / name, mesh, vtu_fields(state, study.mesh.grid.dim, FieldPlace::Node, node_ids),
                         vtu_fields(state, study.mesh.grid.dim, FieldPlace::Agent, study.mesh.cell_of_element),
                         k == 1 ? std::size_t(steps) : 1);  // the first step: the whole series must fit
    series.emplace_back(factor, name);
    const auto& d = state.diagnostics;
    diagnostics << k << ',' << factor << ',' << d.agents_generated << ',' << d.agent_updates << ',' << d.applied << ','
                << d.rigid_reaction << ',' << d.passed_out << ',' << d.dropped << ',' << d.lost << ','
                << d.lateral_reaction << ',' << d.lateral_passed_out << ',' << d.lateral_dropped << '\n';
    log << "agent: step " << k << "/" << steps << ": load " << agent::point_text(load_vector(study, factor), study.mesh.grid.dim)
        << " N (" << d.applied << " N applied in all), " << d.agents_generated << " agents, rigid reaction "
        << d.rigid_reaction << " N, passed out " << d.passed_out << " N, dropped " << d.dropped << " N, lost "
        << d.lost << " N\n";
  }
  diagnostics.close();
  auto warnings = study.warnings;
  for (const auto& w : load_balance_warnings(states.back().diagnostics)) warnings.push_back(w);
  for (const auto& w : warnings) log << "agent: warning: " << w << "\n";
  write_summary(dir / "agent_summary.json", study, states.back().diagnostics, warnings);
  workbench::write_pvd(dir / "agent.pvd", series);
  write_cells_csv(dir / "agent_cells.csv", study, states.back());
  write_nodes_csv(dir / "agent_nodes.csv", study, states.back(), mesh);
  return states;
}

}  // namespace agent_study
