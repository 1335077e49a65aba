#pragma once
// The agents of the load-transfer method: a structured grid of equal, axis-aligned squares (2D)
// or boxes (3D), one agent per cell, with the kind of boundary on every outer face.
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace agent {

/// Face directions and outer sides of the box: 0 = -x, 1 = +x, 2 = -y, 3 = +y, 4 = -z, 5 = +z.
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

/// An outer face of the grid: the agent it belongs to and its outward direction.
struct BoundaryFace {
  std::size_t cell;
  int side;
};

struct Grid {
  int dim = 2;                                 ///< 2 (squares) or 3 (cubes)
  std::array<int, 3> cells{1, 1, 1};           ///< agents per axis; cells[2] == 1 in 2D
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< lower corner [m]
  Eigen::Vector3d size = Eigen::Vector3d::Ones();    ///< agent edge length per axis [m]
  double thickness = 1.0;                      ///< out-of-plane thickness in 2D [m]
  /// Boundary kind of each outer face, per side; a side's faces are indexed by side_slot().
  std::array<std::vector<Boundary>, 6> sides;

  /// A box of n[0] x n[1] (x n[2]) agents of the given size, every outer face free.
  static Grid box(int dim, std::array<int, 3> n, Eigen::Vector3d size, double thickness = 1.0);

  std::size_t count() const { return std::size_t(cells[0]) * cells[1] * cells[2]; }
  std::size_t stride(int axis) const { return axis == 0 ? 1 : axis == 1 ? std::size_t(cells[0]) : std::size_t(cells[0]) * cells[1]; }
  std::size_t index(int i, int j, int k) const { return i + std::size_t(cells[0]) * (j + std::size_t(cells[1]) * k); }
  std::array<int, 3> coords(std::size_t cell) const {
    const int i = int(cell % cells[0]);
    const std::size_t rest = cell / cells[0];
    return {i, int(rest % cells[1]), int(rest / cells[1])};
  }
  /// Index of a cell's face on outer side `side` within sides[side].
  std::size_t side_slot(int side, const std::array<int, 3>& c) const;
  Boundary boundary(int side, const std::array<int, 3>& c) const { return sides[side][side_slot(side, c)]; }
  /// Area of an agent face whose normal is `axis` [m^2] (edge length times thickness in 2D).
  double face_area(int axis) const;
  /// Centre of an agent [m].
  Eigen::Vector3d centre(std::size_t cell) const;
  /// Nodes per axis (cells + 1 along the grid's axes, 1 along z in 2D) and their count.
  std::array<int, 3> node_counts() const { return {cells[0] + 1, cells[1] + 1, dim == 3 ? cells[2] + 1 : 1}; }
  std::size_t node_count() const;
  std::size_t node_index(int i, int j, int k) const { return i + std::size_t(cells[0] + 1) * (j + std::size_t(cells[1] + 1) * k); }
  /// Marks the given outer faces with a boundary kind.
  void set_boundary(const std::vector<BoundaryFace>& faces, Boundary kind);
};

}  // namespace agent
