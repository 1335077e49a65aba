// The agent comparison's files (step 5, docs/compare.md): lines.csv, compare.vtu, cells.csv,
// nodes.csv, steps.csv, lines.json, and the same fields in memory for Python.
#include "agent_compare.h"

#include <workbench/csv_file.h>
#include <workbench/error.h>
#include <workbench/vtk_output.h>

#include <cmath>
#include <optional>

namespace compare::agent_compare {

namespace fs = std::filesystem;
using workbench::open_csv;

std::vector<int> line_segments(const Line& line) {
  std::vector<int> segment;
  for (std::size_t i = 0; i < line.body_samples.size(); ++i)
    segment.push_back(i == 0 ? 0 : segment.back() + (line.body_samples[i] != line.body_samples[i - 1] + 1));
  return segment;
}

void write_lines_csv(const fs::path& file, const agent::Grid& grid, const std::vector<Line>& lines,
                     const std::vector<ScopeSamples>& samples) {
  const int dim = grid.dim;
  auto csv = open_csv(file);
  csv << "model,line,segment,arc_length [m],x [m],y [m]" << (dim == 3 ? ",z [m]" : "");
  for (const auto& field : kFields)  // each component once: the displacement vector is u_x, u_y (, u_z)
    if (field.in(dim) && field.slot >= 0) csv << ',' << field.name << " [" << field.unit << ']';
  csv << '\n';
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const auto segment = line_segments(lines[li]);
    for (int m = 0; m < 2; ++m)
      for (std::size_t i = 0; i < lines[li].body_samples.size(); ++i) {  // the samples in the body only
        const Eigen::Vector3d p = lines[li].point(lines[li].body_samples[i]);
        csv << (m == 0 ? "agent" : "fem") << ',' << lines[li].name << ',' << segment[i] << ',' << (p - lines[li].from).norm();
        for (int a = 0; a < dim; ++a) csv << ',' << p[a];
        const auto& to = kSources[m].second;  // the agent (m = 0) or the reference
        for (std::size_t k = 0; k < std::size(kFields); ++k)
          if (kFields[k].in(dim) && kFields[k].slot >= 0) csv << ',' << (samples[li][k].*to)[i];
        csv << '\n';
      }
  }
  csv.close();  // complete on disk before figures.py reads it
}

void write_field_files(const fs::path& dir, const AgentCompareInput& in, const GridFields& agent,
                       const GridFields& fem, const agent_study::AgentState& state, double mask) {
  const auto& study = in.study;
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim;
  const auto mesh = agent_study::output_mesh(study);
  const auto rx = ratios(component(agent.stress, kStressSlots, kSigmaX), component(fem.stress, kStressSlots, kSigmaX), mask);
  const auto ry = ratios(component(agent.stress, kStressSlots, kSigmaY), component(fem.stress, kStressSlots, kSigmaY), mask);
  // The stress fields compared in this dimension (kFields): agent, FEM and their difference per cell.
  std::vector<int> slots;
  for (const auto& f : kFields)
    if (f.in(dim) && !f.per_node) slots.push_back(f.slot);
  std::vector<workbench::Field> cells;
  for (const char* model : {"agent_", "fem_", "diff_"})
    for (int slot : slots) cells.push_back({std::string(model) + stress_name(slot) + " [Pa]", 1, {}, {}, {}});
  const std::size_t ratio_at = cells.size();
  for (const char* n : {"ratio_sigma_x [-]", "ratio_sigma_y [-]", "ratio_masked_x [-]", "ratio_masked_y [-]",
                        "generation [-]", "far [-]"})
    cells.push_back({n, 1, {}, {}, {}});
  for (std::size_t cell : study.mesh.cell_of_element) {
    std::size_t f = 0;
    for (const GridFields* model : {&agent, &fem})
      for (int slot : slots) cells[f++].values.push_back(model->stress[kStressSlots * cell + slot]);
    for (int slot : slots)
      cells[f++].values.push_back(agent.stress[kStressSlots * cell + slot] - fem.stress[kStressSlots * cell + slot]);
    for (double v : {rx.ratio[cell], ry.ratio[cell], double(rx.masked[cell]), double(ry.masked[cell]),
                     double(state.generation[cell]), double(!in.near.cells[cell])})
      cells[f++].values.push_back(v);
  }
  for (std::size_t cell : study.mesh.cell_of_element) {  // masked ratios: NaN, blanked by ParaView
    cells[ratio_at].undefined.push_back(rx.masked[cell]);
    cells[ratio_at + 1].undefined.push_back(ry.masked[cell]);
  }
  const std::vector<std::string> xyz{"x", "y", "z"};
  std::vector<workbench::Field> points{
      {"agent_u [m]", 3, {}, xyz, {}}, {"fem_u [m]", 3, {}, xyz, {}}, {"diff_u [m]", 3, {}, xyz, {}}};
  for (std::size_t n = 0; n < grid.node_count(); ++n)
    for (int a = 0; a < 3; ++a) {
      const double ua = a < dim ? agent.u[n * dim + a] : 0.0, uf = a < dim ? fem.u[n * dim + a] : 0.0;
      points[0].values.push_back(ua);
      points[1].values.push_back(uf);
      points[2].values.push_back(ua - uf);
    }
  workbench::write_vtu(dir / "compare.vtu", mesh, points, cells);

  // A masked ratio means nothing: an empty field on purpose (workbench::CsvFile, docs/compare.md); NaN in compare.vtu.
  auto ratio_field = [](const Ratios& r, std::size_t cell) {
    return r.masked[cell] ? std::nullopt : std::optional<double>(r.ratio[cell] + 0.0);  // + 0.0: no "-0"
  };
  auto cells_csv = open_csv(dir / "cells.csv");
  cells_csv << "cell,x [m],y [m]" << (dim == 3 ? ",z [m]" : "")
            << ",generation,agent_sigma_x [Pa],agent_sigma_y [Pa],fem_sigma_x [Pa],fem_sigma_y [Pa],ratio_sigma_x [-],"
               "ratio_sigma_y [-],masked_x,masked_y,far";
  for (int slot : slots)  // the other stress fields after the seed's
    if (slot != kSigmaX && slot != kSigmaY)
      cells_csv << ",agent_" << stress_name(slot) << " [Pa],fem_" << stress_name(slot) << " [Pa]";
  cells_csv << '\n';
  for (std::size_t e = 0; e < study.mesh.cell_of_element.size(); ++e) {
    const std::size_t cell = study.mesh.cell_of_element[e];
    const Eigen::Vector3d c = grid.centre(cell);
    cells_csv << e;
    for (int a = 0; a < dim; ++a) cells_csv << ',' << c[a];
    const double* a = &agent.stress[kStressSlots * cell];
    const double* f = &fem.stress[kStressSlots * cell];
    cells_csv << ',' << state.generation[cell] << ',' << a[kSigmaX] << ',' << a[kSigmaY] << ',' << f[kSigmaX] << ','
              << f[kSigmaY] << ',' << ratio_field(rx, cell) << ',' << ratio_field(ry, cell) << ',' << int(rx.masked[cell])
              << ',' << int(ry.masked[cell]) << ',' << int(!in.near.cells[cell]);
    for (int slot : slots)
      if (slot != kSigmaX && slot != kSigmaY) cells_csv << ',' << a[slot] << ',' << f[slot];
    cells_csv << '\n';
  }
  auto nodes_csv = open_csv(dir / "nodes.csv");
  nodes_csv << "i,j" << (dim == 3 ? ",k" : "") << ",x [m],y [m]" << (dim == 3 ? ",z [m]" : "")
            << ",agent_u_x [m],agent_u_y [m]" << (dim == 3 ? ",agent_u_z [m]" : "") << ",fem_u_x [m],fem_u_y [m]"
            << (dim == 3 ? ",fem_u_z [m]" : "") << "\n";
  for (std::size_t n : compare::body_node_ids(grid)) {  // air has no nodes; box order on any layout
    const auto c = grid.node_coords(n);
    nodes_csv << c[0] << ',' << c[1];
    if (dim == 3) nodes_csv << ',' << c[2];
    for (int a = 0; a < dim; ++a) nodes_csv << ',' << mesh.points[3 * n + a];
    for (int a = 0; a < dim; ++a) nodes_csv << ',' << agent.u[n * dim + a];
    for (int a = 0; a < dim; ++a) nodes_csv << ',' << fem.u[n * dim + a];
    nodes_csv << '\n';
  }
  cells_csv.close();
  nodes_csv.close();
}

/// The fields of cells.csv, nodes.csv and lines.csv, in their rows' order, in memory (ComparedFields).
ComparedFields compared_fields(const AgentCompareInput& in, const GridFields& agent, const GridFields& fem,
                               const agent_study::AgentState& state, double mask, const std::vector<ScopeSamples>& samples) {
  using Kind = FieldTable::Kind;
  const auto& grid = in.study.mesh.grid;
  const int dim = grid.dim;
  const Ratios r[2] = {ratios(component(agent.stress, kStressSlots, kSigmaX), component(fem.stress, kStressSlots, kSigmaX), mask),
                       ratios(component(agent.stress, kStressSlots, kSigmaY), component(fem.stress, kStressSlots, kSigmaY), mask)};
  // The other stress fields of this dimension (kFields): agent_<name>, fem_<name> columns as in cells.csv.
  std::vector<const FieldSpec*> others;
  for (const auto& field : kFields)
    if (field.in(dim) && !field.per_node && field.slot != kSigmaX && field.slot != kSigmaY) others.push_back(&field);
  std::vector<std::vector<double>> other_values(2 * others.size());
  std::vector<double> point, a, f, d, ratio, masked, far, generation, box;
  for (std::size_t cell : in.study.mesh.cell_of_element) {
    const Eigen::Vector3d c = grid.centre(cell);
    point.insert(point.end(), c.data(), c.data() + dim);
    for (std::size_t o = 0; o < others.size(); ++o) {
      other_values[2 * o].push_back(agent.stress[kStressSlots * cell + others[o]->slot]);
      other_values[2 * o + 1].push_back(fem.stress[kStressSlots * cell + others[o]->slot]);
    }
    for (int k = 0; k < 2; ++k) {
      a.push_back(agent.stress[kStressSlots * cell + kSigmaX + k]);
      f.push_back(fem.stress[kStressSlots * cell + kSigmaX + k]);
      d.push_back(a.back() - f.back());
      ratio.push_back(r[k].masked[cell] ? NAN : r[k].ratio[cell]);
      masked.push_back(r[k].masked[cell]);
    }
    far.push_back(!in.near.cells[cell]);
    generation.push_back(state.generation[cell]);
  }
  ComparedFields out;
  auto& t = out.cells;
  t.add("point", dim, std::move(point)), t.add("agent_sigma", 2, std::move(a)), t.add("fem_sigma", 2, std::move(f));
  t.add("diff_sigma", 2, std::move(d)), t.add("ratio_sigma", 2, std::move(ratio));
  t.add("masked", 2, std::move(masked), Kind::Flag), t.add("far", 1, std::move(far), Kind::Flag);
  t.add("generation", 1, std::move(generation), Kind::Integer);
  for (std::size_t o = 0; o < others.size(); ++o) {
    t.add(std::string("agent_") + others[o]->name, 1, std::move(other_values[2 * o]));
    t.add(std::string("fem_") + others[o]->name, 1, std::move(other_values[2 * o + 1]));
  }
  for (std::size_t node : compare::body_node_ids(grid)) {
    const auto c = grid.node_coords(node);
    const Eigen::Vector3d x = grid.node_position(c[0], c[1], c[2]);
    box.insert(box.end(), c.begin(), c.begin() + dim);
    point.insert(point.end(), x.data(), x.data() + dim);
    for (int k = 0; k < dim; ++k) {
      a.push_back(agent.u[node * dim + k]);
      f.push_back(fem.u[node * dim + k]);
      d.push_back(a.back() - f.back());
    }
    far.push_back(!in.near.nodes[node]);
  }
  auto& n = out.nodes;  // the moved-from vectors above are empty again (and refilled)
  n.add("box_coords", dim, std::move(box), Kind::Integer), n.add("point", dim, std::move(point));
  n.add("agent_u", dim, std::move(a)), n.add("fem_u", dim, std::move(f)), n.add("diff_u", dim, std::move(d));
  n.add("far", 1, std::move(far), Kind::Flag);
  for (std::size_t li = 0; li < in.lines.size(); ++li) {
    const auto& line = in.lines[li];
    const auto& s = samples[li];
    std::vector<double> arc, at, sigma[2], u[2];
    constexpr std::size_t sx = field_index("sigma_x"), sy = field_index("sigma_y"), ux = field_index("u_x"),
                          uy = field_index("u_y"), uz = field_index("u_z");
    for (std::size_t i = 0; i < line.body_samples.size(); ++i) {
      const Eigen::Vector3d p = line.point(line.body_samples[i]);
      arc.push_back((p - line.from).norm());
      at.insert(at.end(), p.data(), p.data() + dim);
      for (int m = 0; m < 2; ++m) {
        const auto& to = kSources[m].second;  // the agent, then the reference
        sigma[m].insert(sigma[m].end(), {(s[sx].*to)[i], (s[sy].*to)[i]});
        for (std::size_t c : {ux, uy, uz})
          if (kFields[c].in(dim)) u[m].push_back((s[c].*to)[i]);
      }
    }
    FieldTable l;
    const auto segment = line_segments(line);
    l.add("segment", 1, {segment.begin(), segment.end()}, Kind::Integer);
    l.add("arc_length", 1, std::move(arc)), l.add("point", dim, std::move(at));
    l.add("agent_sigma", 2, std::move(sigma[0])), l.add("fem_sigma", 2, std::move(sigma[1]));
    l.add("agent_u", dim, std::move(u[0])), l.add("fem_u", dim, std::move(u[1]));
    for (const FieldSpec* field : others) {
      const std::size_t k = std::size_t(field - kFields);
      l.add(std::string("agent_") + field->name, 1, s[k].agent);
      l.add(std::string("fem_") + field->name, 1, s[k].reference);
    }
    out.lines.emplace_back(line.name, std::move(l));
  }
  return out;
}

/// The agent's sigma per cell at every load step, with the cell's centre (the animation's data,
/// drawn before the other files exist).
void write_steps_csv(const fs::path& file, const agent_study::AgentStudy& study,
                     const std::vector<agent_study::AgentState>& states) {
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim;
  auto csv = open_csv(file);
  csv << "step,load [N],cell,x [m],y [m]" << (dim == 3 ? ",z [m]" : "") << ",generation,sigma_x [Pa],sigma_y [Pa]\n";
  for (std::size_t k = 0; k < states.size(); ++k) {
    const auto& s = states[k];
    for (std::size_t e = 0; e < study.mesh.cell_of_element.size(); ++e) {
      const std::size_t cell = study.mesh.cell_of_element[e];
      const Eigen::Vector3d c = grid.centre(cell);
      csv << k + 1 << ',' << s.diagnostics.applied << ',' << e;
      for (int a = 0; a < dim; ++a) csv << ',' << c[a];
      csv << ',' << s.generation[cell] << ',' << s.stress[cell][workbench::kXX] << ',' << s.stress[cell][workbench::kYY] << '\n';
    }
  }
  csv.close();
}

/// The sample lines as lines.json (for the figures) and summary.json list them.
nlohmann::json lines_json(const std::vector<Line>& lines) {
  auto json = nlohmann::json::array();
  for (const auto& l : lines) {
    auto segments = nlohmann::json::array();  // [start, end] arc length of each piece in the body
    const auto segment = line_segments(l);
    for (std::size_t i = 0; i < segment.size(); ++i) {
      const double arc = (l.point(l.body_samples[i]) - l.from).norm();
      if (i == 0 || segment[i] != segment[i - 1]) segments.push_back({arc, arc});
      segments.back()[1] = arc;
    }
    json.push_back({{"name", l.name}, {"description", l.description}, {"kind", l.kind},
                    {"from", {l.from[0], l.from[1], l.from[2]}}, {"to", {l.to[0], l.to[1], l.to[2]}},
                    {"segments", segments}});
  }
  return json;
}

}  // namespace compare::agent_compare
