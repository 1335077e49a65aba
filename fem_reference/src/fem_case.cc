// The FEM reference's case-file glue (fem_case.h): [fem] and the case file -> FemProblem in, the
// study's CSV files out. The solve itself (solve_fem.cc) knows no case file.
#include <fem_reference/fem_case.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>
#include <workbench/study_setup.h>

#include <fstream>
#include <ostream>

namespace fem_reference {

namespace fs = std::filesystem;
using workbench::Range;

FemSection read_fem_section(const workbench::CaseTable& root) {
  const auto t = root.table("fem");
  FemSection section;
  FemOptions& o = section.options;
  const FemOptions defaults;  // each default in one place: fem.h
  o.degree = t.integer("degree", defaults.degree, 1, 2);
  const std::string model = t.text("model", "plane_stress", {"plane_stress", "plane_strain"});
  o.model = model == "plane_stress" ? Model::PlaneStress : Model::PlaneStrain;
  const std::string solver = t.text("solver", "auto", {"auto", "direct", "amg", "mg"});
  o.solver = solver == "auto"     ? SolverKind::Auto
             : solver == "direct" ? SolverKind::Direct
             : solver == "mg"     ? SolverKind::Mg
                                  : SolverKind::Amg;
  o.direct_limit = t.integer("direct_limit", defaults.direct_limit, 0, 2000000000);
  o.tolerance = t.number("tolerance", defaults.tolerance, Range{0.0, 1e-2, true, false});
  o.max_iterations = t.integer("max_iterations", defaults.max_iterations, 1, 1000000);
  o.refine = t.integer("refine", defaults.refine, 0, 10);
  const std::string load = t.text("load", "traction", {"traction", "point"});
  o.load = load == "traction" ? LoadKind::Traction : LoadKind::Point;
  o.write_vtu = t.flag("vtu", defaults.write_vtu);
  const auto body = t.numbers("body_force", std::vector<double>{});
  if (!body.empty() && body.size() != 2 && body.size() != 3)
    t.fail("body_force", "must have 2 (2D) or 3 (3D) components [N/m^3]");
  for (std::size_t a = 0; a < body.size(); ++a) section.body_force[a] = body[a];
  return section;
}

FemProblem problem_from_case(const workbench::CaseFile& file) {
  const auto root = file.root();
  const auto setup = workbench::read_study_setup(root);
  FemProblem p;
  p.name = file.path().string();
  p.mesh_file = setup.mesh_file;
  p.mesh_parameters = setup.mesh_parameters;
  p.mesh_unit = setup.mesh_unit;
  p.young = setup.young;
  p.poisson = setup.poisson;
  p.thickness = setup.thickness;
  for (const auto& g : setup.rigid_groups) p.supports.push_back({g, SupportKind::Clamped, {}});
  for (const auto& g : setup.roller_groups) p.supports.push_back({g, SupportKind::Roller, {}});
  const auto fem = read_fem_section(root);
  p.options = fem.options;
  p.body_force = fem.body_force;
  // One force per [[load]] table, as given: a vector direction's axis components add up again.
  std::vector<std::array<double, 3>> forces;
  std::vector<std::string> groups;
  for (const auto& l : setup.loads) {
    if (l.entry >= forces.size()) forces.resize(l.entry + 1, {}), groups.resize(l.entry + 1);
    forces[l.entry][std::size_t(l.axis)] = l.sign * l.force;
    groups[l.entry] = l.group;
  }
  for (std::size_t i = 0; i < forces.size(); ++i) {
    if (p.options.load == LoadKind::Traction)
      p.tractions.push_back({groups[i], forces[i], {}});
    else
      p.point_forces.push_back({{}, forces[i], groups[i]});
  }
  if (p.supports.empty())
    root.table("boundary").fail("rigid", "no supports (rigid and rollers are both empty): the body could move "
                                         "freely, the FEM problem has no unique solution");
  if (setup.loads.empty() && p.body_force == std::array<double, 3>{})
    root.fail("load", "missing: nothing loads the body (give a [[load]] table or fem.body_force)");
  return p;
}

namespace {

using workbench::open_csv;

}  // namespace

void write_fem_csv(const FemResult& r, const fs::path& dir) {
  const int dim = r.dim;
  {
    const auto file = dir / "fem_cells.csv";
    auto out = open_csv(file);
    out << "cell,x [m],y [m]" << (dim == 3 ? ",z [m]" : "") << ",sigma_x [Pa],sigma_y [Pa],sigma_z [Pa],tau_xy [Pa]"
        << (dim == 3 ? ",tau_yz [Pa],tau_xz [Pa]" : "") << ",von_mises [Pa]\n";
    for (std::size_t e = 0; e < r.cell_count(); ++e) {
      out << e;
      for (int a = 0; a < dim; ++a) out << ',' << r.cell_centres[3 * e + a];
      out << ',' << r.sigma_x[e] << ',' << r.sigma_y[e] << ',' << r.sigma_z[e] << ',' << r.tau_xy[e];
      if (dim == 3) out << ',' << r.tau_yz[e] << ',' << r.tau_xz[e];
      out << ',' << r.von_mises[e] << '\n';
    }
    out.close();
  }
  {
    const auto file = dir / "fem_nodes.csv";
    auto out = open_csv(file);
    out << "node,x [m],y [m]" << (dim == 3 ? ",z [m]" : "") << ",u_x [m],u_y [m]" << (dim == 3 ? ",u_z [m]" : "") << "\n";
    for (std::size_t n = 0; n < r.node_count(); ++n) {
      out << n;
      for (int a = 0; a < dim; ++a) out << ',' << r.node_points[3 * n + a];
      for (int a = 0; a < dim; ++a) out << ',' << r.node_displacement[dim * n + a];
      out << '\n';
    }
    out.close();
  }
  {
    const auto file = dir / "fem_reactions.csv";
    auto out = open_csv(file);
    out << "group,kind,f_x [N],f_y [N]" << (dim == 3 ? ",f_z [N]" : "") << "\n";
    for (const auto& g : r.reactions) {
      out << g.group << ',' << g.kind;
      for (int a = 0; a < dim; ++a) out << ',' << g.force[a];
      out << '\n';
    }
    out << "(applied),load";
    for (int a = 0; a < dim; ++a) out << ',' << r.applied[a];
    out << '\n';
    out.close();
  }
  {
    const auto file = dir / "fem_summary.csv";
    auto out = open_csv(file);
    out << "key,value\n"
        << "dim," << r.dim << "\ndegree," << r.degree << "\nmodel," << r.model << "\ncells," << r.cells
        << "\nranks," << r.ranks << "\ndofs," << r.n_dofs << "\nactive_cells," << r.n_active_cells << "\nsolver,"
        << r.solver << "\niterations," << r.iterations << "\nresidual," << r.residual;
    if (r.backward_error) out << "\nbackward_error," << *r.backward_error;
    out << "\nmesh_seconds,"
        << r.mesh_seconds << "\nsetup_seconds," << r.setup_seconds << "\nassemble_seconds," << r.assemble_seconds
        << "\nsolve_seconds," << r.solve_seconds << "\noutput_seconds," << r.output_seconds
        << "\npeak_memory_bytes," << r.peak_memory_bytes << "\n";
    out.close();
  }
}

}  // namespace fem_reference
