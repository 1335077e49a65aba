#include "agent_study.h"

#include <workbench/error.h>
#include <workbench/vtk_output.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <ostream>

namespace agent_study {

namespace fs = std::filesystem;
using workbench::Error;
using workbench::Range;

void read_agent_section(const workbench::CaseTable& root, agent::Coefficients& k, agent::RuleSet& rules) {
  const auto t = root.table("agent");
  const std::string rule_set = t.text("rule_set", "patent", {"patent", "conserving"});
  rules = rule_set == "patent" ? agent::RuleSet::Patent : agent::RuleSet::Conserving;
  const auto unit = Range::closed(0, 1);
  k.alpha1 = t.number("alpha1", 0.5, unit);
  k.alpha2 = t.number("alpha2", 0.5, unit);
  k.alpha3 = t.number("alpha3", 0.25, unit);
  k.beta = t.number("beta", 0.5, unit);
  k.gamma = t.number("gamma", 1e-3, Range::non_negative());
  k.poisson_decay = t.number("poisson_decay", k.alpha2, unit);
  if (rules == agent::RuleSet::Conserving && k.alpha2 + k.alpha3 <= 0)
    t.fail("alpha2", "the conserving rule set needs alpha2 + alpha3 > 0");
}

AgentStudy load_agent_study(const workbench::CaseFile& file) {
  AgentStudy study;
  const auto root = file.root();
  study.setup = workbench::read_study_setup(root);
  read_agent_section(root, study.coefficients, study.rules);
  try {
    study.mesh = agent::import_mesh(study.setup.mesh_file, study.setup.mesh_parameters);
  } catch (const std::runtime_error& e) {
    throw Error(e.what());
  }
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
    const std::string key = "load[" + std::to_string(i) + "]";
    if (spec.axis >= grid.dim)
      throw Error(file.path().string() + ": " + key + ".direction: " + spec.direction_name() + " is not an axis of a " +
                  std::to_string(grid.dim) + "D mesh");
    const auto& faces = study.mesh.face_groups.at(spec.group);
    if (faces.empty()) throw Error(file.path().string() + ": " + key + ".group: group '" + spec.group + "' has no faces");
    double area = 0;
    for (const auto& f : faces) area += grid.face_area(agent::axis_of(f.side));
    for (const auto& f : faces)
      study.loads.push_back({f.cell, agent::direction(spec.axis, spec.sign > 0),
                             spec.force * grid.face_area(agent::axis_of(f.side)) / area});
  }
  return study;
}

AgentState evaluate(const AgentStudy& study, agent::LoadTransfer& model, double factor) {
  std::vector<agent::EntryLoad> loads = study.loads;
  for (auto& l : loads) l.force *= factor;
  model.solve(loads);
  AgentState s;
  const auto& grid = study.mesh.grid;
  s.face_forces = model.face_forces();
  s.generation = model.generation();
  s.diagnostics = model.diagnostics();
  s.stress = agent::agent_stresses(grid, s.face_forces);
  s.strain = agent::agent_strains(grid, model.material(), s.stress);
  s.displacement = agent::node_displacements(grid, s.strain, agent::choose_datums(grid, loads));
  return s;
}

workbench::OutputMesh output_mesh(const AgentStudy& study) {
  const auto& grid = study.mesh.grid;
  workbench::OutputMesh mesh;
  const auto nn = grid.node_counts();
  mesh.points.reserve(grid.node_count() * 3);
  for (int k = 0; k < nn[2]; ++k)
    for (int j = 0; j < nn[1]; ++j)
      for (int i = 0; i < nn[0]; ++i) {
        const Eigen::Vector3d x = grid.origin + Eigen::Vector3d(i * grid.size[0], j * grid.size[1],
                                                                grid.dim == 3 ? k * grid.size[2] : 0.0);
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

const char* kDirections[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};

/// Cell fields in mesh element order.
std::vector<workbench::Field> cell_fields(const AgentStudy& study, const AgentState& s) {
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim, nd = 2 * dim;
  const auto& order = study.mesh.cell_of_element;
  std::vector<workbench::Field> fields;
  fields.push_back({"generation", 1, {}});
  fields.push_back({"face_force", nd, {}});
  for (int a = 0; a < dim; ++a) fields.push_back({std::string("sigma_") + char('x' + a), 1, {}});
  fields.push_back({"strain", 3, {}});
  for (std::size_t cell : order) {
    fields[0].values.push_back(s.generation[cell]);
    for (int f = 0; f < nd; ++f) fields[1].values.push_back(s.face_forces[cell * nd + f]);
    for (int a = 0; a < dim; ++a) fields[2 + a].values.push_back(s.stress[cell * dim + a]);
    for (int a = 0; a < 3; ++a) fields[2 + dim].values.push_back(s.strain[cell * 3 + a]);
  }
  return fields;
}

std::vector<workbench::Field> point_fields(const AgentStudy& study, const AgentState& s) {
  const int dim = study.mesh.grid.dim;
  workbench::Field u{"displacement", 3, {}};
  for (std::size_t node = 0; node < study.mesh.grid.node_count(); ++node)
    for (int a = 0; a < 3; ++a) u.values.push_back(a < dim ? s.displacement[node * dim + a] : 0.0);
  return {u};
}

void check_finite(const std::vector<double>& v, const std::string& what) {
  for (double x : v)
    if (!std::isfinite(x)) throw Error("agent model produced a non-finite " + what);
}

std::ofstream open_csv(const fs::path& file) {
  std::ofstream out(file);
  if (!out) throw Error(file.string() + ": cannot open for writing");
  out.precision(12);
  return out;
}

void write_cells_csv(const fs::path& file, const AgentStudy& study, const AgentState& s) {
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim, nd = 2 * dim;
  auto out = open_csv(file);
  out << "cell,x,y" << (dim == 3 ? ",z" : "") << ",generation";
  for (int f = 0; f < nd; ++f) out << ",f_" << kDirections[f];
  for (int a = 0; a < dim; ++a) out << ",sigma_" << char('x' + a);
  out << ",eps_x,eps_y,eps_z\n";
  for (std::size_t e = 0; e < study.mesh.cell_of_element.size(); ++e) {
    const std::size_t cell = study.mesh.cell_of_element[e];
    const Eigen::Vector3d x = grid.centre(cell);
    out << e;
    for (int a = 0; a < dim; ++a) out << ',' << x[a];
    out << ',' << s.generation[cell];
    for (int f = 0; f < nd; ++f) out << ',' << s.face_forces[cell * nd + f];
    for (int a = 0; a < dim; ++a) out << ',' << s.stress[cell * dim + a];
    for (int a = 0; a < 3; ++a) out << ',' << s.strain[cell * 3 + a];
    out << '\n';
  }
  if (!out) throw Error(file.string() + ": write failed");
}

void write_nodes_csv(const fs::path& file, const AgentStudy& study, const AgentState& s,
                     const workbench::OutputMesh& mesh) {
  const int dim = study.mesh.grid.dim;
  auto out = open_csv(file);
  out << "node,x,y" << (dim == 3 ? ",z" : "") << ",u_x,u_y" << (dim == 3 ? ",u_z" : "") << "\n";
  for (std::size_t node = 0; node < mesh.point_count(); ++node) {
    out << node;
    for (int a = 0; a < dim; ++a) out << ',' << mesh.points[3 * node + a];
    for (int a = 0; a < dim; ++a) out << ',' << s.displacement[node * dim + a];
    out << '\n';
  }
  if (!out) throw Error(file.string() + ": write failed");
}

}  // namespace

std::vector<AgentState> write_agent_outputs(const AgentStudy& study, const fs::path& dir, std::ostream& log) {
  agent::Material material{study.setup.young, study.setup.poisson};
  agent::LoadTransfer model(study.mesh.grid, material, study.coefficients, study.rules);
  const auto mesh = output_mesh(study);
  const int steps = study.setup.steps;
  std::vector<std::pair<double, std::string>> series;
  auto diagnostics = open_csv(dir / "agent_diagnostics.csv");
  diagnostics << "step,load_factor,agents_generated,agent_updates,applied,rigid_reaction,passed_out,dropped,"
                 "lateral_reaction,lateral_passed_out,lateral_dropped\n";
  std::vector<AgentState> states;
  for (int k = 1; k <= steps; ++k) {
    const double factor = double(k) / steps;
    states.push_back(evaluate(study, model, factor));
    const auto& state = states.back();
    check_finite(state.face_forces, "face force");
    check_finite(state.displacement, "displacement");
    char name[64];
    std::snprintf(name, sizeof name, "agent_step_%03d.vtu", k);
    workbench::write_vtu(dir / name, mesh, point_fields(study, state), cell_fields(study, state));
    series.emplace_back(factor, name);
    const auto& d = state.diagnostics;
    diagnostics << k << ',' << factor << ',' << d.agents_generated << ',' << d.agent_updates << ',' << d.applied << ','
                << d.rigid_reaction << ',' << d.passed_out << ',' << d.dropped << ',' << d.lateral_reaction << ','
                << d.lateral_passed_out << ',' << d.lateral_dropped << '\n';
    log << "agent: step " << k << "/" << steps << ": load " << d.applied << " N, " << d.agents_generated
        << " agents, rigid reaction " << d.rigid_reaction << " N, passed out " << d.passed_out << " N, dropped "
        << d.dropped << " N\n";
  }
  if (!diagnostics) throw Error((dir / "agent_diagnostics.csv").string() + ": write failed");
  workbench::write_pvd(dir / "agent.pvd", series);
  write_cells_csv(dir / "agent_cells.csv", study, states.back());
  write_nodes_csv(dir / "agent_nodes.csv", study, states.back(), mesh);
  return states;
}

}  // namespace agent_study
