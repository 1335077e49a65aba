#pragma once
// VTU (through VTK's XML writer) and PVD series output for meshes of points and cells.
// Used by the agent and PBD models; the FEM reference writes through deal.II's DataOut.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace workbench {

/// A mesh for output: points (x, y, z) and cells given by VTK cell type and point indices.
struct OutputMesh {
  std::vector<double> points;          // 3 per point
  std::vector<int> cell_types;         // VTK cell type per cell (VTK_LINE = 3, VTK_TRIANGLE = 5, VTK_QUAD = 9, VTK_HEXAHEDRON = 12)
  std::vector<long long> connectivity;  // point indices, cell after cell
  std::vector<long long> offsets;       // end of each cell in `connectivity`
  std::size_t point_count() const { return points.size() / 3; }
  std::size_t cell_count() const { return cell_types.size(); }
  void add_cell(int vtk_type, std::initializer_list<long long> ids);
};

/// A named field: `components` values per point or per cell.
struct Field {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

/// Writes one VTU file (binary, compressed). Throws workbench::Error if a field's size does not
/// match the mesh or holds a NaN or infinity, so that no non-finite value is written silently.
void write_vtu(const std::filesystem::path& file, const OutputMesh& mesh, const std::vector<Field>& point_fields,
               const std::vector<Field>& cell_fields);

/// Writes a ParaView collection: (time, file name relative to the PVD's folder) pairs.
void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& series);

}  // namespace workbench
