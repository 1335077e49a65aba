// Stress, strain and displacement of the agents from their face forces.
#include <agent/fields.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

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

namespace {

// node_displacements on a tiled grid: the dense grid's numbers, bit for bit, from the stored tiles
// only. A column's line (its strain integrated from the box's lower side) changes only inside
// stored tiles (air adds 0.0 exactly), so it is integrated tile by tile along its tile column and
// read between them as the value it carried out of the last stored tile below. Each stored node
// then adds its adjacent columns in the dense loop's order (v, then w) and divides by their count.
// Cost: each column that a stored node touches once over its tile column's stored tiles.
std::vector<double> tiled_node_displacements(const Grid& grid, const std::vector<double>& strains, const Datums& datums) {
  const int dim = grid.dim;
  const Tiles& t = grid.tiles;
  std::vector<double> u(grid.node_count() * dim, 0.0);
  for (int a = 0; a < dim; ++a) {
    const int l0 = a == 0 ? 1 : 0, l1 = a == 2 ? 1 : 2;
    const int n = grid.cells[a], tile_a = 1 << t.shift[a];
    const double position = std::min(std::max(datums[a], 0.0), double(n));
    const int datum_cell = std::min(int(position), n - 1);
    const double frac = position - datum_cell;
    // The stored tiles along a of each tile column (tile coordinates on l0, l1), in order.
    std::map<std::pair<int, int>, std::vector<int>> along;
    for (const auto& first : t.first) along[{first[l0] >> t.shift[l0], first[l1] >> t.shift[l1]}].push_back(first[a] >> t.shift[a]);
    for (auto& [key, tiles] : along) std::sort(tiles.begin(), tiles.end());
    // A column's line at the nodes of its stored tiles ((tile_a + 1) values each) and its shift.
    struct Column {
      const std::vector<int>* tiles = nullptr;
      std::vector<double> line;
      double shift = 0;
    };
    std::map<std::pair<int, int>, Column> columns;
    auto line_at = [&](const Column& c, int i) {
      if (!c.tiles) return 0.0;
      const auto& tiles = *c.tiles;
      const auto it = std::upper_bound(tiles.begin(), tiles.end(), i / tile_a);  // tiles starting at or below i
      if (it == tiles.begin()) return 0.0;
      const std::size_t k = std::size_t(it - tiles.begin()) - 1;
      const int r = std::min(i - tiles[k] * tile_a, tile_a);  // past the tile: what it carried out
      return c.line[k * (tile_a + 1) + r];
    };
    auto column = [&](int w, int v) -> const Column& {
      auto [entry, added] = columns.try_emplace({w, v});
      Column& c = entry->second;
      if (!added) return c;
      const auto found = along.find({w >> t.shift[l0], v >> t.shift[l1]});
      if (found == along.end()) return c;
      c.tiles = &found->second;
      c.line.resize(c.tiles->size() * (tile_a + 1));
      double carried = 0.0;
      std::array<int, 3> at{};
      at[l0] = w;
      at[l1] = v;
      for (std::size_t k = 0; k < c.tiles->size(); ++k) {
        const int i0 = (*c.tiles)[k] * tile_a;
        double* line = &c.line[k * (tile_a + 1)];
        line[0] = carried;
        for (int r = 0; r < tile_a; ++r) {
          at[a] = i0 + r;
          if (at[a] < n) carried = carried + strains[3 * grid.index(at[0], at[1], at[2]) + a] * grid.size[a];
          line[r + 1] = carried;
        }
      }
      const double below = line_at(c, datum_cell), above = line_at(c, datum_cell + 1);
      c.shift = below + frac * (above - below);
      return c;
    };
    for (std::size_t node = 0; node < grid.node_count(); ++node) {
      if (!grid.is_grid_node(node)) continue;
      const auto p = grid.node_coords(node);
      double sum = 0.0, weight = 0;
      const int v_lo = dim == 3 ? p[l1] - 1 : 0, v_hi = dim == 3 ? p[l1] : 0;
      for (int v = std::max(v_lo, 0); v <= std::min(v_hi, grid.cells[l1] - 1); ++v)
        for (int w = std::max(p[l0] - 1, 0); w <= std::min(p[l0], grid.cells[l0] - 1); ++w) {
          const Column& c = column(w, v);
          sum += line_at(c, p[a]) - c.shift;
          weight += 1;
        }
      u[node * dim + a] = sum / weight;
    }
  }
  return u;
}

}  // namespace

std::vector<double> node_displacements(const Grid& grid, const std::vector<double>& strains, const Datums& datums) {
  if (grid.tiled()) return tiled_node_displacements(grid, strains, datums);
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
