#pragma once
// The simulation model: particles and constraints built from a mesh by the seed's rules
// (CN104268305A steps 1, 2 and 4a-4c) plus what a usable simulator needs (distance constraints on
// the edges, pinned nodes, physical masses and XPBD compliances). The time stepping is in solver.h.
#include <pbd/constraints.h>
#include <pbd/mesh.h>
#include <pbd/particles.h>

#include <vector>

namespace pbd {

struct ModelOptions {
  enum class Masses {
    Seed,    ///< the seed's m_i = total_mass / n for every node (the seed has total_mass = 1)
    Lumped,  ///< total_mass shared by cell length/area, each cell's share split over its corners
  } masses = Masses::Seed;
  double total_mass = 1.0;  ///< [kg]; Lumped counts only cells with a free node
  /// Bending: XPBD compliance of every angle constraint [1/(N m)], used when bending_stiffness is 0.
  /// 0 with bending_stiffness 0 = rigid angles (the seed's k = 1 in the XPBD limit).
  double bending_compliance = 0;
  /// E I [N m^2]: if > 0, each angle constraint gets compliance l_v / (E I), l_v = half the sum of
  /// its two edge lengths, not counting an edge between two pinned nodes (so half at a clamp).
  double bending_stiffness = 0;
  bool stretch = true;            ///< distance constraints on the mesh edges
  double stretch_compliance = 0;  ///< [m/N]; 0 = inextensible
  /// Unit axis of the signed angle form for a planar mesh (see constraints.h); zero vector = the
  /// unsigned form (3D meshes).
  Vec3 planar_axis = Vec3::Zero();
  /// Constraints per block of the parallel solve (see Model::angle_colouring).
  int block_size = 256;
};

/// Block b holds constraints [block_begin[b], block_begin[b+1]); colour c holds blocks
/// [colour_begin[c], colour_begin[c+1]).
struct Colouring {
  std::vector<std::size_t> block_begin{0};
  std::vector<std::size_t> colour_begin{0};
  std::size_t colours() const { return colour_begin.size() - 1; }
  std::size_t blocks() const { return block_begin.size() - 1; }
};

struct Model {
  Particles particles;
  std::vector<DistanceConstraint> distances;
  std::vector<AngleConstraint> angles;
  /// Blocks of consecutive constraints (kept in their geometric order, for locality and a natural
  /// Gauss-Seidel order), greedily coloured so that no two blocks of a colour share a particle:
  /// the blocks of a colour can be projected in parallel, each block serially.
  Colouring distance_colouring, angle_colouring;
  bool planar = false;
  Vec3 axis = Vec3::UnitZ();
  std::size_t raw_triple_count = 0;  ///< chains found by step 4b before deduplication
  const Vec3* axis_ptr() const { return planar ? &axis : nullptr; }
};

/// Builds the model; `pinned` lists node indices that do not move. Constraints are ordered by
/// the rest positions of their nodes (not their numbers) and then coloured, so that the solve does
/// not depend on node numbering. Constraints whose nodes are all pinned are dropped.
Model build_model(const Mesh& mesh, const std::vector<int>& pinned, const ModelOptions& options);

/// True when every point has the same z (relative tolerance of the bounding box).
bool lies_in_xy_plane(const std::vector<Vec3>& points);

/// Cuts both constraint arrays into blocks of `block_size` in their current order and colours the
/// blocks greedily, reordering the arrays colour by colour (build_model calls it).
void colour_constraints(Model& model, int block_size);

}  // namespace pbd
