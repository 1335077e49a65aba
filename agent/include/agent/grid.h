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
/// The name of each direction (and of the box side it points to), in direction() order.
inline constexpr const char* kDirectionNames[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};
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

/// One axis of a compressed lattice (docs/agent-model.md, "Memory"): the lattice planes that hold
/// cells are kept, and every run of two or more empty planes collapses into one wide air slot.
/// Lattice coordinates are 64-bit integers (agent sizes from the lattice's origin).
struct CompressedAxis {
  /// Lattice coordinate of each plane of the compressed axis (slots + 1 values, increasing):
  /// slot s spans [first[s], first[s + 1]); an agent's slot spans one, a collapsed air slot more.
  std::vector<std::int64_t> first;
  /// Keeps the planes of the given lattice coordinates (any order, repeats allowed, not empty).
  explicit CompressedAxis(std::vector<std::int64_t> occupied);
  std::size_t slots() const { return first.size() - 1; }
  /// Slot holding lattice coordinate `l` (first[0] <= l < first.back()).
  std::size_t slot(std::int64_t l) const;
  /// Whether a run of empty planes was collapsed (some slot spans more than one coordinate).
  bool collapsed() const;
};

/// The tiles of a sparse grid (docs/agent-model.md, "Memory"): the box is cut into tiles of
/// 64 x 16 slots (2D) or 16 x 8 x 8 (3D), and only the tiles that hold an agent, with the tiles
/// just above them along each axis (they hold those agents' upper nodes), are stored. A slot's id
/// is then its tile's place among the stored tiles times 1024 plus its place in the tile (x
/// fastest): memory follows the tiles an agent touches, not the box.
struct Tiles {
  static constexpr int kSlotsLog2 = 10;        ///< 1024 slots per tile
  static constexpr std::uint32_t kNone = UINT32_MAX;
  std::array<int, 3> shift{};                  ///< log2 of a tile's slots per axis
  std::array<int, 3> count{1, 1, 1};           ///< tiles per axis, covering the box's nodes
  /// Per tile of the box (x fastest): its place among the stored tiles, kNone if not stored.
  std::vector<std::uint32_t> number;
  /// Per stored tile: the box coordinates of its first slot.
  std::vector<std::array<int, 3>> first;

  /// Id of slot (i, j, k) of the box; Grid::npos in a tile that is not stored.
  std::size_t id(int i, int j, int k) const {
    const std::uint32_t n = number[tile_of(i, j, k)];
    if (n == kNone) return std::size_t(-1);
    return (std::size_t(n) << kSlotsLog2) | std::size_t(i & ((1 << shift[0]) - 1)) |
           (std::size_t(j & ((1 << shift[1]) - 1)) << shift[0]) |
           (std::size_t(k & ((1 << shift[2]) - 1)) << (shift[0] + shift[1]));
  }
  /// Box coordinates of slot id `cell`.
  std::array<int, 3> coords(std::size_t cell) const {
    const auto& f = first[cell >> kSlotsLog2];
    const int local = int(cell & ((std::size_t(1) << kSlotsLog2) - 1));
    return {f[0] + (local & ((1 << shift[0]) - 1)), f[1] + ((local >> shift[0]) & ((1 << shift[1]) - 1)),
            f[2] + (local >> (shift[0] + shift[1]))};
  }
  /// The slot across face `side` of slot `cell` in a box of `cells`; npos outside the box or in a
  /// tile that is not stored. Inside the tile a step of the local id; across its side, the next
  /// tile's number from the table and the local id with the coordinate along the axis flipped.
  std::size_t neighbour(std::size_t cell, int side, const std::array<int, 3>& cells) const {
    const int a = side / 2, offset = a == 0 ? 0 : a == 1 ? shift[0] : shift[0] + shift[1];
    const int last = (1 << shift[a]) - 1, l = int(cell >> offset) & last;
    const auto& f = first[cell >> kSlotsLog2];
    const bool positive = side % 2 == 1;
    if (positive) {
      if (f[a] + l + 1 >= cells[a]) return std::size_t(-1);
      if (l < last) return cell + (std::size_t(1) << offset);
    } else {
      if (f[a] + l == 0) return std::size_t(-1);
      if (l > 0) return cell - (std::size_t(1) << offset);
    }
    const std::size_t step = a == 0 ? 1 : a == 1 ? std::size_t(count[0]) : std::size_t(count[0]) * count[1];
    const std::size_t tile = tile_of(f[0], f[1], f[2]);
    const std::uint32_t n = number[positive ? tile + step : tile - step];
    if (n == kNone) return std::size_t(-1);
    return (std::size_t(n) << kSlotsLog2) | ((cell & ((std::size_t(1) << kSlotsLog2) - 1)) ^ (std::size_t(last) << offset));
  }
  /// Bytes held by the tile table and the stored tiles' corners.
  std::size_t memory_bytes() const {
    return number.capacity() * sizeof(std::uint32_t) + first.capacity() * sizeof(std::array<int, 3>);
  }

 private:
  std::size_t tile_of(int i, int j, int k) const {
    return std::size_t(i >> shift[0]) +
           std::size_t(count[0]) * (std::size_t(j >> shift[1]) + std::size_t(count[1]) * std::size_t(k >> shift[2]));
  }
};

/// The agents: a set of equal, axis-aligned squares (2D) or cubes (3D) on a lattice. Each slot of
/// the bounding box has an id: a **dense** grid numbers every slot of the box (i fastest, then j,
/// then k), a **tiled** one (`tiles`, see agent::Tiles) only the slots of its stored tiles; a slot
/// that holds no agent is air, and so is every slot of a tile that lies beyond the box. Every face
/// between an agent and air or the box's outside is a boundary face, free unless marked rigid.
/// Along an axis the box may be compressed (`planes`): a run of empty lattice planes is one air
/// slot as wide as the gap, so memory follows the occupied planes; agents always have edge
/// `size`, and face adjacency is that of the uncompressed lattice. Nodes (slot corners) have ids
/// too: (cells + 1) per axis in a dense grid; in a tiled one, node (i, j, k) has the id of slot
/// (i, j, k), so that node ids beyond the box exist (is_grid_node tells them apart).
struct Grid {
  int dim = 2;                                 ///< 2 (squares) or 3 (cubes)
  std::array<int, 3> cells{1, 1, 1};           ///< bounding box in agents per axis; cells[2] == 1 in 2D
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< lower corner of the box [m]
  Eigen::Vector3d size = Eigen::Vector3d::Ones();    ///< agent edge length per axis [m]
  double thickness = 1.0;                      ///< out-of-plane thickness in 2D [m]
  /// Per slot id: bit `side` (0-5) marks that boundary face rigid, kAirBit marks air.
  std::vector<std::uint8_t> flags;
  static constexpr std::uint8_t kAirBit = 1 << 6;
  /// Per axis, the position of each slot boundary (cells[a] + 1 values) where the axis is
  /// compressed; empty where it is uniform (plane i at origin + i * size).
  std::array<std::vector<double>, 3> planes;
  /// The stored tiles of a tiled grid; `tiles.number` is empty in a dense one.
  Tiles tiles;
  /// No slot: outside the box, or in a tile that is not stored (air).
  static constexpr std::size_t npos = std::size_t(-1);

  /// A box of n[0] x n[1] (x n[2]) agents of the given size, every outer face free (dense).
  static Grid box(int dim, std::array<int, 3> n, Eigen::Vector3d size, double thickness = 1.0);

  /// The compressed box of the given axes (axes[2] unused in 2D), every slot an agent with free
  /// outer faces: lattice coordinate l of axis a lies at origin[a] + (l - first[0]) * size[a].
  /// A collapsed axis stores its planes; an axis without a collapsed run stays uniform (the
  /// same positions as Grid::box, bit for bit).
  static Grid lattice(int dim, const std::array<const CompressedAxis*, 3>& axes, Eigen::Vector3d origin,
                      Eigen::Vector3d size);

  /// The same lattice holding agents only at the given slots (box coordinates, repeats allowed),
  /// every other slot air, tiled or dense as agent::lattice_layout says; either way no array of
  /// the box's size is made.
  static Grid lattice(int dim, const std::array<const CompressedAxis*, 3>& axes, Eigen::Vector3d origin,
                      Eigen::Vector3d size, const std::vector<std::array<int, 3>>& agents);

  bool tiled() const { return !tiles.number.empty(); }
  /// Slot ids: the box's slots (dense), or the stored tiles' slots (tiled).
  std::size_t count() const {
    return tiled() ? tiles.first.size() << Tiles::kSlotsLog2 : std::size_t(cells[0]) * cells[1] * cells[2];
  }
  /// Agents: the slots that are not air.
  std::size_t agent_count() const;
  bool is_air(std::size_t cell) const { return flags[cell] & kAirBit; }
  /// Makes a slot air: its neighbours' faces toward it become (free) boundary faces.
  void make_air(std::size_t cell) { flags[cell] = kAirBit; }
  /// The agent across face `side` of `cell`, or false when that face is a boundary face.
  bool has_neighbour(std::size_t cell, int side) const {
    const std::size_t n = neighbour(cell, side);
    return n != npos && !is_air(n);
  }
  /// The slot across face `side` of slot `cell` (an agent or air), npos outside the box or in a
  /// tile that is not stored.
  std::size_t neighbour(std::size_t cell, int side) const {
    return tiled() ? tiles.neighbour(cell, side, cells) : dense_neighbour(cell, side);
  }
  /// Id step to the next slot along `axis` (dense grids only; a tiled grid steps with neighbour).
  std::size_t stride(int axis) const { return axis == 0 ? 1 : axis == 1 ? std::size_t(cells[0]) : std::size_t(cells[0]) * cells[1]; }
  /// Id of slot (i, j, k) of the box (0 <= i < cells[0], ...); npos in a tile that is not stored.
  std::size_t index(int i, int j, int k) const {
    if (!tiled()) return i + std::size_t(cells[0]) * (j + std::size_t(cells[1]) * k);
    return tiles.id(i, j, k);
  }
  /// Box coordinates of slot id `cell` (beyond the box for the air slots of an edge tile).
  std::array<int, 3> coords(std::size_t cell) const {
    if (tiled()) return tiles.coords(cell);
    const int i = int(cell % cells[0]);
    const std::size_t rest = cell / cells[0];
    return {i, int(rest % cells[1]), int(rest / cells[1])};
  }
  /// Whether box coordinates lie in the box.
  bool in_box(const std::array<int, 3>& c) const {
    return c[0] >= 0 && c[0] < cells[0] && c[1] >= 0 && c[1] < cells[1] && c[2] >= 0 && c[2] < cells[2];
  }
  /// Kind of a boundary face of an agent (meaningful where has_neighbour is false).
  Boundary boundary(int side, std::size_t cell) const {
    return (flags[cell] >> side) & 1 ? Boundary::Rigid : Boundary::Free;
  }
  Boundary boundary(int side, const std::array<int, 3>& c) const { return boundary(side, index(c[0], c[1], c[2])); }
  /// Area of an agent face whose normal is `axis` [m^2] (edge length times thickness in 2D).
  double face_area(int axis) const;
  /// Centre of a slot [m] (of an agent, or the middle of an air slot).
  Eigen::Vector3d centre(std::size_t cell) const;
  /// Position of plane (slot boundary) i along `axis` [m], i in [0, cells[axis]].
  /// (Beyond the box, for the node ids of a tiled grid's edge tiles: extended with the agent size.)
  double plane(int axis, int i) const {
    if (planes[axis].empty()) return origin[axis] + i * size[axis];
    return i <= cells[axis] ? planes[axis][i] : planes[axis].back() + (i - cells[axis]) * size[axis];
  }
  /// Position of node (i, j, k) [m] (z = origin z in 2D).
  Eigen::Vector3d node_position(int i, int j, int k) const;
  /// Position `x` [m] along `axis` in slots: i + the fraction of slot i below x (linear inside a
  /// slot; outside the box, extended with the agent size). Uniform: (x - origin) / size.
  double slot_coordinate(int axis, double x) const;
  /// Inverse of slot_coordinate: the position [m] at slot coordinate `s` along `axis`.
  double position(int axis, double s) const;
  /// Whether some axis is compressed (a run of empty planes is one wider air slot).
  bool compressed() const { return !planes[0].empty() || !planes[1].empty() || !planes[2].empty(); }
  /// Nodes per axis (cells + 1 along the grid's axes, 1 along z in 2D) and their count.
  std::array<int, 3> node_counts() const { return {cells[0] + 1, cells[1] + 1, dim == 3 ? cells[2] + 1 : 1}; }
  /// Node ids (dense: every node of the box; tiled: as many as slot ids, some beyond the box).
  std::size_t node_count() const;
  /// Id of node (i, j, k) (0 <= i <= cells[0], ...); tiled: npos where no agent has a corner
  /// and its tile is not stored.
  std::size_t node_index(int i, int j, int k) const {
    if (!tiled()) return i + std::size_t(cells[0] + 1) * (j + std::size_t(cells[1] + 1) * k);
    return tiles.id(i, j, k);
  }
  /// Box coordinates of node id `node`.
  std::array<int, 3> node_coords(std::size_t node) const;
  /// Whether node id `node` is a node of the box (a tiled grid has node ids beyond it).
  bool is_grid_node(std::size_t node) const;
  /// Every boundary face of the body (faces toward air or the box's outside), cell by cell.
  std::vector<BoundaryFace> boundary_faces() const;
  /// The faces of the agents on the box's outer side `side` (a support along a whole side).
  std::vector<BoundaryFace> box_side(int side) const;
  /// Marks the given boundary faces with a boundary kind.
  void set_boundary(const std::vector<BoundaryFace>& faces, Boundary kind);

 private:
  std::size_t dense_neighbour(std::size_t cell, int side) const;
};

/// How Grid::lattice lays out these agents (box coordinates) in a box of `cells`: on tiles when
/// the tiles that hold an agent or an agent's corner node have at most half the box's slots,
/// else dense. Computed without allocating the box (a sort of the agents' tile numbers).
struct LatticeLayout {
  bool tiled = false;
  double slots = 0;        ///< slot ids stored (the stored tiles' slots, or the box's)
  double tile_table = 0;   ///< entries of the tile table (tiles covering the box), 0 when dense
};
LatticeLayout lattice_layout(int dim, const std::array<int, 3>& cells, const std::vector<std::array<int, 3>>& agents);

/// The same body on tiles (tests and benchmarks): every agent, flag and position of a dense
/// grid, its slots renumbered by agent::Tiles. A tiled grid is returned as it is.
Grid tile(const Grid& dense);

}  // namespace agent
