#pragma once
// Mesh input for the PBD model (the seed's step 1, "import the mesh"): gmsh .msh/.geo (through
// the gmsh API and the process's shared gmsh session), Wavefront OBJ and VTK .vtu. Lines,
// triangles and quadrilaterals; named node groups from gmsh physical groups, OBJ `g`/`o` groups
// and 0/1 point arrays of a VTU. Every problem is a one-line workbench::Error "file: what".
#include <pbd/mesh.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pbd_io {

struct LoadedMesh {
  pbd::Mesh mesh;
  std::vector<long long> node_names;  ///< the file's own node numbers (gmsh tags, OBJ 1-based, VTU 0-based)
};

/// Reads and checks a mesh (pbd::mesh_problem: zero-length edges, duplicate and isolated nodes,
/// bad cells). `parameters` set DefineConstant values of a .geo (an error for other formats).
LoadedMesh read_mesh(const std::filesystem::path& file, const std::map<std::string, double>& parameters = {});

/// The nodes of the named groups; "file: group 'x' does not exist (it has: ...)" for a missing
/// one, "file: group 'x' has no nodes" for an empty one.
std::vector<int> group_nodes(const LoadedMesh& mesh, const std::filesystem::path& file,
                             const std::vector<std::string>& groups);

}  // namespace pbd_io
