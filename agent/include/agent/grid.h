#pragma once
// The agents of the load-transfer method: any set of equal, axis-aligned squares (2D) or boxes
// (3D) on a lattice, one agent per cell, with the kind of boundary on every face toward air.
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace agent {

/// Face directions: 0 = -x, 1 = +x, 2 = -y, 3 = +y, 4 = -z, 5 = +z.
/// direction = 2 * axis + (positive ? 1 : 0).
constexpr int direction(int axis, bool positive) { return 2 * axis + (positive ? 1 : 0); }
constexpr int axis_of(int dir) { return dir / 2; }
constexpr bool is_positive(int dir) { return dir % 2 == 1; }
constexpr int opposite(int dir) { return dir ^ 1; }

/// What surrounds an outer face of the body (seed: "boundary agents").
enum class Boundary : std::uint8_t {
  Free,   ///< air, water, vacuum: a load is passed out unchanged, nothing pushes back
  Rigid,  ///< displacement constrained: a load of equal value is returned (a reaction)
};

/// A face between an agent and what is not the body (air, or outside the box): the agent it
/// belongs to and its outward direction.
struct BoundaryFace {
  std::size_t cell;
  int side;
};

/// The agents: a set of equal, axis-aligned squares (2D) or cubes (3D) on a lattice. Cells are
/// addressed in their bounding box (i fastest, then j, then k); a slot of the box that holds no
/// agent is air. Every face between an agent and air or the box's outside is a boundary face,
/// free unless marked rigid.
struct Grid {
  int dim = 2;                                 ///< 2 (squares) or 3 (cubes)
  std::array<int, 3> cells{1, 1, 1};           ///< bounding box in agents per axis; cells[2] == 1 in 2D
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< lower corner of the box [m]
  Eigen::Vector3d size = Eigen::Vector3d::Ones();    ///< agent edge length per axis [m]
  double thickness = 1.0;                      ///< out-of-plane thickness in 2D [m]
  /// Per slot of the box: bit `side` (0-5) marks that boundary face rigid, kAirBit marks air.
  std::vector<std::uint8_t> flags;
  static constexpr std::uint8_t kAirBit = 1 << 6;

  /// A box of n[0] x n[1] (x n[2]) agents of the given size, every outer face free.
  static Grid box(int dim, std::array<int, 3> n, Eigen::Vector3d size, double thickness = 1.0);

  /// Slots of the bounding box (agents and air).
  std::size_t count() const { return std::size_t(cells[0]) * cells[1] * cells[2]; }
  /// Agents: the slots that are not air.
  std::size_t agent_count() const;
  bool is_air(std::size_t cell) const { return flags[cell] & kAirBit; }
  /// Makes a slot air: its neighbours' faces toward it become (free) boundary faces.
  void make_air(std::size_t cell) { flags[cell] = kAirBit; }
  /// The agent across face `side` of `cell`, or false when that face is a boundary face.
  bool has_neighbour(std::size_t cell, int side) const;
  std::size_t stride(int axis) const { return axis == 0 ? 1 : axis == 1 ? std::size_t(cells[0]) : std::size_t(cells[0]) * cells[1]; }
  std::size_t index(int i, int j, int k) const { return i + std::size_t(cells[0]) * (j + std::size_t(cells[1]) * k); }
  std::array<int, 3> coords(std::size_t cell) const {
    const int i = int(cell % cells[0]);
    const std::size_t rest = cell / cells[0];
    return {i, int(rest % cells[1]), int(rest / cells[1])};
  }
  /// Kind of a boundary face of an agent (meaningful where has_neighbour is false).
  Boundary boundary(int side, std::size_t cell) const {
    return (flags[cell] >> side) & 1 ? Boundary::Rigid : Boundary::Free;
  }
  Boundary boundary(int side, const std::array<int, 3>& c) const { return boundary(side, index(c[0], c[1], c[2])); }
  /// Area of an agent face whose normal is `axis` [m^2] (edge length times thickness in 2D).
  double face_area(int axis) const;
  /// Centre of an agent [m].
  Eigen::Vector3d centre(std::size_t cell) const;
  /// Nodes per axis (cells + 1 along the grid's axes, 1 along z in 2D) and their count.
  std::array<int, 3> node_counts() const { return {cells[0] + 1, cells[1] + 1, dim == 3 ? cells[2] + 1 : 1}; }
  std::size_t node_count() const;
  std::size_t node_index(int i, int j, int k) const { return i + std::size_t(cells[0] + 1) * (j + std::size_t(cells[1] + 1) * k); }
  /// Every boundary face of the body (faces toward air or the box's outside), cell by cell.
  std::vector<BoundaryFace> boundary_faces() const;
  /// The faces of the agents on the box's outer side `side` (a support along a whole side).
  std::vector<BoundaryFace> box_side(int side) const;
  /// Marks the given boundary faces with a boundary kind.
  void set_boundary(const std::vector<BoundaryFace>& faces, Boundary kind);
};

}  // namespace agent
