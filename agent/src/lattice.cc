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
