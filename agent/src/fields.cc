// Stress, strain and displacement of the agents from their face forces.
#include <agent/fields.h>

#include <algorithm>
#include <cmath>

namespace agent {

std::vector<double> agent_stresses(const Grid& grid, const std::vector<double>& face_forces) {
  const int dim = grid.dim, nd = 2 * dim;
  std::vector<double> sigma(grid.count() * dim);
  std::array<double, 3> area{};
  for (int a = 0; a < dim; ++a) area[a] = grid.face_area(a);
  for (std::size_t c = 0; c < grid.count(); ++c)
    for (int a = 0; a < dim; ++a)
      sigma[c * dim + a] = -0.5 * (face_forces[c * nd + 2 * a] + face_forces[c * nd + 2 * a + 1]) / area[a];
  return sigma;
}

std::vector<double> agent_stresses(const Grid& grid, const std::vector<double>& face_forces, const Readings& readings,
                                   int load_dir, double beta, double poisson) {
  auto sigma = agent_stresses(grid, face_forces);
  if (!readings.entering_face_stress && !readings.lateral_strain_stress) return sigma;
  const int dim = grid.dim, nd = 2 * dim, a = axis_of(load_dir), enter_face = opposite(load_dir);
  const double area = grid.face_area(a);
  for (std::size_t c = 0; c < grid.count(); ++c) {
    double* s = &sigma[c * dim];
    if (readings.entering_face_stress) s[a] = -face_forces[c * nd + enter_face] / area;
    if (readings.lateral_strain_stress)
      for (int l = 0; l < dim; ++l)
        if (l != a) s[l] = -beta * poisson * s[a];
  }
  return sigma;
}

std::vector<double> agent_strains(const Grid& grid, const Material& m, const std::vector<double>& stresses) {
  const int dim = grid.dim;
  const double E = m.young, nu = m.poisson;
  std::vector<double> eps(grid.count() * 3);
  for (std::size_t c = 0; c < grid.count(); ++c) {
    const double sx = stresses[c * dim], sy = stresses[c * dim + 1], sz = dim == 3 ? stresses[c * dim + 2] : 0.0;
    eps[3 * c + 0] = (sx - nu * (sy + sz)) / E;
    eps[3 * c + 1] = (sy - nu * (sx + sz)) / E;
    eps[3 * c + 2] = (sz - nu * (sx + sy)) / E;
  }
  return eps;
}

Datums choose_datums(const Grid& grid, const std::vector<EntryLoad>& loads) {
  Datums datums{0, 0, 0};
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double total = 0;
  for (const auto& l : loads) {
    centre += l.force * grid.centre(l.cell);
    total += l.force;
  }
  if (total > 0) centre /= total;
  // The lowest rigid face looking down each axis (or, failing that, the highest looking up).
  std::array<double, 3> low{}, high{};
  std::array<bool, 3> has_low{}, has_high{};
  for (const auto& f : grid.boundary_faces()) {
    if (grid.boundary(f.side, f.cell) != Boundary::Rigid) continue;
    const int a = axis_of(f.side);
    const double at = grid.coords(f.cell)[a] + (is_positive(f.side) ? 1.0 : 0.0);
    if (!is_positive(f.side)) {
      low[a] = has_low[a] ? std::min(low[a], at) : at;
      has_low[a] = true;
    } else {
      high[a] = has_high[a] ? std::max(high[a], at) : at;
      has_high[a] = true;
    }
  }
  for (int a = 0; a < grid.dim; ++a) {
    if (has_low[a])
      datums[a] = low[a];
    else if (has_high[a])
      datums[a] = high[a];
    else
      datums[a] = total > 0 ? grid.slot_coordinate(a, centre[a]) : 0.5 * grid.cells[a];
  }
  return datums;
}

std::vector<double> node_displacements(const Grid& grid, const std::vector<double>& strains, const Datums& datums) {
  const int dim = grid.dim;
  std::vector<double> u(grid.node_count() * dim, 0.0);
  std::vector<double> weight(grid.node_count());
  std::vector<double> line;
  for (int a = 0; a < dim; ++a) {
    const int l0 = a == 0 ? 1 : 0, l1 = a == 2 ? 1 : 2;
    const int n = grid.cells[a];
    // The datum sits in agent `cell` at fraction `frac` of its length.
    const double position = std::min(std::max(datums[a], 0.0), double(n));
    const int cell = std::min(int(position), n - 1);
    const double frac = position - cell;
    std::fill(weight.begin(), weight.end(), 0.0);
    line.assign(n + 1, 0.0);
    for (int v = 0; v < grid.cells[l1]; ++v)
      for (int w = 0; w < grid.cells[l0]; ++w) {
        std::array<int, 3> c{};
        c[l0] = w;
        c[l1] = v;
        auto strain = [&](int i) {
          c[a] = i;
          return strains[3 * grid.index(c[0], c[1], c[2]) + a] * grid.size[a];
        };
        // Integrate the column's strain from its first node, then shift to zero at the datum.
        for (int i = 0; i < n; ++i) line[i + 1] = line[i] + strain(i);
        const double shift = line[cell] + frac * (line[cell + 1] - line[cell]);
        // Add to the nodes of this column's cells (2 node lines across in 2D, 4 in 3D).
        const int corners_v = dim == 3 ? 2 : 1;
        for (int dv = 0; dv < corners_v; ++dv)
          for (int dw = 0; dw < 2; ++dw)
            for (int i = 0; i <= n; ++i) {
              std::array<int, 3> p{};
              p[a] = i;
              p[l0] = w + dw;
              p[l1] = v + dv;
              const std::size_t node = grid.node_index(p[0], p[1], p[2]);
              u[node * dim + a] += line[i] - shift;
              weight[node] += 1;
            }
      }
    for (std::size_t node = 0; node < grid.node_count(); ++node) u[node * dim + a] /= weight[node];
  }
  return u;
}

}  // namespace agent
