// VTU/PVTU/PVD writing for every module (VTK's XML writer; the two small XML records by hand).
#include <workbench/error.h>
#include <workbench/output_file.h>
#include <workbench/vtk_output.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

namespace workbench {

void OutputMesh::add_cell(int vtk_type, std::initializer_list<long long> ids) {
  cell_types.push_back(vtk_type);
  connectivity.insert(connectivity.end(), ids.begin(), ids.end());
  offsets.push_back(static_cast<long long>(connectivity.size()));
}

void OutputMesh::add_cell(int vtk_type, const std::vector<long long>& ids) {
  cell_types.push_back(vtk_type);
  connectivity.insert(connectivity.end(), ids.begin(), ids.end());
  offsets.push_back(static_cast<long long>(connectivity.size()));
}

namespace {
vtkNew<vtkDoubleArray> to_array(const Field& field, std::size_t count, const char* where,
                                const std::filesystem::path& file) {
  const std::size_t nc = static_cast<std::size_t>(field.components);
  if (field.components < 1 || field.values.size() != count * nc)
    throw Error(file.string() + ": field '" + field.name + "' has " + std::to_string(field.values.size()) +
                " values for " + std::to_string(count) + " " + where);
  if (!field.component_names.empty() && field.component_names.size() != nc)
    throw Error(file.string() + ": field '" + field.name + "' names " + std::to_string(field.component_names.size()) +
                " of its " + std::to_string(nc) + " components");
  if (!field.undefined.empty() && field.undefined.size() != count)
    throw Error(file.string() + ": field '" + field.name + "' marks " + std::to_string(field.undefined.size()) +
                " undefined entries for " + std::to_string(count) + " " + where);
  vtkNew<vtkDoubleArray> array;
  array->SetName(field.name.c_str());
  array->SetNumberOfComponents(field.components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(count));
  for (std::size_t c = 0; c < field.component_names.size(); ++c)
    array->SetComponentName(static_cast<vtkIdType>(c), field.component_names[c].c_str());
  double* out = array->GetPointer(0);
  for (std::size_t i = 0; i < field.values.size(); ++i) {
    if (!field.undefined.empty() && field.undefined[i / nc]) {
      out[i] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const double v = field.values[i];
    if (!std::isfinite(v)) throw Error(file.string() + ": field '" + field.name + "' holds a non-finite value");
    out[i] = v + 0.0;  // -0 + 0 is +0: ParaView would print "-0"
  }
  return array;
}
}  // namespace

void write_vtu(const std::filesystem::path& file, const OutputMesh& mesh, const std::vector<Field>& point_fields,
               const std::vector<Field>& cell_fields, std::size_t series_frames) {
  // One file at a time: the agent model writes its steps beside the FEM reference writing its own
  // (compare), and VTK's object factories and array type registry are not documented thread-safe.
  static std::mutex vtk_lock;
  std::lock_guard<std::mutex> hold(vtk_lock);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.point_count()));
  for (std::size_t i = 0; i < mesh.point_count(); ++i)
    points->SetPoint(static_cast<vtkIdType>(i), &mesh.points[3 * i]);

  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(static_cast<vtkIdType>(mesh.cell_count() + 1));
  offsets->SetValue(0, 0);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) offsets->SetValue(static_cast<vtkIdType>(c + 1), mesh.offsets[c]);
  connectivity->SetNumberOfTuples(static_cast<vtkIdType>(mesh.connectivity.size()));
  for (std::size_t i = 0; i < mesh.connectivity.size(); ++i)
    connectivity->SetValue(static_cast<vtkIdType>(i), mesh.connectivity[i]);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfTuples(static_cast<vtkIdType>(mesh.cell_count()));
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    types->SetValue(static_cast<vtkIdType>(c), static_cast<unsigned char>(mesh.cell_types[c]));

  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(types, cells);
  for (const auto& f : point_fields) grid->GetPointData()->AddArray(to_array(f, mesh.point_count(), "points", file));
  for (const auto& f : cell_fields) grid->GetCellData()->AddArray(to_array(f, mesh.cell_count(), "cells", file));

  // To memory, then to the disk through our checked writes: VTK 9.1's writer crashes (a bad free
  // in DeletePositionArrays) after a write that failed on a full disk.
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->WriteToOutputStringOn();
  writer->SetInputData(grid);
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  writer->SetCompressionLevel(1);  // zlib's fastest: at the default the seed study spent 0.2 s compressing
  if (writer->Write() != 1) throw Error(file.string() + ": VTK could not write the file");
  const std::string bytes = writer->GetOutputString();
  // The frames of a series are alike in size: the first one's, times their number, must fit.
  if (series_frames > 1)
    require_room(file.parent_path(), bytes.size() * series_frames,
                 "the series of " + std::to_string(series_frames) + " VTU files (" + std::to_string(bytes.size()) +
                     " bytes each)");
  write_file(file, bytes);
}

namespace {
std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

void write_pdata(std::ostream& out, const char* tag, const std::vector<Field>& fields) {
  out << "    <" << tag << ">\n";
  for (const auto& f : fields) {
    out << "      <PDataArray type=\"Float64\" Name=\"" << xml_escaped(f.name) << "\" NumberOfComponents=\""
        << f.components << "\"";
    for (std::size_t c = 0; c < f.component_names.size(); ++c)
      out << " ComponentName" << c << "=\"" << xml_escaped(f.component_names[c]) << "\"";
    out << "/>\n";
  }
  out << "    </" << tag << ">\n";
}
}  // namespace

void write_pvtu(const std::filesystem::path& file, const std::vector<std::string>& pieces,
                const std::vector<Field>& point_fields, const std::vector<Field>& cell_fields) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <PUnstructuredGrid GhostLevel=\"0\">\n";
  write_pdata(out, "PPointData", point_fields);
  write_pdata(out, "PCellData", cell_fields);
  out << "    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n    </PPoints>\n";
  for (const auto& p : pieces) out << "    <Piece Source=\"" << xml_escaped(p) << "\"/>\n";
  out << "  </PUnstructuredGrid>\n</VTKFile>\n";
  write_file(file, out.str());
}

void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& series) {
  std::ostringstream out;
  out.precision(17);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
  for (const auto& [time, name] : series)
    out << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << xml_escaped(name) << "\"/>\n";
  out << "  </Collection>\n</VTKFile>\n";
  write_file(file, out.str());
}

}  // namespace workbench
