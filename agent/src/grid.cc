#include <agent/grid.h>

#include <stdexcept>

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
  for (int side = 0; side < 2 * dim; ++side) {
    const int a = axis_of(side);
    std::size_t count = 1;
    for (int b = 0; b < 3; ++b)
      if (b != a) count *= std::size_t(n[b]);
    g.sides[side].assign(count, Boundary::Free);
  }
  return g;
}

std::size_t Grid::side_slot(int side, const std::array<int, 3>& c) const {
  const int a = axis_of(side);
  const int b = a == 0 ? 1 : 0, d = a == 2 ? 1 : 2;  // the other two axes, ascending
  return std::size_t(c[b]) + std::size_t(cells[b]) * c[d];
}

double Grid::face_area(int axis) const {
  if (dim == 2) return size[axis == 0 ? 1 : 0] * thickness;
  return size[(axis + 1) % 3] * size[(axis + 2) % 3];
}

Eigen::Vector3d Grid::centre(std::size_t cell) const {
  const auto c = coords(cell);
  Eigen::Vector3d x = origin;
  for (int a = 0; a < dim; ++a) x[a] += (c[a] + 0.5) * size[a];
  return x;
}

std::size_t Grid::node_count() const {
  const auto n = node_counts();
  return std::size_t(n[0]) * n[1] * n[2];
}

void Grid::set_boundary(const std::vector<BoundaryFace>& faces, Boundary kind) {
  for (const auto& f : faces) sides[f.side][side_slot(f.side, coords(f.cell))] = kind;
}

}  // namespace agent
