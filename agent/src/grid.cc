// The agent lattice: cells, air, faces and their boundary kinds.
#include <agent/grid.h>

#include <stdexcept>
#include <string>

namespace agent {

Grid Grid::box(int dim, std::array<int, 3> n, Eigen::Vector3d size, double thickness) {
  if (dim != 2 && dim != 3) throw std::invalid_argument("agent::Grid::box: dim must be 2 or 3");
  if (dim == 2) n[2] = 1;
  for (int a = 0; a < 3; ++a)
    if (n[a] < 1 || !(size[a] > 0)) throw std::invalid_argument("agent::Grid::box: counts and sizes must be positive");
  Grid g;
  g.dim = dim;
  g.cells = n;
  g.size = size;
  g.thickness = thickness;
  g.flags.assign(g.count(), 0);
  return g;
}

std::size_t Grid::agent_count() const {
  std::size_t n = 0;
  for (auto f : flags) n += !(f & kAirBit);
  return n;
}

std::size_t Grid::dense_neighbour(std::size_t cell, int side) const {
  const int a = axis_of(side);
  const int c = coords(cell)[a] + (is_positive(side) ? 1 : -1);
  if (c < 0 || c >= cells[a]) return npos;
  return is_positive(side) ? cell + stride(a) : cell - stride(a);
}

double Grid::face_area(int axis) const {
  if (dim == 2) return size[axis == 0 ? 1 : 0] * thickness;
  return size[(axis + 1) % 3] * size[(axis + 2) % 3];
}

Eigen::Vector3d Grid::centre(std::size_t cell) const {
  const auto c = coords(cell);
  Eigen::Vector3d x = origin;
  for (int a = 0; a < dim; ++a)
    x[a] = planes[a].empty() ? x[a] + (c[a] + 0.5) * size[a] : 0.5 * (plane(a, c[a]) + plane(a, c[a] + 1));
  return x;
}

std::size_t Grid::node_count() const {
  if (tiled()) return count();
  const auto n = node_counts();
  return std::size_t(n[0]) * n[1] * n[2];
}

std::array<int, 3> Grid::node_coords(std::size_t node) const {
  if (tiled()) return tiles.coords(node);
  const auto n = node_counts();
  const int i = int(node % n[0]);
  const std::size_t rest = node / n[0];
  return {i, int(rest % n[1]), int(rest / n[1])};
}

bool Grid::is_grid_node(std::size_t node) const {
  if (!tiled()) return node < node_count();
  const auto c = tiles.coords(node);
  const auto n = node_counts();
  return c[0] < n[0] && c[1] < n[1] && c[2] < n[2];
}

std::vector<BoundaryFace> Grid::boundary_faces() const {
  std::vector<BoundaryFace> out;
  for (std::size_t cell = 0; cell < count(); ++cell)
    if (!is_air(cell))
      for (int side = 0; side < 2 * dim; ++side)
        if (!has_neighbour(cell, side)) out.push_back({cell, side});
  return out;
}

std::vector<BoundaryFace> Grid::box_side(int side) const {
  std::vector<BoundaryFace> out;
  const int a = axis_of(side), at = is_positive(side) ? cells[a] - 1 : 0;
  for (std::size_t cell = 0; cell < count(); ++cell)
    if (!is_air(cell) && coords(cell)[a] == at) out.push_back({cell, side});
  return out;
}

void Grid::set_boundary(const std::vector<BoundaryFace>& faces, Boundary kind) {
  for (const auto& f : faces) {
    if (f.cell >= count() || is_air(f.cell) || has_neighbour(f.cell, f.side))
      throw std::invalid_argument("agent::Grid::set_boundary: cell " + std::to_string(f.cell) + " face " +
                                  std::to_string(f.side) + " is not a boundary face of the body");
    const auto bit = std::uint8_t(1u << f.side);
    flags[f.cell] = kind == Boundary::Rigid ? flags[f.cell] | bit : flags[f.cell] & ~bit;
  }
}

}  // namespace agent
