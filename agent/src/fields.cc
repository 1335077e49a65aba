// Stress, strain and displacement of the agents from their face forces.
#include <agent/fields.h>
#include <agent/slots.h>

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <utility>

namespace agent {

namespace {
constexpr double kPi = 3.14159265358979323846;

/// The cosine transform y_m = sum_{i=0..n} w_i x_i cos(pi m i / n), w = 1/2 at both ends (DCT-I),
/// by a real FFT of the even extension (Eigen's FFT): n log n, not the (n + 1)^2 of the sums.
class CosineTransform {
 public:
  explicit CosineTransform(int n) : n_(n), even_(2 * std::size_t(n)) {}
  void apply(const double* x, double* y) {
    for (int i = 0; i <= n_; ++i) even_[std::size_t(i)] = x[i];
    for (int i = 1; i < n_; ++i) even_[2 * std::size_t(n_) - std::size_t(i)] = x[i];
    fft_.fwd(spectrum_, even_);
    for (int m = 0; m <= n_; ++m) y[m] = 0.5 * spectrum_[std::size_t(m)].real();
  }

 private:
  int n_;
  std::vector<double> even_;
  std::vector<std::complex<double>> spectrum_;
  Eigen::FFT<double> fft_;
};

/// Calls f(cell, side) for every rigid boundary face, in Grid::boundary_faces' order. Only the
/// agents with a rigid bit are looked at: listing every boundary face to keep the rigid ones cost
/// a fifth of the patent rule set's whole solve.
template <class F>
void for_each_rigid_face(const Grid& grid, F&& f) {
  constexpr std::uint8_t kRigidBits = (1 << 6) - 1;
  for (std::size_t cell = 0; cell < grid.count(); ++cell) {
    const std::uint8_t flags = grid.flags[cell];
    if ((flags & Grid::kAirBit) || !(flags & kRigidBits)) continue;
    for (int side = 0; side < 2 * grid.dim; ++side)
      if ((flags >> side) & 1 && !grid.has_neighbour(cell, side)) f(cell, side);
  }
}

/// 2D: u_l on the nodes (n_l + 1 across, n_a + 1 along the march counted from the rigid face; row
/// 0, the face, held at 0) closest in least squares to the increments the strains give:
/// `across[k * (n_l + 1) + i]` from node (i, k) to (i + 1, k) (eps_l h_l; rows k >= 1), `up[k * (n_l +
/// 1) + i]` from (i, k) to (i, k + 1) ((gamma - du_a/dl) h_a), whose squares weigh r (h_l / h_a)^2
/// against the first's (`aspect` = h_l / h_a). It minimises the grid's form of the integral of
/// (du_l/dl - eps_l)^2 + r (du_l/da - gamma + du_a/dl)^2: each edge weighs the area it stands for
/// (half on the box's sides and the free face), r = (1 + nu^2) / (4 (1 + nu)^2), the ratio of the
/// variances one Pa of error in each stress gives eps_l and gamma (docs/agent-model.md,
/// "Displacement"). Returns u[k * (n_l + 1) + i]. Solved exactly: with the sides' half weights the
/// normal equations' rows split into the cosine modes cos(pi m i / n_l) (each row's Laplacian over
/// the sides' weights has them as eigenvectors, eigenvalue 2 - 2 cos(pi m / n_l)), and each mode is
/// one tridiagonal solve along the march.
std::vector<double> closest_lateral(int n_l, int n_a, const std::vector<double>& across, const std::vector<double>& up,
                                    double nu, double aspect) {
  const int n = n_l, row = n_l + 1;
  const double rho = (1 + nu * nu) / (4 * (1 + nu) * (1 + nu)) * aspect * aspect;
  auto side_weight = [&](int i) { return i == 0 || i == n ? 0.5 : 1.0; };
  auto row_weight = [&](int k) { return k == n_a ? 0.5 : 1.0; };
  // The normal equations' right-hand side of node row k = 1..n_a divided by the sides' weights (the
  // modes' equation's); mode m of it is its cosine transform over norm(m).
  std::vector<double> modes(std::size_t(row) * n_a, 0.0), out(std::size_t(row) * (n_a + 1), 0.0);
  CosineTransform cosines(n);
  std::vector<double> scratch(static_cast<std::size_t>(row));
  for (int k = 1; k <= n_a; ++k) {
    const double* a = &across[std::size_t(k) * row];
    for (int i = 0; i <= n; ++i) {
      const double along = (i > 0 ? a[i - 1] : 0.0) - (i < n ? a[i] : 0.0);
      const double rise = up[std::size_t(k - 1) * row + i] - (k < n_a ? up[std::size_t(k) * row + i] : 0.0);
      scratch[std::size_t(i)] = row_weight(k) * along / side_weight(i) + rho * rise;
    }
    double* to = &modes[std::size_t(k - 1) * row];
    cosines.apply(scratch.data(), to);
    for (int m = 0; m <= n; ++m) to[m] /= m == 0 || m == n ? n : 0.5 * n;
  }
  std::vector<double> c(std::size_t(n_a), 0.0);  // the sweep's upper coefficients
  for (int m = 0; m <= n; ++m) {
    // (row_weight(k) mu + rho Ly) x = modes along k, Ly the march's Laplacian held at row 0: Thomas.
    const double mu = 2 - 2 * std::cos(kPi * m / n);
    double previous = 0;
    for (int k = 0; k < n_a; ++k) {
      const double diagonal = row_weight(k + 1) * mu + (k + 1 < n_a ? 2 * rho : rho) + (k > 0 ? rho * c[k - 1] : 0.0);
      c[k] = -rho / diagonal;
      previous = (modes[std::size_t(k) * row + m] + (k > 0 ? rho * previous : 0.0)) / diagonal;
      modes[std::size_t(k) * row + m] = previous;
    }
    for (int k = n_a - 2; k >= 0; --k) modes[std::size_t(k) * row + m] -= c[k] * modes[std::size_t(k + 1) * row + m];
  }
  for (int k = 0; k < n_a; ++k) {  // u_i = sum_m amplitude_m cos(pi m i / n): the transform of amplitude / weight
    for (int m = 0; m <= n; ++m) scratch[std::size_t(m)] = modes[std::size_t(k) * row + m] / side_weight(m);
    cosines.apply(scratch.data(), &out[std::size_t(k + 1) * row]);
  }
  return out;
}
}  // namespace

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

std::vector<double> agent_stresses(const Grid& grid, const std::vector<double>& face_forces,
                                   const StressReadings& readings, int load_dir, double beta, double poisson) {
  auto sigma = agent_stresses(grid, face_forces);
  if (!readings.any()) return sigma;
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
  for_each_rigid_face(grid, [&](std::size_t cell, int side) {
    const int a = axis_of(side);
    const double at = grid.coords(cell)[a] + (is_positive(side) ? 1.0 : 0.0);
    if (!is_positive(side)) {
      low[a] = has_low[a] ? std::min(low[a], at) : at;
      has_low[a] = true;
    } else {
      high[a] = has_high[a] ? std::max(high[a], at) : at;
      has_high[a] = true;
    }
  });
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

/// node_displacements on a dense grid: one block, so a column's line is its strain integrated
/// along the whole axis and every node of the column gets it. The same sums in the same order as
/// the general walk (bit for bit), with strides in place of the block lookups, which cost nine
/// tenths of it.
std::vector<double> dense_node_displacements(const Grid& grid, const std::vector<double>& strains,
                                             const Datums& datums) {
  const int dim = grid.dim;
  const auto nodes = grid.node_counts();
  const std::array<std::size_t, 3> node_stride{1, std::size_t(nodes[0]), std::size_t(nodes[0]) * nodes[1]};
  std::vector<double> u(grid.node_count() * dim, 0.0);
  std::vector<double> line;
  for (int a = 0; a < dim; ++a) {
    const int l0 = lateral_axes(a).l0, l1 = lateral_axes(a).l1, n = grid.cells[a];
    const double position = std::min(std::max(datums[a], 0.0), double(n));
    const int datum_cell = std::min(int(position), n - 1);
    const double frac = position - datum_cell, h = grid.size[a];
    const std::size_t step = grid.stride(a), node_step = node_stride[a];
    line.assign(std::size_t(n) + 1, 0.0);
    for (int v = 0; v < grid.cells[l1]; ++v)
      for (int w = 0; w < grid.cells[l0]; ++w) {
        const std::size_t first = grid.stride(l0) * w + grid.stride(l1) * v;
        double carried = 0.0;
        for (int r = 0; r < n; ++r) line[r + 1] = carried = carried + strains[3 * (first + r * step) + a] * h;
        const double below = line[datum_cell], above = line[datum_cell + 1];
        const double shift = below + frac * (above - below);
        for (int dv = 0; dv < (dim == 3 ? 2 : 1); ++dv)
          for (int dw = 0; dw < 2; ++dw) {
            double* at = u.data() + (node_stride[l0] * (w + dw) + node_stride[l1] * (v + dv)) * dim + a;
            for (int i = 0; i <= n; ++i) at[i * node_step * dim] += line[i] - shift;
          }
      }
    // Every node: the columns beside it.
    auto beside = [](int i, int cells) { return double(std::min(i, cells - 1) - std::max(i - 1, 0) + 1); };
    for (int k = 0; k < nodes[2]; ++k)
      for (int j = 0; j < nodes[1]; ++j)
        for (int i = 0; i < nodes[0]; ++i) {
          const std::array<int, 3> p{i, j, k};
          u[(i + node_stride[1] * j + node_stride[2] * k) * dim + a] /=
              beside(p[l0], grid.cells[l0]) * (dim == 3 ? beside(p[l1], grid.cells[l1]) : 1.0);
        }
  }
  return u;
}

}  // namespace

std::vector<double> node_displacements(const Grid& grid, const std::vector<double>& strains, const Datums& datums) {
  if (!grid.tiled()) return dense_node_displacements(grid, strains, datums);
  // Column by column along each axis: a column's line (its strain integrated from the box's lower
  // side, then shifted to zero at the datum) is added to the nodes of its cells, and each node is
  // divided by the number of columns beside it. Only stored slots are walked (agent/slots.h,
  // blocks()): a column's line changes only inside stored blocks (air adds 0.0 exactly), so between
  // them it is the value carried out of the last stored block below; a column with no stored block
  // adds 0 to its nodes and is skipped. Columns go in (l1, l0) order, so every node adds its
  // columns in one order whatever the layout: a tiled grid gives the dense grid's numbers bit for
  // bit, and a dense grid is one block.
  const int dim = grid.dim;
  const Blocks blocks = with_slots(grid, [](const auto& slots) { return slots.blocks(); });
  std::vector<double> u(grid.node_count() * dim, 0.0);
  std::vector<double> line;
  for (int a = 0; a < dim; ++a) {
    const int l0 = lateral_axes(a).l0, l1 = lateral_axes(a).l1;
    const int n = grid.cells[a], b = blocks.size[a], b0 = blocks.size[l0], b1 = blocks.size[l1];
    // The datum sits in agent `datum_cell` at fraction `frac` of its length.
    const double position = std::min(std::max(datums[a], 0.0), double(n));
    const int datum_cell = std::min(int(position), n - 1);
    const double frac = position - datum_cell;
    // The stored blocks along a of each column of blocks, keyed (l1, l0) in block units, in order.
    std::map<std::pair<int, int>, std::vector<int>> along;
    for (const auto& first : *blocks.first) along[{first[l1] / b1, first[l0] / b0}].push_back(first[a] / b);
    for (auto& entry : along) std::sort(entry.second.begin(), entry.second.end());
    // A column's line at node i: in block k of its stored blocks at line[k * (b + 1) + i - start].
    auto line_at = [&](const std::vector<int>& starts, int i) {
      const auto it = std::upper_bound(starts.begin(), starts.end(), i / b);  // blocks starting at or below i
      if (it == starts.begin()) return 0.0;
      const std::size_t k = std::size_t(it - starts.begin()) - 1;
      const int r = std::min(i - starts[k] * b, b);  // past the block: what it carried out
      return line[k * (b + 1) + r];
    };
    for (auto row = along.begin(); row != along.end();) {
      auto row_end = row;
      while (row_end != along.end() && row_end->first.first == row->first.first) ++row_end;
      const int v_end = std::min((row->first.first + 1) * b1, grid.cells[l1]);
      for (int v = row->first.first * b1; v < v_end; ++v)
        for (auto column = row; column != row_end; ++column) {
          const auto& starts = column->second;
          const int w_end = std::min((column->first.second + 1) * b0, grid.cells[l0]);
          for (int w = column->first.second * b0; w < w_end; ++w) {
            // Integrate the column's strain from its first node, then shift to zero at the datum.
            std::array<int, 3> at{};
            at[l0] = w;
            at[l1] = v;
            line.resize(starts.size() * (b + 1));
            double carried = 0.0;
            for (std::size_t k = 0; k < starts.size(); ++k) {
              line[k * (b + 1)] = carried;
              for (int r = 0; r < b; ++r) {
                at[a] = starts[k] * b + r;
                if (at[a] < n) carried = carried + strains[3 * grid.index(at[0], at[1], at[2]) + a] * grid.size[a];
                line[k * (b + 1) + r + 1] = carried;
              }
            }
            const double below = line_at(starts, datum_cell), above = line_at(starts, datum_cell + 1);
            const double shift = below + frac * (above - below);
            // Add to the nodes of this column's cells (2 node lines across in 2D, 4 in 3D) that
            // have ids: those in the stored blocks of the node line's column of blocks.
            for (int dv = 0; dv < (dim == 3 ? 2 : 1); ++dv)
              for (int dw = 0; dw < 2; ++dw) {
                const auto nodes = along.find({(v + dv) / b1, (w + dw) / b0});
                if (nodes == along.end()) continue;
                std::array<int, 3> p{};
                p[l0] = w + dw;
                p[l1] = v + dv;
                for (int start : nodes->second)
                  for (int i = start * b; i < std::min((start + 1) * b, n + 1); ++i) {
                    p[a] = i;
                    u[grid.node_index(p[0], p[1], p[2]) * dim + a] += line_at(starts, i) - shift;
                  }
              }
          }
        }
      row = row_end;
    }
    // Every node of the box: the columns beside it (a node beyond a tiled box's side keeps 0).
    for (std::size_t node = 0; node < grid.node_count(); ++node) {
      if (!grid.is_grid_node(node)) continue;
      const auto p = grid.node_coords(node);
      auto beside = [](int i, int cells) { return double(std::min(i, cells - 1) - std::max(i - 1, 0) + 1); };
      u[node * dim + a] /= beside(p[l0], grid.cells[l0]) * (dim == 3 ? beside(p[l1], grid.cells[l1]) : 1.0);
    }
  }
  return u;
}

std::vector<double> node_displacements_marched(const Grid& grid, const std::vector<double>& strains,
                                               const std::vector<double>& shear, const Material& material,
                                               const Datums& datums, int a) {
  auto u = node_displacements(grid, strains, datums);
  const int dim = grid.dim, shears = dim == 3 ? 3 : 1;
  if (grid.tiled() || shear.size() != grid.count() * std::size_t(shears)) return u;
  const int n_a = grid.cells[a];
  const bool base_low = datums[a] == 0;
  if (!base_low && datums[a] != n_a) return u;
  for (std::size_t c = 0; c < grid.count(); ++c)
    if (grid.is_air(c)) return u;
  // u_a on the box's sides across the march: the columns' lines extrapolated to the side (2 u(side)
  // - u(next node) = 1.5 c_0 - 0.5 c_1), not the side column's own line half an agent inside it,
  // which would halve du_a/dl in the side columns and tilt every line across by the difference.
  const LateralAxes lat = lateral_axes(a);
  const auto nodes = grid.node_counts();
  for (const int l : {lat.l0, lat.l1}) {
    if (l >= dim) continue;
    for (int k = 0; k < nodes[2]; ++k)
      for (int j = 0; j < nodes[1]; ++j)
        for (int i = 0; i < nodes[0]; ++i) {
          std::array<int, 3> p{i, j, k};
          if (p[l] != 0 && p[l] != grid.cells[l]) continue;
          const std::size_t side = grid.node_index(p[0], p[1], p[2]);
          p[l] += p[l] == 0 ? 1 : -1;
          u[side * dim + a] = 2 * u[side * dim + a] - u[grid.node_index(p[0], p[1], p[2]) * dim + a];
        }
  }
  const double h_a = (base_low ? 1 : -1) * grid.size[a];
  const double shear_modulus = material.young / (2 * (1 + material.poisson));
  // Each lateral axis l in turn, o the other one (in 2D a single line: n_o = 1 and no o nodes).
  for (const int l : {lat.l0, lat.l1}) {
    if (l >= dim) continue;
    const int o = l == lat.l0 ? lat.l1 : lat.l0;
    const int n_l = grid.cells[l], n_o = dim == 3 ? grid.cells[o] : 1, o_nodes = dim == 3 ? n_o + 1 : 1;
    const int o_sides = dim == 3 ? 2 : 1;  // the node lines along o beside a column
    const int component = dim == 3 ? shear_pair(a, l) : 0;
    const double h_l = grid.size[l];
    // (i along l, k counted from the rigid face along a, j along o; a dense box: by strides)
    const std::array<std::size_t, 3> node_stride{1, std::size_t(nodes[0]), std::size_t(nodes[0]) * nodes[1]};
    auto agent = [&](int i, int k, int j) {
      return grid.stride(l) * i + grid.stride(a) * (base_low ? k : n_a - 1 - k) + grid.stride(o) * j;
    };
    auto node = [&](int i, int k, int j) {
      return node_stride[l] * i + node_stride[a] * (base_low ? k : n_a - k) + node_stride[o] * j;
    };
    // Each column of agents marched from the rigid face: du_l/da = gamma - du_a/dl, at the nodes of
    // its edges along a; a node takes the mean of the columns beside it.
    std::vector<double> march(std::size_t(n_l + 1) * (n_a + 1) * o_nodes, 0.0), line(march.size(), 0.0);
    std::vector<double> up(dim == 2 ? march.size() : 0, 0.0), across(up.size(), 0.0);  // 2D's increments
    auto at = [&](int i, int k, int j) { return std::size_t(i) + std::size_t(n_l + 1) * (k + std::size_t(n_a + 1) * j); };
    auto share = [](int index, int count) { return index == 0 || index == count ? 1.0 : 0.5; };  // of a node
    // u_a on the face across l at column i at mid-height of agent k (the mean of its nodes), per k:
    // a column's upper face is the next one's lower face, so each face is taken once.
    std::vector<double> mid_low(n_a, 0.0), mid_high(n_a, 0.0);
    auto mids = [&](int column, int j, std::vector<double>& out) {
      for (int k = 0; k < n_a; ++k) {
        double sum = 0;
        for (int dj = 0; dj < o_sides; ++dj)
          sum += u[node(column, k, j + dj) * dim + a] + u[node(column, k + 1, j + dj) * dim + a];
        out[k] = sum / (2.0 * (o_sides));
      }
    };
    for (int j = 0; j < n_o; ++j) {
      mids(0, j, mid_high);
      for (int i = 0; i < n_l; ++i) {
        std::swap(mid_low, mid_high);
        mids(i + 1, j, mid_high);
        double carried = 0;
        for (int k = 0; k < n_a; ++k) {
          const double dua_dl = (mid_high[k] - mid_low[k]) / h_l;
          const double rise = (shear[agent(i, k, j) * shears + component] / shear_modulus - dua_dl) * h_a;
          if (dim == 2) {  // 2D: each node's mean of the columns beside it, for closest_lateral
            up[at(i, k, 0)] += share(i, n_l) * rise;
            up[at(i + 1, k, 0)] += share(i + 1, n_l) * rise;
            continue;
          }
          carried += rise;
          for (int dj = 0; dj < o_sides; ++dj) {
            const double w_o = share(j + dj, n_o);  // 1 in 2D: a single line
            march[at(i, k + 1, j + dj)] += share(i, n_l) * w_o * carried;
            march[at(i + 1, k + 1, j + dj)] += share(i + 1, n_l) * w_o * carried;
          }
        }
      }
    }
    // eps_l integrated along each line of nodes along l (a node line's strain: the mean of the agent
    // lines beside it), the line's constant the mean over it of the marches (3D; 2D takes the field
    // closest to both increments, below).
    for (int j = 0; j < o_nodes; ++j)
      for (int k = 0; k <= n_a; ++k) {
        const int below = std::max(k - 1, 0), above = std::min(k, n_a - 1);
        const int before = std::max(j - 1, 0), after = std::min(j, n_o - 1);
        double carried = 0, offset = 0;
        for (int i = 0; i < n_l; ++i) {
          // (2D: the two agents' mean as 0.5 (a + b), which the 3D sum of four would round differently)
          const double strain =
              dim == 3 ? 0.25 * (strains[3 * agent(i, below, before) + l] + strains[3 * agent(i, above, before) + l] +
                                 strains[3 * agent(i, below, after) + l] + strains[3 * agent(i, above, after) + l])
                       : 0.5 * (strains[3 * agent(i, below, 0) + l] + strains[3 * agent(i, above, 0) + l]);
          if (dim == 2) across[at(i, k, 0)] = strain * h_l;  // (the line below is 3D's)
          carried += strain * h_l;
          line[at(i + 1, k, j)] = carried;
        }
        if (dim == 2) continue;
        for (int i = 0; i <= n_l; ++i) offset += march[at(i, k, j)] - line[at(i, k, j)];
        offset /= n_l + 1;
        for (int i = 0; i <= n_l; ++i) u[node(i, k, j) * dim + l] = line[at(i, k, j)] + offset;
      }
    if (dim == 2) {
      const auto closest = closest_lateral(n_l, n_a, across, up, material.poisson, h_l / h_a);
      for (int k = 0; k <= n_a; ++k)
        for (int i = 0; i <= n_l; ++i) u[node(i, k, 0) * dim + l] = closest[at(i, k, 0)];
    }
  }
  return u;
}

void hold_rigid_faces(const Grid& grid, std::vector<double>& u) {
  const int dim = grid.dim;
  for_each_rigid_face(grid, [&](std::size_t cell, int side) {
    const int a = axis_of(side), l0 = lateral_axes(a).l0, l1 = lateral_axes(a).l1;
    auto c = grid.coords(cell);
    c[a] += is_positive(side) ? 1 : 0;
    for (int d1 = 0; d1 < (dim == 3 ? 2 : 1); ++d1)
      for (int d0 = 0; d0 < 2; ++d0) {
        std::array<int, 3> p = c;
        p[l0] += d0;
        p[l1] += d1;
        const std::size_t n = grid.node_index(p[0], p[1], p[2]);
        if (n == Grid::npos) continue;
        for (int x = 0; x < dim; ++x) u[n * dim + x] = 0.0;
      }
  });
}

}  // namespace agent
