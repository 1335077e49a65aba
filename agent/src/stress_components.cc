// Every stress component of the agents: the shear of the packets and of the row moment balance,
// the tie scan and the bonded face's layer (agent/stress_components.h).
#include <agent/stress_components.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace agent {

double von_mises_2d(double sx, double sy, double txy) {
  return std::sqrt(std::max(0.0, sx * sx - sx * sy + sy * sy + 3 * txy * txy));
}

double von_mises_3d(const double* s) {
  const double dxy = s[0] - s[1], dyz = s[1] - s[2], dzx = s[2] - s[0];
  return std::sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx) + 3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

void fitted_slope(const double* values, std::size_t stride, int count, double window, double* slope) {
  const int reach = std::max(1, int(std::ceil(4 * window)));
  if (count < 3) {
    for (int j = 0; j < count; ++j) slope[j * stride] = count == 2 ? values[stride] - values[0] : 0.0;
    return;
  }
  // The slope is linear in the values: per entry, weights c_i = e1' M^-1 w_i p_i of its
  // neighbours. Away from the ends every entry has the same weights: computed once.
  auto weights = [&](int j, std::vector<double>& c, int& first) {
    first = std::max(0, j - reach);
    const int last = std::min(count - 1, j + reach);
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (int i = first; i <= last; ++i) {
      const double d = i - j, w = std::exp(-0.5 * (d / window) * (d / window));
      const Eigen::Vector3d p(1, d, d * d);
      m += w * p * p.transpose();
    }
    c.assign(std::size_t(last - first + 1), 0.0);
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
    if (lu.rank() < 3) {  // too narrow a window for a quadratic: the nearest difference
      const int lo = std::max(0, j - 1), hi = std::min(count - 1, j + 1);
      c[lo - first] -= 1.0 / (hi - lo);
      c[hi - first] += 1.0 / (hi - lo);
      return;
    }
    const Eigen::Vector3d row = lu.inverse().row(1).transpose();
    for (int i = first; i <= last; ++i) {
      const double d = i - j, w = std::exp(-0.5 * (d / window) * (d / window));
      c[i - first] = w * (row[0] + row[1] * d + row[2] * d * d);
    }
  };
  std::vector<double> inner, c;
  int first = 0;
  if (count > 2 * reach) weights(reach, inner, first);
  for (int j = 0; j < count; ++j) {
    const bool interior = j >= reach && j + reach < count && !inner.empty();
    if (!interior) weights(j, c, first);
    const std::vector<double>& use = interior ? inner : c;
    const int from = interior ? j - reach : first;
    double sum = 0;
    for (std::size_t i = 0; i < use.size(); ++i) sum += use[i] * values[(from + i) * stride];
    slope[j * stride] = sum;
  }
}

namespace {

/// The agents of a 2D grid seen along march axis a: (i along the lateral axis l, j along a).
struct Lines {
  int a, l, n_l, n_a;
  std::vector<std::size_t> id;  ///< Grid::npos for air
  std::size_t at(int i, int j) const { return id[std::size_t(i) + std::size_t(n_l) * j]; }
  Lines(const Grid& g, int axis) : a(axis), l(1 - axis), n_l(g.cells[1 - axis]), n_a(g.cells[axis]) {
    id.resize(std::size_t(n_l) * n_a);
    for (int j = 0; j < n_a; ++j)
      for (int i = 0; i < n_l; ++i) {
        std::array<int, 3> c{0, 0, 0};
        c[l] = i;
        c[a] = j;
        const std::size_t cell = g.index(c[0], c[1], c[2]);
        id[std::size_t(i) + std::size_t(n_l) * j] = cell != Grid::npos && !g.is_air(cell) ? cell : Grid::npos;
      }
  }
  /// Calls f(first, count) for each run of agents along l in row j (i from first to first + count - 1).
  template <class F>
  void rows(int j, F&& f) const {
    for (int i = 0; i < n_l;) {
      if (at(i, j) == Grid::npos) { ++i; continue; }
      int end = i;
      while (end + 1 < n_l && at(end + 1, j) != Grid::npos) ++end;
      f(i, end - i + 1);
      i = end + 1;
    }
  }
  /// The same along a in column i.
  template <class F>
  void columns(int i, F&& f) const {
    for (int j = 0; j < n_a;) {
      if (at(i, j) == Grid::npos) { ++j; continue; }
      int end = j;
      while (end + 1 < n_a && at(i, end + 1) != Grid::npos) ++end;
      f(j, end - j + 1);
      j = end + 1;
    }
  }
};

/// An agent's lower side along axis `a`, in agents from the box's lower side (the transfer's
/// lateral positions: collapsed air planes keep their true distance).
double position(const Grid& g, std::size_t cell, int a) {
  return std::round((g.centre(cell)[a] - g.origin[a]) / g.size[a] - 0.5);
}

/// d/d(position along a) [per m] of a per-agent field, fitted along each column run.
std::vector<double> derivative_along(const Lines& lines, const std::vector<double>& field, double h_a, double window) {
  std::vector<double> out(field.size(), 0.0), values, slopes;
  for (int i = 0; i < lines.n_l; ++i)
    lines.columns(i, [&](int first, int count) {
      values.resize(count);
      slopes.resize(count);
      for (int j = 0; j < count; ++j) values[j] = field[lines.at(i, first + j)];
      fitted_slope(values.data(), 1, count, window, slopes.data());
      for (int j = 0; j < count; ++j) out[lines.at(i, first + j)] = slopes[j] / h_a;
    });
  return out;
}

/// The bonded rigid face's layer for loads marching along a toward `exit_side`: adds its sigma
/// across a to `sigma` and its shear to `tau`.
void add_base_layer(const Grid& g, const Lines& lines, int exit_side, const std::vector<double>& normal, double ell_share,
                    double poisson, std::vector<double>& sigma, std::vector<double>& tau) {
  const int a = lines.a, l = lines.l, dim = g.dim;
  const double h_a = g.size[a], h_l = g.size[l];
  const bool up = is_positive(exit_side);
  // Per agent: its height above a rigid exit face at the end of its column run (-1: none).
  std::vector<double> height(normal.size() / dim, -1.0);
  double weight = 0, mean = 0, square = 0, lo = 1e300, hi = -1e300;
  for (int i = 0; i < lines.n_l; ++i)
    lines.columns(i, [&](int first, int count) {
      const std::size_t end = lines.at(i, up ? first + count - 1 : first);
      if (g.boundary(exit_side, end) != Boundary::Rigid) return;
      for (int j = 0; j < count; ++j) height[lines.at(i, first + j)] = ((up ? count - 1 - j : j) + 0.5) * h_a;
      // The pressure on the face: its width is sqrt(12 variance) (the width of a uniform one).
      const double w = std::abs(normal[end * dim + a]), x = g.centre(end)[l];
      weight += w;
      mean += w * x;
      square += w * x * x;
      lo = std::min(lo, x - 0.5 * h_l);
      hi = std::max(hi, x + 0.5 * h_l);
    });
  if (!(weight > 0)) return;
  mean /= weight;
  const double variance = std::max(0.0, square / weight - mean * mean);
  const double ell = ell_share * std::min(std::sqrt(12 * variance), hi - lo);
  if (!(ell > 0)) return;
  std::vector<double> layer(height.size(), 0.0), gradient(height.size(), 0.0);
  for (int j = 0; j < lines.n_a; ++j)
    lines.rows(j, [&](int first, int count) {
      for (int i = first; i < first + count; ++i) {
        const std::size_t c = lines.at(i, j);
        const double y = height[c];
        if (y < 0) continue;
        const double side = std::min(i - first + 0.5, first + count - i - 0.5) * h_l;
        layer[c] = poisson * normal[c * dim + a] * std::max(0.0, 1 - y / ell) * (1 - std::exp(-side / y));
      }
      for (int i = first; i < first + count; ++i) {  // d layer / d(position along l)
        const int p = std::max(first, i - 1), q = std::min(first + count - 1, i + 1);
        if (q > p) gradient[lines.at(i, j)] = (layer[lines.at(q, j)] - layer[lines.at(p, j)]) / ((q - p) * h_l);
      }
    });
  for (std::size_t c = 0; c < layer.size(); ++c) sigma[c * dim + l] += layer[c];
  // d tau / d(along a) = -d layer / d(along l), tau = 0 at the run's end away from the face.
  for (int i = 0; i < lines.n_l; ++i)
    lines.columns(i, [&](int first, int count) {
      double sum = 0;
      for (int n = 0; n < count; ++n) {
        const int j = up ? first + n : first + count - 1 - n;  // from the far end toward the face
        const std::size_t c = lines.at(i, j);
        const double step = gradient[c] * h_a;
        tau[c] += up ? -(sum + 0.5 * step) : sum + 0.5 * step;
        sum += step;
      }
    });
}

}  // namespace

StressComponents agent_stress_components(const Grid& g, const std::vector<double>& normal,
                                         const std::vector<double>& shear_flux, const std::vector<double>& balance,
                                         const DirectionalCoefficients& k, double poisson,
                                         const std::vector<EntryLoad>& loads) {
  const int dim = g.dim;
  const std::size_t n = g.count();
  StressComponents out;
  out.sigma = normal;
  out.shear.assign(n * shear_count(dim), 0.0);
  if (dim == 2 && !shear_flux.empty()) {
    std::vector<double> field(n, 0.0);
    std::copy(shear_flux.begin(), shear_flux.end(), out.shear.begin());  // the packets'
    for (int a = 0; a < 2; ++a) {
      const auto load = std::find_if(loads.begin(), loads.end(), [&](const EntryLoad& e) { return axis_of(e.dir) == a; });
      if (load == loads.end()) continue;  // no load marches along a: nothing written for it
      const Lines lines(g, a);
      const int l = lines.l;
      const double h_l = g.size[l], h_a = g.size[a], area = g.face_area(a);
      const double window = k.window_length / h_a;
      // The balance's shear: tau = -d Q / d(along a), Q its sigma_a integrated along the row; its
      // force at an agent is slope x (position - the row's mean position), in agents (as the transfer).
      const double* slope = balance.data() + (a == 1 ? g.cells[0] : 0);
      std::fill(field.begin(), field.end(), 0.0);
      for (int j = 0; j < lines.n_a; ++j) {
        if (slope[j] == 0) continue;
        double mean = 0, count = 0;
        for (int i = 0; i < lines.n_l; ++i)
          if (lines.at(i, j) != Grid::npos) mean += position(g, lines.at(i, j), l), count += 1;
        mean /= count;
        lines.rows(j, [&](int first, int run) {
          double q = 0;
          for (int i = first; i < first + run; ++i) {
            const std::size_t c = lines.at(i, j);
            const double s = -slope[j] * (position(g, c, l) - mean) / area * h_l;
            field[c] = q + 0.5 * s;
            q += s;
          }
        });
      }
      const auto balance_shear = derivative_along(lines, field, h_a, window);
      for (std::size_t c = 0; c < n; ++c) out.shear[c] -= balance_shear[c];
      if (k.paths != Paths::Turning) continue;
      // The tie: d sigma_l / d(along l) = -d tau / d(along a), scanned from each run's lower end.
      // (Loads along both axes: each tie reads every packet's shear.)
      const auto dtau = derivative_along(lines, out.shear, h_a, window);
      std::vector<double> faces;
      for (int j = 0; j < lines.n_a; ++j)
        lines.rows(j, [&](int first, int count) {
          faces.assign(std::size_t(count) + 1, 0.0);
          for (int i = 0; i < count; ++i) faces[i + 1] = faces[i] - h_l * dtau[lines.at(first + i, j)];
          const double rest = faces[count];  // the round-off of an unbalanced row: taken out linearly
          for (int i = 0; i <= count; ++i) faces[i] -= rest * i / count;
          for (int i = 0; i < count; ++i) out.sigma[lines.at(first + i, j) * 2 + l] += 0.5 * (faces[i] + faces[i + 1]);
        });
      add_base_layer(g, lines, load->dir, normal, k.base_layer, poisson, out.sigma, out.shear);
    }
  }
  out.von_mises.assign(n, 0.0);
  for (std::size_t c = 0; c < n; ++c) {
    if (dim == 2) {
      out.von_mises[c] = von_mises_2d(out.sigma[2 * c], out.sigma[2 * c + 1], out.shear[c]);
    } else {
      const double s[6] = {out.sigma[3 * c], out.sigma[3 * c + 1], out.sigma[3 * c + 2], 0, 0, 0};
      out.von_mises[c] = von_mises_3d(s);
    }
  }
  return out;
}

}  // namespace agent
