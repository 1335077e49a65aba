// PBD mesh input: gmsh (.geo/.msh through the shared session), Wavefront OBJ and VTK .vtu, each
// checked (pbd::mesh_problem) and every problem one line.
#include <pbd_io/mesh_io.h>

#include <gmsh.h>
#include <gmsh_session.h>
#include <workbench/error.h>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <unordered_map>

namespace pbd_io {

namespace fs = std::filesystem;
using workbench::Error;

namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& what) { throw Error(file.string() + ": " + what); }

LoadedMesh read_gmsh(const fs::path& file, const std::map<std::string, double>& parameters) {
  LoadedMesh out;
  try {
    workbench::gmsh_load(file, parameters);
  } catch (const std::runtime_error& e) {
    throw Error(e.what());
  }

  const int dim = gmsh::model::getDimension();
  if (dim < 1) fail(file, "holds no lines or surfaces (model dimension " + std::to_string(dim) + ")");
  if (dim > 2) fail(file, "is a volume mesh; the PBD model takes line and surface meshes");
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric);
  std::vector<std::size_t> order(tags.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tags[a] < tags[b]; });
  std::unordered_map<std::size_t, int> index;
  for (std::size_t i : order) {
    if (index.count(tags[i])) continue;
    index[tags[i]] = int(out.mesh.points.size());
    out.mesh.points.emplace_back(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);
    out.node_names.push_back((long long)tags[i]);
  }
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> etags, enodes;
  gmsh::model::mesh::getElements(types, etags, enodes, dim);
  for (std::size_t t = 0; t < types.size(); ++t) {
    int vtk = 0;
    switch (types[t]) {
      case 1: vtk = pbd::kLine; break;
      case 2: vtk = pbd::kTriangle; break;
      case 3: vtk = pbd::kQuad; break;
      default: {
        std::string type_name;
        int d, order_, nn, np;
        std::vector<double> local;
        gmsh::model::mesh::getElementProperties(types[t], type_name, d, order_, nn, local, np);
        fail(file, "has " + type_name + " elements; the PBD model takes 2-node lines, 3-node triangles and 4-node quadrangles");
      }
    }
    const int corners = pbd::corner_count(vtk);
    for (std::size_t e = 0; e < etags[t].size(); ++e) {
      out.mesh.cell_types.push_back(vtk);
      for (int c = 0; c < corners; ++c) out.mesh.cell_nodes.push_back(index.at(enodes[t][e * corners + c]));
      out.mesh.cell_offsets.push_back(int(out.mesh.cell_nodes.size()));
    }
  }
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  for (const auto& [gdim, gtag] : groups) {
    std::string group;
    gmsh::model::getPhysicalName(gdim, gtag, group);
    if (group.empty()) group = std::to_string(gtag);
    std::vector<std::size_t> ntags;
    std::vector<double> ncoords;
    gmsh::model::mesh::getNodesForPhysicalGroup(gdim, gtag, ntags, ncoords);
    auto& nodes = out.mesh.groups[group];
    for (std::size_t tag : ntags) nodes.push_back(index.at(tag));
  }
  return out;
}

/// "12", "12/3", "12/3/4", "-1" (relative) -> 0-based index.
int obj_index(const std::string& token, std::size_t vertex_count, const fs::path& file, int line) {
  long v = 0;
  try {
    v = std::stol(token.substr(0, token.find('/')));
  } catch (...) {
    fail(file, "line " + std::to_string(line) + ": bad vertex reference '" + token + "'");
  }
  const long i = v < 0 ? long(vertex_count) + v : v - 1;
  if (v == 0 || i < 0 || i >= long(vertex_count))
    fail(file, "line " + std::to_string(line) + ": vertex " + token + " does not exist (" + std::to_string(vertex_count) + " so far)");
  return int(i);
}

LoadedMesh read_obj(const fs::path& file) {
  std::ifstream in(file);
  if (!in) fail(file, "cannot open");
  LoadedMesh out;
  std::string text, group;
  int line = 0;
  auto add_to_group = [&](std::initializer_list<int> nodes) {
    if (!group.empty()) out.mesh.groups[group].insert(out.mesh.groups[group].end(), nodes);
  };
  while (std::getline(in, text)) {
    ++line;
    std::istringstream s(text);
    std::string tag;
    if (!(s >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      double x, y, z = 0;
      if (!(s >> x >> y)) fail(file, "line " + std::to_string(line) + ": a vertex needs x y [z]");
      s >> z;
      out.mesh.points.emplace_back(x, y, z);
    } else if (tag == "f" || tag == "l") {
      std::vector<int> v;
      std::string tok;
      while (s >> tok) v.push_back(obj_index(tok, out.mesh.points.size(), file, line));
      if (tag == "l") {
        if (v.size() < 2) fail(file, "line " + std::to_string(line) + ": a polyline needs 2 or more vertices");
        for (std::size_t k = 0; k + 1 < v.size(); ++k) {
          out.mesh.add_cell(pbd::kLine, {v[k], v[k + 1]});
          add_to_group({v[k], v[k + 1]});
        }
      } else if (v.size() == 3) {
        out.mesh.add_cell(pbd::kTriangle, {v[0], v[1], v[2]});
        add_to_group({v[0], v[1], v[2]});
      } else if (v.size() == 4) {
        out.mesh.add_cell(pbd::kQuad, {v[0], v[1], v[2], v[3]});
        add_to_group({v[0], v[1], v[2], v[3]});
      } else {
        fail(file, "line " + std::to_string(line) + ": a face with " + std::to_string(v.size()) +
                       " vertices; the PBD model takes triangles and quadrilaterals");
      }
    } else if (tag == "g" || tag == "o") {
      std::getline(s >> std::ws, group);
    }
    // vt, vn, usemtl, mtllib, s: not needed.
  }
  for (std::size_t i = 0; i < out.mesh.points.size(); ++i) out.node_names.push_back((long long)i + 1);
  return out;
}

/// Catches VTK's errors while a file is read, so that its multi-line log stays off the terminal
/// (every problem is one line of ours), and remembers whether there was one. VTK passes an error
/// to an object's ErrorEvent observer instead of printing it.
class VtkErrors {
 public:
  explicit VtkErrors(vtkXMLUnstructuredGridReader* reader) {
    callback_->SetClientData(&failed_);
    callback_->SetCallback([](vtkObject*, unsigned long, void* failed, void*) { *static_cast<bool*>(failed) = true; });
    reader->AddObserver(vtkCommand::ErrorEvent, callback_);
    reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, callback_);
    reader->SetReaderErrorObserver(callback_);
    reader->SetParserErrorObserver(callback_);
  }
  bool failed() const { return failed_; }

 private:
  bool failed_ = false;
  vtkNew<vtkCallbackCommand> callback_;
};

LoadedMesh read_vtu(const fs::path& file) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  VtkErrors errors(reader);
  if (!reader->CanReadFile(file.string().c_str())) fail(file, "is not a VTK XML unstructured grid");
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (!grid || reader->GetErrorCode() != 0 || errors.failed())
    fail(file, "VTK could not read it (a truncated or malformed VTK XML file)");
  LoadedMesh out;
  const vtkIdType n = grid->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    grid->GetPoint(i, p);
    out.mesh.points.emplace_back(p[0], p[1], p[2]);
    out.node_names.push_back(i);
  }
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    const int type = grid->GetCellType(c);
    vtkIdType np;
    const vtkIdType* pts;
    grid->GetCellPoints(c, np, pts);
    if (type == 1 || type == 2) continue;  // vertices carry no structure
    if (type == 4) {                       // polyline
      for (vtkIdType k = 0; k + 1 < np; ++k) out.mesh.add_cell(pbd::kLine, {int(pts[k]), int(pts[k + 1])});
      continue;
    }
    if (type != pbd::kLine && type != pbd::kTriangle && type != pbd::kQuad)
      fail(file, "cell " + std::to_string(c) + " has VTK type " + std::to_string(type) +
                     "; the PBD model takes lines, polylines, triangles and quadrilaterals");
    out.mesh.cell_types.push_back(type);
    for (vtkIdType k = 0; k < np; ++k) out.mesh.cell_nodes.push_back(int(pts[k]));
    out.mesh.cell_offsets.push_back(int(out.mesh.cell_nodes.size()));
  }
  // Groups: single-component point arrays holding only 0 and 1.
  vtkPointData* pd = grid->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = pd->GetArray(a);
    if (!array || array->GetNumberOfComponents() != 1 || !array->GetName()) continue;
    std::vector<int> nodes;
    bool flags = true;
    for (vtkIdType i = 0; i < n && flags; ++i) {
      const double v = array->GetTuple1(i);
      flags = v == 0 || v == 1;
      if (v == 1) nodes.push_back(int(i));
    }
    if (flags) out.mesh.groups[array->GetName()] = nodes;
  }
  return out;
}

}  // namespace

LoadedMesh read_mesh(const fs::path& file, const std::map<std::string, double>& parameters) {
  if (!fs::is_regular_file(file)) fail(file, "no such mesh file");
  const std::string ext = file.extension().string();
  if (!parameters.empty() && ext != ".geo") fail(file, "mesh parameters apply to .geo files only");
  LoadedMesh out;
  if (ext == ".msh" || ext == ".geo") out = read_gmsh(file, parameters);
  else if (ext == ".obj") out = read_obj(file);
  else if (ext == ".vtu") out = read_vtu(file);
  else fail(file, "unknown mesh format '" + ext + "' (gmsh .msh or .geo, .obj, .vtu)");
  const std::string problem = pbd::mesh_problem(out.mesh, 1e-9, &out.node_names);
  if (!problem.empty()) fail(file, problem);
  for (auto& [name, nodes] : out.mesh.groups) {
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  }
  return out;
}

std::vector<int> group_nodes(const LoadedMesh& mesh, const fs::path& file, const std::vector<std::string>& groups) {
  std::vector<int> out;
  for (const auto& g : groups) {
    auto it = mesh.mesh.groups.find(g);
    if (it == mesh.mesh.groups.end()) {
      std::string have;
      for (const auto& [name, nodes] : mesh.mesh.groups) have += (have.empty() ? "" : ", ") + name;
      fail(file, "group '" + g + "' does not exist (it has: " + (have.empty() ? "none" : have) + ")");
    }
    if (it->second.empty()) fail(file, "group '" + g + "' has no nodes");
    out.insert(out.end(), it->second.begin(), it->second.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace pbd_io
