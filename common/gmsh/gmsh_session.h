#pragma once
// gmsh keeps global state (models, options a .geo sets, ONELAB parameters, parser variables,
// error counters), shared by every module that meshes in this process. All of them load meshes
// through gmsh_load(), which starts every load from a freshly initialised gmsh.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace workbench {

/// Opens a gmsh .geo (and meshes it in its own dimension) or .msh file into gmsh's current model.
/// `parameters` override the .geo's DefineConstant values (ONELAB numbers); a name the .geo does
/// not declare is an error, and so are parameters for a .msh. Returns the names the .geo declares.
/// Before gmsh sees the file: parameters must be finite, a .msh passes check_msh_file(), a .geo's
/// estimated mesh must fit the memory limit (mesh_checks.h); after loading, every node coordinate
/// must be finite. Errors (no such file, a .geo's Error(), these checks, gmsh failures) are
/// std::runtime_error with a one-line message starting with the file name. The model stays
/// loaded until the next gmsh_load().
std::vector<std::string> gmsh_load(const std::filesystem::path& file, const std::map<std::string, double>& parameters);

/// An element of a physical group: its gmsh element type and its node tags.
struct GroupElement {
  int type;
  std::vector<std::size_t> nodes;
};

/// The physical groups of dimension `dim` of the loaded model, by name (an unnamed group by its
/// number), with their elements.
std::map<std::string, std::vector<GroupElement>> gmsh_physical_groups(int dim);

}  // namespace workbench
