// The compressed lattice: which lattice planes a grid keeps, and where its planes lie.
#include <agent/grid.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace agent {

CompressedAxis::CompressedAxis(std::vector<std::int64_t> occupied) {
  if (occupied.empty()) throw std::invalid_argument("agent::CompressedAxis: no occupied coordinate");
  std::sort(occupied.begin(), occupied.end());
  occupied.erase(std::unique(occupied.begin(), occupied.end()), occupied.end());
  first.reserve(2 * occupied.size() + 1);
  first.push_back(occupied[0]);
  for (std::size_t i = 1; i < occupied.size(); ++i) {
    if (occupied[i] > occupied[i - 1] + 1) first.push_back(occupied[i - 1] + 1);  // one air slot for the gap
    first.push_back(occupied[i]);
  }
  first.push_back(occupied.back() + 1);
}

std::size_t CompressedAxis::slot(std::int64_t l) const {
  return std::size_t(std::upper_bound(first.begin(), first.end(), l) - first.begin()) - 1;
}

bool CompressedAxis::collapsed() const {
  for (std::size_t s = 0; s + 1 < first.size(); ++s)
    if (first[s + 1] - first[s] > 1) return true;
  return false;
}

namespace {

// Tile shape (log2 of slots per axis): 64 x 16 in 2D, 16 x 8 x 8 in 3D; 1024 slots either way.
std::array<int, 3> tile_shift(int dim) { return dim == 2 ? std::array<int, 3>{6, 4, 0} : std::array<int, 3>{4, 3, 3}; }

// Tiles per axis covering the box's nodes (cells + 1 along the grid's axes).
std::array<int, 3> tile_count(int dim, const std::array<int, 3>& cells, const std::array<int, 3>& shift) {
  std::array<int, 3> n{1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = int(((std::int64_t(cells[a]) + 1) + (std::int64_t(1) << shift[a]) - 1) >> shift[a]);
  return n;
}

// The tiles (linear numbers, x fastest) holding an agent or an agent's corner node, sorted, once each.
std::vector<std::uint64_t> stored_tiles(int dim, const std::array<int, 3>& cells, const std::vector<std::array<int, 3>>& agents) {
  const auto shift = tile_shift(dim);
  const auto count = tile_count(dim, cells, shift);
  std::vector<std::uint64_t> tiles;
  tiles.reserve(agents.size() / 8 + 16);
  const int corners = dim == 2 ? 4 : 8;
  for (const auto& c : agents) {
    std::uint64_t last = UINT64_MAX;
    for (int corner = 0; corner < corners; ++corner) {
      std::array<std::uint64_t, 3> t{0, 0, 0};
      for (int a = 0; a < dim; ++a) t[a] = std::uint64_t(c[a] + ((corner >> a) & 1)) >> shift[a];
      const std::uint64_t number = t[0] + std::uint64_t(count[0]) * (t[1] + std::uint64_t(count[1]) * t[2]);
      if (number != last && (tiles.empty() || tiles.back() != number)) tiles.push_back(number);
      last = number;
    }
  }
  std::sort(tiles.begin(), tiles.end());
  tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
  return tiles;
}

// Lays `g` (box, positions set; no slots yet) out on the tiles of `agents`, every slot air but the agents.
void lay_out_tiles(Grid& g, const std::vector<std::array<int, 3>>& agents) {
  Tiles& t = g.tiles;
  t.shift = tile_shift(g.dim);
  t.count = tile_count(g.dim, g.cells, t.shift);
  const auto stored = stored_tiles(g.dim, g.cells, agents);
  if (stored.size() >= std::size_t(Tiles::kNone)) throw std::invalid_argument("agent::Grid: more tiles than 32-bit tile numbers hold");
  t.number.assign(std::size_t(t.count[0]) * t.count[1] * t.count[2], Tiles::kNone);
  t.first.resize(stored.size());
  for (std::size_t s = 0; s < stored.size(); ++s) {
    t.number[stored[s]] = std::uint32_t(s);
    const std::uint64_t n = stored[s];
    const std::array<std::uint64_t, 3> tc{n % std::uint64_t(t.count[0]), (n / std::uint64_t(t.count[0])) % std::uint64_t(t.count[1]),
                                          n / (std::uint64_t(t.count[0]) * std::uint64_t(t.count[1]))};
    for (int a = 0; a < 3; ++a) t.first[s][a] = int(tc[a] << t.shift[a]);
  }
  g.flags.assign(g.count(), Grid::kAirBit);
  for (const auto& c : agents) g.flags[g.index(c[0], c[1], c[2])] = 0;
}

}  // namespace

// The lattice's box and positions, without slots (flags empty).
static Grid positioned(int dim, const std::array<const CompressedAxis*, 3>& axes, Eigen::Vector3d origin, Eigen::Vector3d size) {
  std::array<int, 3> n{1, 1, 1};
  for (int a = 0; a < dim; ++a) {
    if (axes[a]->slots() > std::size_t(std::numeric_limits<int>::max() - 1))
      throw std::invalid_argument("agent::Grid::lattice: more slots along an axis than an int holds");
    n[a] = int(axes[a]->slots());
  }
  Grid g = Grid::box(dim, {1, 1, 1}, size);
  g.flags.clear();
  g.cells = n;
  g.origin = origin;
  for (int a = 0; a < dim; ++a)
    if (axes[a]->collapsed()) {
      const auto& first = axes[a]->first;
      g.planes[a].resize(first.size());
      for (std::size_t p = 0; p < first.size(); ++p) g.planes[a][p] = origin[a] + double(first[p] - first[0]) * size[a];
    }
  return g;
}

Grid Grid::lattice(int dim, const std::array<const CompressedAxis*, 3>& axes, Eigen::Vector3d origin,
                   Eigen::Vector3d size) {
  Grid g = positioned(dim, axes, origin, size);
  g.flags.assign(g.count(), 0);
  return g;
}

Grid Grid::lattice(int dim, const std::array<const CompressedAxis*, 3>& axes, Eigen::Vector3d origin,
                   Eigen::Vector3d size, const std::vector<std::array<int, 3>>& agents) {
  Grid g = positioned(dim, axes, origin, size);
  for (const auto& c : agents)
    if (!g.in_box(c)) throw std::invalid_argument("agent::Grid::lattice: an agent lies outside the box");
  if (lattice_layout(dim, g.cells, agents).tiled) {
    lay_out_tiles(g, agents);
    return g;
  }
  g.flags.assign(g.count(), kAirBit);
  for (const auto& c : agents) g.flags[g.index(c[0], c[1], c[2])] = 0;
  return g;
}

LatticeLayout lattice_layout(int dim, const std::array<int, 3>& cells, const std::vector<std::array<int, 3>>& agents) {
  const double box = double(cells[0]) * cells[1] * cells[2];
  const double tiled = double(stored_tiles(dim, cells, agents).size() << Tiles::kSlotsLog2);
  if (!(2 * tiled <= box)) return {false, box, 0};
  const auto count = tile_count(dim, cells, tile_shift(dim));
  return {true, tiled, double(count[0]) * count[1] * count[2]};
}

Grid tile(const Grid& dense) {
  if (dense.tiled()) return dense;
  std::vector<std::array<int, 3>> agents;
  agents.reserve(dense.agent_count());
  for (std::size_t c = 0; c < dense.count(); ++c)
    if (!dense.is_air(c)) agents.push_back(dense.coords(c));
  Grid g = dense;
  g.flags.clear();
  lay_out_tiles(g, agents);
  for (std::size_t c = 0; c < dense.count(); ++c)
    if (!dense.is_air(c)) {
      const auto x = dense.coords(c);
      g.flags[g.index(x[0], x[1], x[2])] = dense.flags[c];
    }
  return g;
}

Eigen::Vector3d Grid::node_position(int i, int j, int k) const {
  const int at[3] = {i, j, k};
  Eigen::Vector3d x = origin;
  for (int a = 0; a < 3; ++a) x[a] = a < dim ? plane(a, at[a]) : origin[a] + 0.0;
  return x;
}

double Grid::slot_coordinate(int axis, double x) const {
  const auto& p = planes[axis];
  if (p.empty()) return (x - origin[axis]) / size[axis];
  if (!(x >= p.front())) return (x - p.front()) / size[axis];
  if (!(x < p.back())) return (x - p.back()) / size[axis] + double(p.size() - 1);
  const std::size_t i = std::size_t(std::upper_bound(p.begin(), p.end(), x) - p.begin()) - 1;
  return double(i) + (x - p[i]) / (p[i + 1] - p[i]);
}

double Grid::position(int axis, double s) const {
  const auto& p = planes[axis];
  if (p.empty()) return origin[axis] + s * size[axis];
  const double last = double(p.size() - 1);
  if (!(s >= 0)) return p.front() + s * size[axis];
  if (!(s < last)) return p.back() + (s - last) * size[axis];
  const std::size_t i = std::size_t(s);
  return p[i] + (s - double(i)) * (p[i + 1] - p[i]);
}

}  // namespace agent
