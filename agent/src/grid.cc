// The agent lattice: cells, air, faces and their boundary kinds.
#include <agent/grid.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <limits>
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

Grid Grid::lattice(int dim, const std::array<const CompressedAxis*, 3>& axes, Eigen::Vector3d origin,
                   Eigen::Vector3d size) {
  std::array<int, 3> n{1, 1, 1};
  for (int a = 0; a < dim; ++a) {
    if (axes[a]->slots() > std::size_t(std::numeric_limits<int>::max() - 1))
      throw std::invalid_argument("agent::Grid::lattice: more slots along an axis than an int holds");
    n[a] = int(axes[a]->slots());
  }
  Grid g = box(dim, n, size);
  g.origin = origin;
  for (int a = 0; a < dim; ++a)
    if (axes[a]->collapsed()) {
      const auto& first = axes[a]->first;
      g.planes[a].resize(first.size());
      for (std::size_t p = 0; p < first.size(); ++p) g.planes[a][p] = origin[a] + double(first[p] - first[0]) * size[a];
    }
  return g;
}

std::size_t Grid::agent_count() const {
  std::size_t n = 0;
  for (auto f : flags) n += !(f & kAirBit);
  return n;
}

bool Grid::has_neighbour(std::size_t cell, int side) const {
  const int a = axis_of(side);
  const int c = coords(cell)[a];
  if (is_positive(side) ? c == cells[a] - 1 : c == 0) return false;
  const std::size_t s = stride(a);
  return !is_air(is_positive(side) ? cell + s : cell - s);
}

double Grid::face_area(int axis) const {
  if (dim == 2) return size[axis == 0 ? 1 : 0] * thickness;
  return size[(axis + 1) % 3] * size[(axis + 2) % 3];
}

Eigen::Vector3d Grid::centre(std::size_t cell) const {
  const auto c = coords(cell);
  Eigen::Vector3d x = origin;
  for (int a = 0; a < dim; ++a)
    x[a] = planes[a].empty() ? x[a] + (c[a] + 0.5) * size[a] : 0.5 * (planes[a][c[a]] + planes[a][c[a] + 1]);
  return x;
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

std::size_t Grid::node_count() const {
  const auto n = node_counts();
  return std::size_t(n[0]) * n[1] * n[2];
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
