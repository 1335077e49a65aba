// The same-body check: the agents' mesh against the reference's, before anything is solved.
#include <compare/same_body.h>

#include <agent/grid.h>
#include <Eigen/Geometry>
#include <gmsh.h>
#include <gmsh_session.h>
#include <workbench/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>

namespace compare {

namespace fs = std::filesystem;
using Eigen::Vector3d;
using workbench::Error;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Adds a piece of `measure` centred at `centre` spanning [lo, hi] to a group.
void add_piece(GroupShape& g, double measure, const Vector3d& centre, const Vector3d& lo, const Vector3d& hi) {
  g.centroid = (g.centroid * g.measure + centre * measure) / std::max(g.measure + measure, 1e-300);
  g.measure += measure;
  g.lo = g.lo.cwiseMin(lo);
  g.hi = g.hi.cwiseMax(hi);
}

/// An agent face's measure (no thickness), centre and corners' box.
void add_face(GroupShape& g, const agent::Grid& grid, const agent::BoundaryFace& f) {
  const int axis = agent::axis_of(f.side);
  Vector3d centre = grid.centre(f.cell), half = 0.5 * grid.size;
  if (grid.dim == 2) half[2] = 0;
  centre[axis] += agent::is_positive(f.side) ? half[axis] : -half[axis];
  double measure = 1;
  for (int a = 0; a < grid.dim; ++a)
    if (a != axis) measure *= grid.size[a];
  half[axis] = 0;
  add_piece(g, measure, centre, centre - half, centre + half);
}

std::string point(const Vector3d& x, int dim) { return agent::point_text(x, dim); }

/// The first axis along which a and b differ by more than `tol`, -1 when none.
int apart(const Vector3d& a, const Vector3d& b, int dim, double tol) {
  for (int k = 0; k < dim; ++k)
    if (!(std::abs(a[k] - b[k]) <= tol)) return k;
  return -1;
}

/// The gmsh model's nodes by tag.
std::unordered_map<std::size_t, Vector3d> model_nodes() {
  std::vector<std::size_t> tags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, false, false);
  std::unordered_map<std::size_t, Vector3d> at;
  for (std::size_t i = 0; i < tags.size(); ++i) at[tags[i]] = Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  return at;
}

/// The measure of the model's elements of dimension `dim` (any order: Gauss points on the
/// Jacobians) and their nodes' bounding box.
void body_of_model(int dim, const std::unordered_map<std::size_t, Vector3d>& nodes, BodyShape& out) {
  out.lo = Vector3d::Constant(kInf);
  out.hi = -out.lo;
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types, dim);
  for (int type : types) {
    std::vector<double> local, weights, jacobians, determinants, coords;
    gmsh::model::mesh::getIntegrationPoints(type, "Gauss2", local, weights);
    gmsh::model::mesh::getJacobians(type, local, jacobians, determinants, coords);
    for (std::size_t i = 0; i < determinants.size(); ++i) out.measure += std::abs(determinants[i]) * weights[i % weights.size()];
    std::vector<std::size_t> tags, element_nodes;
    gmsh::model::mesh::getElementsByType(type, tags, element_nodes);
    for (std::size_t n : element_nodes) {
      out.lo = out.lo.cwiseMin(nodes.at(n));
      out.hi = out.hi.cwiseMax(nodes.at(n));
    }
  }
}

/// A boundary element's measure and centre from its primary corners (2: a segment, 3: a triangle,
/// 4: a quadrangle as two triangles).
void add_element(GroupShape& g, const std::vector<Vector3d>& x) {
  double measure = 0;
  if (x.size() == 2) measure = (x[1] - x[0]).norm();
  if (x.size() >= 3) measure = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
  if (x.size() == 4) measure += 0.5 * (x[2] - x[0]).cross(x[3] - x[0]).norm();
  Vector3d centre = Vector3d::Zero(), lo = Vector3d::Constant(kInf), hi = -lo;
  for (const auto& p : x) {
    centre += p / double(x.size());
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  add_piece(g, measure, centre, lo, hi);
}

int primary_nodes(int type) {
  std::string name;
  int d, order, n, primary;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(type, name, d, order, n, local, primary);
  return primary;
}

std::string millimetres(double metres) {
  std::ostringstream s;
  s << 1e3 * metres << " mm";
  return s.str();
}

/// Fails with `key` when the agents' and the reference's group `group` (named by `what`) are apart.
void check_group(const workbench::CaseFile& file, const std::string& key, const std::string& what,
                 const GroupShape& a, const GroupShape& r, int dim, double tol, const std::string& names) {
  auto fail = [&](const std::string& of, const Vector3d& x, const Vector3d& y) {
    throw Error(file.path().string() + ": " + key + ": " + what + ": its " + of + " is " + point(x, dim) +
                " in the agents' mesh and " + point(y, dim) + " in the reference's, more than an agent size (" +
                millimetres(tol) + ") apart" + names);
  };
  if (apart(a.centroid, r.centroid, dim, tol) >= 0) fail("centre", a.centroid, r.centroid);
  if (apart(a.lo, r.lo, dim, tol) >= 0) fail("lower corner", a.lo, r.lo);
  if (apart(a.hi, r.hi, dim, tol) >= 0) fail("upper corner", a.hi, r.hi);
}

/// The warning for a load patch whose measure the agents change by more than kPatchMeasureWarning.
std::string patch_warning(const std::string& what, const workbench::LoadSpec& load, const GroupShape& a,
                          const GroupShape& r, int dim) {
  const double change = a.measure / r.measure - 1;
  if (!(std::abs(change) > kPatchMeasureWarning)) return "";
  std::ostringstream s;
  s.precision(3);
  const char* measure = dim == 2 ? "length" : "area";
  s << what << ": the agents' load patch has " << measure << " " << a.measure << (dim == 2 ? " m" : " m^2")
    << ", the true patch " << r.measure << (dim == 2 ? " m" : " m^2") << " (" << (change > 0 ? "+" : "") << 100 * change
    << " %); the force stays the case's " << load.force << " N, so the agents' pressure on it is "
    << 100 * (1 / (1 + change) - 1) << " % off the true one (smaller agents follow the patch closer: mesh.agent_size, `workbench voxelize -s`)";
  return s.str();
}

/// The bodies' dimension, bounding boxes (within an agent `size` per side) and measures (within the
/// staircase's boundary times an agent size).
void check_body(const std::string& where, const std::string& names, const BodyShape& agents, const BodyShape& reference,
                double size) {
  const int dim = agents.dim;
  if (reference.dim != dim)
    throw Error(where + "the agents' mesh is " + std::to_string(dim) + "D, the reference's " +
                std::to_string(reference.dim) + "D" + names);
  const double tol = size * (1 + 1e-6);
  if (apart(agents.lo, reference.lo, dim, tol) >= 0 || apart(agents.hi, reference.hi, dim, tol) >= 0)
    throw Error(where + "the body's bounding box is " + point(agents.lo, dim) + " to " + point(agents.hi, dim) +
                " in the agents' mesh and " + point(reference.lo, dim) + " to " + point(reference.hi, dim) +
                " in the reference's, more than an agent size (" + millimetres(size) + ") apart" + names);
  const double measure_tol = agents.boundary * size * (1 + 1e-6);
  if (!(std::abs(agents.measure - reference.measure) <= measure_tol)) {
    std::ostringstream s;
    s << where << "the body's " << (dim == 2 ? "area" : "volume") << " is " << agents.measure << " in the agents' mesh and "
      << reference.measure << " in the reference's, more apart than the staircase explains (" << measure_tol << ")" << names;
    throw Error(s.str());
  }
}

}  // namespace

BodyShape shape_of_agents(const agent::ImportedMesh& mesh) {
  const auto& grid = mesh.grid;
  BodyShape s;
  s.dim = grid.dim;
  s.lo = Vector3d::Constant(kInf);
  s.hi = -s.lo;
  Vector3d half = 0.5 * grid.size;
  if (grid.dim == 2) half[2] = 0;
  const double cell = grid.dim == 2 ? grid.size[0] * grid.size[1] : grid.size.prod();
  for (std::size_t c : mesh.cell_of_element) {
    s.lo = s.lo.cwiseMin(grid.centre(c) - half);
    s.hi = s.hi.cwiseMax(grid.centre(c) + half);
    s.measure += cell;
  }
  GroupShape all;
  for (const auto& f : grid.boundary_faces()) add_face(all, grid, f);
  s.boundary = all.measure;
  for (const auto& [name, faces] : mesh.face_groups)
    for (const auto& f : faces) add_face(s.groups[name], grid, f);
  return s;
}

BodyShape shape_of_mesh(const fs::path& file, const std::map<std::string, double>& parameters, double unit) {
  try {
    workbench::gmsh_load(file, parameters, unit);
    BodyShape s;
    s.dim = gmsh::model::getDimension();
    if (s.dim != 2 && s.dim != 3) throw Error(file.string() + ": the model must be 2D or 3D");
    const auto nodes = model_nodes();
    body_of_model(s.dim, nodes, s);
    for (const auto& [name, elements] : workbench::gmsh_physical_groups(s.dim - 1))
      for (const auto& e : elements) {
        std::vector<Vector3d> x;
        for (int k = 0; k < std::min<int>(primary_nodes(e.type), int(e.nodes.size())); ++k) x.push_back(nodes.at(e.nodes[k]));
        add_element(s.groups[name], x);
      }
    return s;
  } catch (const std::runtime_error& e) {
    throw Error(e.what());
  } catch (const std::exception& e) {  // gmsh's own (std::out_of_range of a node it does not have)
    throw Error(file.string() + ": " + e.what());
  } catch (const std::string& e) {  // gmsh 4.8 throws its messages as strings
    throw Error(file.string() + ": " + e);
  }
}

std::vector<std::string> check_same_body(const workbench::CaseFile& file, const std::string& key,
                                         const workbench::StudySetup& setup, double size, const BodyShape& agents,
                                         const BodyShape& reference, const fs::path& reference_file) {
  const std::string where = file.path().string() + ": " + key + ": ";
  const std::string names = " (agents: " + setup.mesh_file.string() + ", reference: " + reference_file.string() +
                            "; the two must be the same body with the same loads and supports)";
  check_body(where, names, agents, reference, size);
  const int dim = agents.dim;
  const double tol = size * (1 + 1e-6);
  std::vector<std::pair<std::string, std::string>> groups;  // (what, group)
  for (std::size_t i = 0; i < setup.loads.size(); ++i)
    groups.push_back({setup.loads[i].key() + ".group '" + setup.loads[i].group + "'", setup.loads[i].group});
  for (const auto& g : setup.rigid_groups) groups.push_back({"boundary.rigid group '" + g + "'", g});
  std::vector<std::string> warnings;
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const auto& [what, group] = groups[i];
    const auto a = agents.groups.find(group), r = reference.groups.find(group);
    if (r == reference.groups.end() || r->second.measure == 0)
      throw Error(where + what + " is not a boundary group of the reference's mesh " + reference_file.string() + names);
    if (a == agents.groups.end() || a->second.measure == 0) continue;  // the agent study refuses an empty load group
    check_group(file, key, what, a->second, r->second, dim, tol, names);
    if (i < setup.loads.size())
      if (auto w = patch_warning(what, setup.loads[i], a->second, r->second, dim); !w.empty()) warnings.push_back(w);
  }
  return warnings;
}

std::vector<std::string> check_reference_body(const workbench::CaseFile& file, const agent_study::AgentStudy& study,
                                              const schema::ReferenceOptions& reference) {
  if (study.mesh.grid.dim == 2)  // read before the dimension is known: refused here, not ignored
    if (const auto r = file.root().table("compare").table("reference"); r.has("tolerance"))
      r.fail("tolerance", "a 2D reference keeps its level (Q2 refined once unless refine says otherwise): the "
                          "tolerance is the 3D default's");
  if (reference.mesh.empty()) return {};  // the reference on the agents' own mesh
  const auto& grid = study.mesh.grid;
  const double size = grid.size.head(grid.dim).maxCoeff();
  const bool own = reference.mesh == study.setup.mesh_file;  // voxelized in the run ([mesh] agent_size)
  const auto true_shape = shape_of_mesh(reference.mesh, own ? study.setup.mesh_parameters : std::map<std::string, double>{},
                                        study.setup.mesh_unit);
  return check_same_body(file, own ? "mesh.agent_size" : "compare.reference.mesh", study.setup, size,
                         shape_of_agents(study.mesh), true_shape, reference.mesh);
}

}  // namespace compare
