#pragma once
// The same-body check (docs/compare.md, "The two meshes are one body"): before a comparison solves
// anything, the agents' mesh and the reference's mesh (the true geometry) must be the same body with
// the same loads and supports, within what the agent size explains. A mismatch is bad input: a
// comparison of two different bodies would exit 0 with a wrong number.
#include <agent/mesh_import.h>
#include <agent_study.h>
#include <schema/compare_options.h>
#include <workbench/case_file.h>
#include <workbench/study_setup.h>

#include <Eigen/Core>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace compare {

/// A boundary group's shape: its measure (length in 2D, area in 3D, no thickness), centroid and
/// bounding box [m].
struct GroupShape {
  double measure = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = Eigen::Vector3d::Constant(-HUGE_VAL);
};

/// What the check compares of a mesh: its bounding box, its measure (area in 2D, volume in 3D) and
/// its boundary groups (physical groups of dimension dim - 1).
struct BodyShape {
  int dim = 0;
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  double measure = 0;
  double boundary = 0;  ///< the body's boundary measure (agents: the staircase's), for the measure's tolerance
  std::map<std::string, GroupShape> groups;
};

/// The agents' body: their squares or cubes and the boundary faces of each group.
BodyShape shape_of_agents(const agent::ImportedMesh& mesh);

/// A gmsh mesh's body (a .geo meshed with `parameters`, or a .msh; coordinates times `unit`): its
/// elements of the top dimension and its physical groups of one dimension less.
BodyShape shape_of_mesh(const std::filesystem::path& file, const std::map<std::string, double>& parameters, double unit);

/// A load patch whose agents' measure differs from the true one's by more than this share warns.
constexpr double kPatchMeasureWarning = 0.03;

/// Checks that `agents` (the agent model's body of `setup`, agent edge `size` [m]) and `reference`
/// (read from `reference_file`) are the same body: bounding boxes within an agent size per side,
/// measures within the staircase's boundary times an agent size, and each load's and rigid group's
/// centroid and bounding box within an agent size. A mismatch throws workbench::Error
/// "<case>: <key>: <group>: ... (both positions)", `key` naming what fixes it. Returns the warnings:
/// each load patch whose measure differs by more than kPatchMeasureWarning (the force stays the case's).
std::vector<std::string> check_same_body(const workbench::CaseFile& file, const std::string& key,
                                         const workbench::StudySetup& setup, double size, const BodyShape& agents,
                                         const BodyShape& reference, const std::filesystem::path& reference_file);

/// check_same_body of a comparison's agent study against its reference's mesh (`reference.mesh`,
/// in the case's mesh.unit), when the reference is on a mesh of its own; returns its warnings. Refuses
/// [compare.reference] tolerance in 2D (it applies to the 3D default).
std::vector<std::string> check_reference_body(const workbench::CaseFile& file, const agent_study::AgentStudy& study,
                                              const schema::ReferenceOptions& reference);

}  // namespace compare
