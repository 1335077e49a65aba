#pragma once
// The parts of a case file every model reads alike: the mesh, the material, the supports, the
// loads and the load steps (docs/case-file.md). Model-specific sections ([agent], [fem], ...)
// are read by their modules.
#include <workbench/case_file.h>
#include <workbench/load_spec.h>

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace workbench {

struct StudySetup {
  std::string title;
  std::filesystem::path mesh_file;                 ///< .geo or .msh, resolved against the case file
  std::map<std::string, double> mesh_parameters;   ///< [mesh.parameters], passed to the .geo
  double mesh_unit = 1.0;                          ///< [mesh] unit: metres per unit of the file's coordinates
  double agent_size = 0;                           ///< [mesh] agent_size [m]: > 0 voxelizes mesh_file for the agents
  double young = 206e9;                            ///< [Pa]
  double poisson = 0.3;
  double thickness = 1.0;                          ///< [m], 2D only
  std::vector<std::string> rigid_groups;           ///< clamped faces (the seed's rigid base)
  std::vector<std::string> roller_groups;          ///< [boundary] rollers: normal displacement zero (FEM)
  std::vector<LoadSpec> loads;                     ///< may be empty (a body under its weight, FEM)
  int steps = 1;                                   ///< load steps: k/steps of the loads, k = 1..steps
};

StudySetup read_study_setup(const CaseTable& root);

/// The names `[mesh] unit` takes, each with the metres it stands for (the one table of them).
const std::vector<std::pair<std::string, double>>& mesh_units();

/// A body whose bounding box's longest side [m] is above this or below kSmallestBody is a warning
/// naming mesh.unit: a millimetre part read as metres (or the other way round).
constexpr double kLargestBody = 20.0, kSmallestBody = 1e-4;

/// The warning for a body of longest side `longest` [m] read from `mesh` in `unit` (metres per unit,
/// [mesh] unit), "" when the size is plausible.
std::string body_size_warning(const std::filesystem::path& mesh, double unit, double longest);

/// Throws "case: key: group 'x' is not a physical group of mesh (it has: ...)" for a group the
/// case names that the mesh lacks.
void check_groups_exist(const CaseFile& file, const StudySetup& setup, const std::vector<std::string>& mesh_groups);

}  // namespace workbench
