#pragma once
// Checks gmsh_load() makes before gmsh sees a file or meshes it (gmsh aborts or crashes on some
// bad input instead of reporting it). Each throws std::runtime_error "file: what".
#include <filesystem>
#include <string>

namespace workbench {

/// Reads an ASCII MSH 2.2 or 4.1 file without gmsh and refuses what gmsh would crash on or
/// silently accept: node tags outside [1, 2^31 - 1] or repeated, a non-finite coordinate, an
/// element naming a node that does not exist, an element type the workbench does not read, two
/// cells of the top dimension on the same nodes, a truncated section, a binary file; and a mesh
/// too large for the memory limit (workbench/memory_limit.h).
void check_msh_file(const std::filesystem::path& file);

/// Estimates the elements the loaded (not yet meshed) .geo model will have, from its transfinite
/// curve divisions and point mesh sizes, and refuses it when their memory exceeds the limit.
void check_geo_mesh_size(const std::filesystem::path& file);

/// Bytes per element of dimension dim (gmsh's mesh plus a model built on it), the estimate's
/// unit: measured with `workbench fem` (the heaviest consumer) on the seed plate.
double bytes_per_element(int dim);

}  // namespace workbench
