#pragma once
// VTU (through VTK's XML writer), PVTU and PVD series output for meshes of points and cells: the
// one way every module (agent, PBD, FEM, comparison) writes files for ParaView.
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
  void add_cell(int vtk_type, const std::vector<long long>& ids);
};

/// A named field: `components` values per point or per cell. The name carries the unit, as
/// ParaView shows it: "sigma_y [Pa]", "displacement [m]", "[-]" for a dimensionless one.
struct Field {
  std::string name;
  int components = 1;
  std::vector<double> values;
  std::vector<std::string> component_names;  ///< empty, or one per component ("x", "+y", ...)
  std::vector<unsigned char> undefined;      ///< empty, or one per tuple: 1 = no value here, written as
                                             ///< NaN so that ParaView blanks it (a masked ratio)
};

/// Writes one VTU file (binary, compressed; made in memory, written by workbench::write_file).
/// Throws workbench::Error if a field's size does not match the mesh or holds a NaN or infinity
/// outside its `undefined` tuples, so that no non-finite value is written silently, and when a
/// write fails. Negative zeros are written as zeros. For the first file of a series of
/// `series_frames` alike files (a load step, a frame), the whole series must fit in the free space
/// first (workbench::require_room with this file's size times `series_frames`).
void write_vtu(const std::filesystem::path& file, const OutputMesh& mesh, const std::vector<Field>& point_fields,
               const std::vector<Field>& cell_fields, std::size_t series_frames = 1);

/// Writes a parallel VTU record naming `pieces` (file names relative to the PVTU's folder) that
/// hold the given fields (their names, components and component names; the values are ignored).
void write_pvtu(const std::filesystem::path& file, const std::vector<std::string>& pieces,
                const std::vector<Field>& point_fields, const std::vector<Field>& cell_fields);

/// Writes a ParaView collection: (time, file name relative to the PVD's folder) pairs.
void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& series);

}  // namespace workbench
