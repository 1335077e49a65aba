#pragma once
// How slot ids are laid out: the one place the layout varies. A dense grid numbers every slot of
// its box (ids by strides), a tiled one only the slots of its stored tiles (agent::Tiles: ids
// through the tile table, Grid::npos for a tile that is not stored). DenseSlots and TiledSlots
// have the same inline interface, and every algorithm that walks the grid (the sweep and its
// clearing, the directional rule set, node_displacements) is written once as a template over it:
//
//   layer(axis, index)     the slots of one layer across `axis`: layer(u, v) is the id at lateral
//                          position u along l0, v along l1 (agent::lateral_axes);
//   layer(...).row(v)      the ids of one row along l0: row(u), and row.runs(lo, hi, f): f(first,
//                          count) for each run of consecutive stored ids (for filling);
//   lane(axis).next(c, s)  the slot one step (s = +1 or -1) along `axis` from slot c, the caller
//                          staying inside the box;
//   air(id), rigid(id, side), blocks().
//
// with_slots(grid, f) calls f with the grid's Slots.
#include <agent/grid.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace agent {

/// The lateral axes of a load moving along `axis`: l0 (rows run along it) and l1 (one slot in 2D).
struct LateralAxes {
  int l0, l1;
};
constexpr LateralAxes lateral_axes(int axis) { return {axis == 0 ? 1 : 0, axis == 2 ? 1 : 2}; }

/// Blocks of slots that hold storage, for walks that skip what is not stored: the dense box is
/// one block of (cells + 1) per axis (its nodes included), a tiled grid's blocks are its tiles.
struct Blocks {
  std::array<int, 3> size;                        ///< slots per block and axis
  const std::vector<std::array<int, 3>>* first;   ///< box coordinates of each block's first slot
};

class DenseSlots {
 public:
  explicit DenseSlots(const Grid& g)
      : flags_(g.flags.data()), stride_{1, std::size_t(g.cells[0]), std::size_t(g.cells[0]) * g.cells[1]},
        block_{{g.cells[0] + 1, g.cells[1] + 1, g.cells[2] + 1}, &kOrigin} {}

  struct Row {
    std::size_t base, step;
    std::size_t operator()(int u) const { return base + u * step; }
    template <class F>
    void runs(int lo, int hi, F&& f) const {
      if (step == 1) return f(base + lo, std::size_t(hi - lo + 1));
      for (int u = lo; u <= hi; ++u) f(base + u * step, std::size_t(1));
    }
  };
  struct Layer {
    std::size_t base, s0, s1;
    std::size_t operator()(int u, int v) const { return base + u * s0 + v * s1; }
    Row row(int v) const { return {base + v * s1, s0}; }
  };
  struct Lane {
    int axis;
    long stride;
    std::size_t next(std::size_t cell, int sgn) const { return cell + sgn * stride; }
  };

  Layer layer(int axis, int index) const {
    const auto l = lateral_axes(axis);
    return {std::size_t(index) * stride_[axis], stride_[l.l0], stride_[l.l1]};
  }
  Lane lane(int axis) const { return {axis, long(stride_[axis])}; }
  bool air(std::size_t cell) const { return (flags_[cell] & Grid::kAirBit) != 0; }
  bool rigid(std::size_t cell, int side) const { return (flags_[cell] >> side) & 1; }
  const Blocks& blocks() const { return block_; }

 private:
  static inline const std::vector<std::array<int, 3>> kOrigin{{0, 0, 0}};
  const std::uint8_t* flags_;
  std::array<std::size_t, 3> stride_;
  Blocks block_;
};

class TiledSlots {
 public:
  explicit TiledSlots(const Grid& g)
      : flags_(g.flags.data()), tiles_(&g.tiles), cells_(g.cells),
        block_{{1 << g.tiles.shift[0], 1 << g.tiles.shift[1], 1 << g.tiles.shift[2]}, &g.tiles.first} {}

  /// One tile-table read per id, the rest bit operations.
  struct Row {
    const std::uint32_t* number;
    std::size_t tile_base, tile_step, local;
    int shift, mask, offset;
    std::size_t operator()(int u) const {
      const std::uint32_t n = number[tile_base + std::size_t(u >> shift) * tile_step];
      if (n == Tiles::kNone) return Grid::npos;
      return (std::size_t(n) << Tiles::kSlotsLog2) | local | (std::size_t(u & mask) << offset);
    }
    template <class F>
    void runs(int lo, int hi, F&& f) const {
      for (int u = lo; u <= hi;) {
        const int end = std::min(hi, u | mask);  // the last position of this tile
        const std::size_t first = (*this)(u);
        if (first != Grid::npos) {
          if (offset == 0) f(first, std::size_t(end - u + 1));  // along x: consecutive ids
          else
            for (int w = u; w <= end; ++w) f((*this)(w), std::size_t(1));
        }
        u = end + 1;
      }
    }
  };
  struct Layer {
    const TiledSlots* slots;
    int axis, index;
    std::size_t operator()(int u, int v) const {
      std::array<int, 3> c{};
      const auto l = lateral_axes(axis);
      c[axis] = index;
      c[l.l0] = u;
      c[l.l1] = v;
      return slots->tiles_->id(c[0], c[1], c[2]);
    }
    Row row(int v) const {
      std::array<int, 3> c{};
      const auto l = lateral_axes(axis);
      c[axis] = index;
      c[l.l1] = v;
      return slots->row(l.l0, c);
    }
  };
  struct Lane {
    int axis;
    const Tiles* tiles;
    const std::array<int, 3>* cells;
    std::size_t next(std::size_t cell, int sgn) const { return tiles->neighbour(cell, direction(axis, sgn > 0), *cells); }
  };

  Layer layer(int axis, int index) const { return {this, axis, index}; }
  Lane lane(int axis) const { return {axis, tiles_, &cells_}; }
  bool air(std::size_t cell) const { return cell == Grid::npos || (flags_[cell] & Grid::kAirBit) != 0; }
  bool rigid(std::size_t cell, int side) const { return cell != Grid::npos && ((flags_[cell] >> side) & 1); }
  const Blocks& blocks() const { return block_; }

 private:
  // The row along axis `along` through box coordinates `c` (c[along] ignored).
  Row row(int along, std::array<int, 3> c) const {
    const Tiles& t = *tiles_;
    const std::array<int, 3> offset{0, t.shift[0], t.shift[0] + t.shift[1]};
    const std::array<std::size_t, 3> step{1, std::size_t(t.count[0]), std::size_t(t.count[0]) * t.count[1]};
    c[along] = 0;
    Row r{t.number.data(), 0, step[along], 0, t.shift[along], (1 << t.shift[along]) - 1, offset[along]};
    for (int x = 0; x < 3; ++x) {
      r.tile_base += std::size_t(c[x] >> t.shift[x]) * step[x];
      r.local |= std::size_t(c[x] & ((1 << t.shift[x]) - 1)) << offset[x];
    }
    return r;
  }

  const std::uint8_t* flags_;
  const Tiles* tiles_;
  std::array<int, 3> cells_;
  Blocks block_;
};

/// Calls f(DenseSlots) or f(TiledSlots), as the grid is laid out, and returns what f returns.
template <class F>
decltype(auto) with_slots(const Grid& grid, F&& f) {
  if (grid.tiled()) return f(TiledSlots(grid));
  return f(DenseSlots(grid));
}

}  // namespace agent
