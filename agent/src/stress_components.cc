// Every stress component of the agents: the shear of the packets and of the row moment balance,
// the tie scan (2D) or the layers (3D) and the bonded face's layer (agent/stress_components.h).
#include <agent/layer_stresses.h>
#include <agent/state.h>
#include <agent/stress_components.h>
#include <agent/slots.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <memory>
#include <utility>
#include <vector>

namespace agent {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// fitted_slope reads the entries within this many windows of each: a Gaussian weight there is
/// exp(-8), 3e-4 of the entry's own.
constexpr double kFitReach = 4;

/// fitted_slope's weights for one window. The slope is linear in the values: per entry, weights
/// c_i = e1' M^-1 w_i p_i of its neighbours. They depend only on the entry's offsets to its
/// neighbours, so on a line longer than two reaches every interior entry has the same weights and
/// each end entry those of its distance to the end: computed once, kept for every such line.
class SlopeFit {
 public:
  explicit SlopeFit(double window) : window_(window), reach_(std::max(1, int(std::ceil(kFitReach * window)))) {
    const int count = 2 * reach_ + 1;  // the shortest line with an interior entry
    int first = 0;
    weights(reach_, count, inner_, first);
    low_.resize(std::size_t(reach_));
    high_.resize(std::size_t(reach_));
    for (int j = 0; j < reach_; ++j) {
      weights(j, count, low_[j], first);
      weights(count - 1 - j, count, high_[j], first);
    }
  }

  void operator()(const double* values, std::size_t stride, int count, double* slope) const {
    if (count < 3) {
      for (int j = 0; j < count; ++j) slope[j * stride] = count == 2 ? values[stride] - values[0] : 0.0;
      return;
    }
    const bool kept = count > 2 * reach_;
    const std::vector<std::vector<double>>* line = kept ? nullptr : &short_line(count);
    for (int j = 0; j < count; ++j) {
      int first = 0;
      const std::vector<double>* use = nullptr;
      if (!kept) {
        use = &(*line)[std::size_t(j)];
        first = std::max(0, j - reach_);
      } else if (j < reach_) {
        use = &low_[j];
      } else if (j + reach_ >= count) {
        use = &high_[count - 1 - j];
        first = j - reach_;
      } else {
        use = &inner_;
        first = j - reach_;
      }
      double sum = 0;
      for (std::size_t i = 0; i < use->size(); ++i) sum += (*use)[i] * values[(first + i) * stride];
      slope[j * stride] = sum;
    }
  }

 private:
  /// Every entry's weights on a line of `count` <= 2 reach entries (no interior entry): the same
  /// for every line of that length, so computed on the first (a box's lines all have one length;
  /// per entry they cost a 3 x 3 LU, two thirds of a 3D solve).
  const std::vector<std::vector<double>>& short_line(int count) const {
    if (short_.size() <= std::size_t(count)) short_.resize(std::size_t(count) + 1);
    auto& line = short_[std::size_t(count)];
    if (line.empty()) {
      line.resize(std::size_t(count));
      int first = 0;
      for (int j = 0; j < count; ++j) weights(j, count, line[std::size_t(j)], first);
    }
    return line;
  }

  /// Entry j's weights on a line of `count` entries, for the entries from `first` on.
  void weights(int j, int count, std::vector<double>& c, int& first) const {
    first = std::max(0, j - reach_);
    const int last = std::min(count - 1, j + reach_);
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (int i = first; i <= last; ++i) {
      const double d = i - j, w = std::exp(-0.5 * (d / window_) * (d / window_));
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
      const double d = i - j, w = std::exp(-0.5 * (d / window_) * (d / window_));
      c[i - first] = w * (row[0] + row[1] * d + row[2] * d * d);
    }
  }

  double window_;
  int reach_;
  std::vector<double> inner_;
  std::vector<std::vector<double>> low_, high_;  // by distance to the line's lower / upper end
  mutable std::vector<std::vector<std::vector<double>>> short_;  // short_line's, by count
};

}  // namespace

void fitted_slope(const double* values, std::size_t stride, int count, double window, double* slope) {
  const SlopeFit fit(window);
  fit(values, stride, count, slope);
}

namespace {

/// Calls f(run) for each run of agents along axis b (slot ids in order along b).
template <class F>
void runs_along(const Grid& g, int b, F&& f) {
  const LateralAxes lat = lateral_axes(b);
  std::vector<std::size_t> run;
  for (int w = 0; w < g.cells[lat.l1]; ++w)
    for (int v = 0; v < g.cells[lat.l0]; ++v) {
      run.clear();
      for (int i = 0; i <= g.cells[b]; ++i) {
        std::size_t cell = Grid::npos;
        if (i < g.cells[b]) {
          std::array<int, 3> c{0, 0, 0};
          c[b] = i;
          c[lat.l0] = v;
          c[lat.l1] = w;
          cell = g.index(c[0], c[1], c[2]);
          if (cell != Grid::npos && g.is_air(cell)) cell = Grid::npos;
        }
        if (cell != Grid::npos) {
          run.push_back(cell);
        } else if (!run.empty()) {
          f(run);
          run.clear();
        }
      }
    }
}

/// A run of agents along an axis: its slot ids in order, first + i stride on a dense grid, else
/// stored in Lines.
struct Run {
  const std::size_t* ids;  ///< nullptr on a dense grid
  std::size_t first, stride, count;
  std::size_t size() const { return count; }
  std::size_t operator[](std::size_t i) const { return ids ? ids[i] : first + i * stride; }
  std::size_t front() const { return (*this)[0]; }
  std::size_t back() const { return (*this)[count - 1]; }
};

/// What every step of one directional_stress_components call walks, taken once: the runs of
/// agents along each axis (runs_along's, in its order) with their first agent's box coordinates,
/// each slot's position along each axis, and a slope fit per window. Walked afresh per step,
/// the runs and positions were a fifth of a 3D solve.
class Lines {
 public:
  explicit Lines(const Grid& grid) : g(grid) {
    for (int b = 0; b < g.dim; ++b) {
      const std::size_t stride = g.tiled() ? 0 : g.stride(b);
      start_[b].push_back(0);
      runs_along(g, b, [&](const std::vector<std::size_t>& run) {
        // (a dense grid's ids follow from the first: only a tiled grid's are kept)
        if (g.tiled()) cells_[b].insert(cells_[b].end(), run.begin(), run.end());
        runs_[b].push_back(Run{nullptr, run.front(), stride, run.size()});
        start_[b].push_back(cells_[b].size());
        first_[b].push_back(g.coords(run.front()));
      });
      for (int i = 0; i < g.cells[b]; ++i) position_[b].push_back(std::round((centre_along(b, i) - g.origin[b]) / g.size[b] - 0.5));
    }
  }
  const Grid& g;

  /// Calls f(run, k) for each run k of agents along axis b, in runs_along's order.
  template <class F>
  void along(int b, F&& f) const {
    for (std::size_t k = 0; k < runs_[b].size(); ++k) {
      Run run = runs_[b][k];
      if (g.tiled()) run.ids = cells_[b].data() + start_[b][k];
      f(run, k);
    }
  }
  /// Box coordinates of the first agent of run k along b.
  const std::array<int, 3>& first(int b, std::size_t k) const { return first_[b][k]; }
  /// An agent's lower side along axis a, in agents from the box's lower side (the transfer's
  /// lateral positions: collapsed air planes keep their true distance), for coordinate i along a.
  double position(int a, int i) const { return position_[a][std::size_t(i)]; }
  /// The slope fit of `window` entries (made on first use).
  const SlopeFit& fit(double window) const {
    for (const auto& f : fits_)
      if (f.first == window) return *f.second;
    fits_.emplace_back(window, std::make_unique<SlopeFit>(window));
    return *fits_.back().second;
  }

 private:
  /// Grid::centre's coordinate along a of the slots with coordinate i along a.
  double centre_along(int a, int i) const {
    return g.planes[a].empty() ? g.origin[a] + (i + 0.5) * g.size[a] : 0.5 * (g.plane(a, i) + g.plane(a, i + 1));
  }
  std::array<std::vector<Run>, 3> runs_;
  std::array<std::vector<std::size_t>, 3> cells_, start_;  // a tiled grid's ids, each run's first
  std::array<std::vector<std::array<int, 3>>, 3> first_;
  std::array<std::vector<double>, 3> position_;
  mutable std::vector<std::pair<double, std::unique_ptr<SlopeFit>>> fits_;
};

/// Per-agent scratch fields of one directional_stress_components call, reused by every step (a step's
/// are dead when the next starts): at a million agents fresh pages cost about as much as the
/// arithmetic (docs/performance.md, "Every core").
struct Scratch {
  std::vector<double> first, second, third;
};

/// d/d(position along a) [per m] of a per-agent field (stride `stride`, offset `at`), fitted along
/// each run of agents along a, into `out` (0 on air).
void derivative_along(const Lines& lines, int a, const std::vector<double>& field, int stride, int at, double window,
                      std::vector<double>& out) {
  const Grid& g = lines.g;
  out.assign(g.count(), 0.0);
  std::vector<double> values, slopes;
  const SlopeFit& fit = lines.fit(window);
  lines.along(a, [&](const Run& run, std::size_t) {
    const int count = int(run.size());
    values.resize(run.size());
    slopes.resize(run.size());
    for (int j = 0; j < count; ++j) values[j] = field[run[j] * stride + at];
    fit(values.data(), 1, count, slopes.data());
    for (int j = 0; j < count; ++j) out[run[j]] = slopes[j] / g.size[a];
  });
}

/// 2D, the bonded rigid face's layer for loads marching along a toward `exit_side`, across l:
/// into `layer` (zeroed), per agent.
///
/// The face holds eps_l = 0, so on it sigma_l = nu sigma_a; the agents' march leaves sigma_l about
/// 0 there. The layer is the elastic half-plane's answer to that restraint, per base run (the
/// agents on the face that are neighbours along l, the columns standing on them) with its two
/// ends free: the restraint's stress S(x) = nu p(x) (p the base agents' sigma_a) in sine modes of
/// the run's width W (zero at the free ends), mode m (wave number k = m pi / W) reaching height y
/// above the face as (1 - k y / 2) exp(-k y): Airy's phi = B y exp(-k y) sin(k x), which leaves the
/// face's normal stress alone (docs/agent-model.md, "The bonded base layer"). No coefficient.
void half_plane_layer(const Lines& lines, int a, int l, int exit_side, const std::vector<double>& normal, double nu,
                      std::vector<double>& layer, std::vector<double>& column_of_end) {
  const Grid& g = lines.g;
  const int dim = g.dim;
  const double h_a = g.size[a], h_l = g.size[l];
  const bool up = is_positive(exit_side);
  layer.assign(g.count(), 0.0);
  // The columns along a that end on a rigid exit face, their agents from the face on, by end agent.
  std::vector<std::vector<std::size_t>> columns;
  column_of_end.assign(g.count(), -1.0);  // -1: not the end of such a column (a scratch field of doubles)
  lines.along(a, [&](const Run& run, std::size_t) {
    const std::size_t end = up ? run.back() : run.front();
    if (g.boundary(exit_side, end) != Boundary::Rigid) return;
    column_of_end[end] = double(columns.size());
    columns.emplace_back(run.size());
    for (std::size_t i = 0; i < run.size(); ++i) columns.back()[i] = run[i];
    if (up) std::reverse(columns.back().begin(), columns.back().end());
  });
  if (columns.empty()) return;
  constexpr double kReach = 40;  // k y beyond which a mode adds less than 1e-16 of its amplitude
  std::vector<std::size_t> base, first;
  std::vector<double> sine, amplitude, reach, modes_at;
  auto layer_of = [&]() {  // one base run
    const int count = int(base.size());
    // Mode m at agent n: sin(pi m (2 n + 1) / (2 count)) = sine[m (2 n + 1) mod 4 count]; the
    // modes of agent n step through the table by 2 n + 1 (a subtraction, not a division per term),
    // into modes_at once per agent.
    const std::size_t period = 4 * std::size_t(count);
    sine.resize(period);
    modes_at.resize(std::size_t(count));
    for (std::size_t q = 0; q < period; ++q) sine[q] = std::sin(kPi * double(q) / (2.0 * count));
    auto take_modes = [&](int n) {
      const std::size_t step = 2 * std::size_t(n) + 1;
      for (std::size_t m = 0, q = step; m < std::size_t(count); ++m, q = q + step >= period ? q + step - period : q + step)
        modes_at[m] = sine[q];
    };
    // sum_{m = 1}^{modes} weight[m - 1] sin(m theta_n) (sin(m theta_n) in at[m - 1]), in four
    // partial sums (modes m, m + 4, ...) so that the adds do not wait on each other
    auto sum_modes = [&](const double* weight, int modes, const double* at) {
      double sum[4] = {0, 0, 0, 0};
      int m = 0;
      for (; m + 4 <= modes; m += 4)
        for (int j = 0; j < 4; ++j) sum[j] += weight[m + j] * at[m + j];
      for (int j = 0; m < modes; ++m, ++j) sum[j] += weight[m] * at[m];
      return (sum[0] + sum[1]) + (sum[2] + sum[3]);
    };
    amplitude.assign(std::size_t(count), 0.0);  // S's sine amplitude per mode m = 1..count
    for (int n = 0; n < count; ++n) {
      const double s_n = nu * normal[base[n] * dim + a];
      take_modes(n);
      for (int m = 0; m < count; ++m) amplitude[m] += s_n * modes_at[m];
    }
    for (int m = 0; m < count; ++m) amplitude[m] *= (m == count - 1 ? 1.0 : 2.0) / count;
    // Per height r above the face, each mode's amplitude there: rows [first[r], first[r + 1]).
    std::size_t height = 0;
    for (std::size_t c : base) height = std::max(height, columns[std::size_t(column_of_end[c])].size());
    const double wave = kPi / (count * h_l);  // k of mode 1
    first.assign(height + 1, 0);
    reach.clear();
    for (std::size_t r = 0; r < height; ++r) {
      const double y = (double(r) + 0.5) * h_a;
      const int modes = int(std::min<double>(count, std::floor(kReach / (wave * y))));
      for (int m = 1; m <= modes; ++m) {
        const double ky = m * wave * y;
        reach.push_back(amplitude[m - 1] * (1 - 0.5 * ky) * std::exp(-ky));
      }
      first[r + 1] = reach.size();
    }
    for (int n = 0; n < count; ++n) {
      take_modes(n);  // for the whole column
      const std::vector<std::size_t>& column = columns[std::size_t(column_of_end[base[n]])];
      for (std::size_t r = 0; r < column.size(); ++r)
        layer[column[r]] = sum_modes(reach.data() + first[r], int(first[r + 1] - first[r]), modes_at.data());
    }
  };
  lines.along(l, [&](const Run& run, std::size_t) {
    base.clear();
    for (std::size_t i = 0; i < run.size(); ++i) {
      const std::size_t c = run[i];
      if (column_of_end[c] >= 0) {
        base.push_back(c);
        continue;
      }
      if (!base.empty()) layer_of();
      base.clear();
    }
    if (!base.empty()) layer_of();
  });
}

/// 3D, the same face's layer, local: nu sigma_a max(0, 1 - y / ell) (1 - exp(-d_side / y)), y the
/// height above the face, d_side the distance to the line's nearer end along l, ell = `ell_share`
/// x the width of the pressure on the face (sqrt(12 variance) of its agents' |sigma_a|, at most
/// their extent). Into `layer` (zeroed).
void local_layer(const Lines& lines, int a, int l, int exit_side, const std::vector<double>& normal, double ell_share,
                 double nu, std::vector<double>& layer, std::vector<double>& height) {
  const Grid& g = lines.g;
  const int dim = g.dim;
  const double h_a = g.size[a], h_l = g.size[l];
  const bool up = is_positive(exit_side);
  layer.assign(g.count(), 0.0);
  // Per agent: its height above a rigid exit face at the end of its run along a (-1: none).
  height.assign(g.count(), -1.0);
  double weight = 0, mean = 0, square = 0, lo = 1e300, hi = -1e300;
  lines.along(a, [&](const Run& run, std::size_t) {
    const std::size_t count = run.size(), end = up ? run.back() : run.front();
    if (g.boundary(exit_side, end) != Boundary::Rigid) return;
    for (std::size_t j = 0; j < count; ++j) height[run[j]] = double(up ? count - 1 - j : j) * h_a + 0.5 * h_a;
    // The pressure on the face: its width along l is sqrt(12 variance) (a uniform one's width).
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
  lines.along(l, [&](const Run& run, std::size_t) {
    const int count = int(run.size());
    for (int i = 0; i < count; ++i) {
      const double y = height[run[i]];
      if (y < 0) continue;
      const double side = std::min(i + 0.5, count - i - 0.5) * h_l;
      layer[run[i]] = nu * normal[run[i] * dim + a] * std::max(0.0, 1 - y / ell) * (1 - std::exp(-side / y));
    }
  });
}

/// Adds a layer across l to sigma_l and its shear (stride, component) by horizontal equilibrium:
/// d tau / d(along a) = -d layer / d(along l), tau = 0 at each run's end away from the face
/// (`exit_side`). `gradient` is scratch.
void add_layer(const Lines& lines, int a, int l, int exit_side, const std::vector<double>& layer,
               std::vector<double>& gradient, std::vector<double>& sigma, std::vector<double>& shear, int stride,
               int component) {
  const Grid& g = lines.g;
  const int dim = g.dim;
  const double h_a = g.size[a], h_l = g.size[l];
  const bool up = is_positive(exit_side);
  gradient.assign(g.count(), 0.0);
  lines.along(l, [&](const Run& run, std::size_t) {  // d layer / d(position along l)
    const int count = int(run.size());
    for (int i = 0; i < count; ++i) {
      const int p = std::max(0, i - 1), q = std::min(count - 1, i + 1);
      if (q > p) gradient[run[i]] = (layer[run[q]] - layer[run[p]]) / ((q - p) * h_l);
    }
  });
  for (std::size_t c = 0; c < layer.size(); ++c) sigma[c * dim + l] += layer[c];
  lines.along(a, [&](const Run& run, std::size_t) {
    const int count = int(run.size());
    double sum = 0;
    for (int n = 0; n < count; ++n) {
      const std::size_t c = run[up ? n : count - 1 - n];  // from the far end toward the face
      const double step = gradient[c] * h_a;
      shear[c * stride + component] += up ? -(sum + 0.5 * step) : sum + 0.5 * step;
      sum += step;
    }
  });
}

}  // namespace

namespace {

/// Per agent the von Mises stress of sigma and shear (plane stress in 2D).
void fill_von_mises(const Grid& g, StressComponents& out) {
  const std::size_t n = g.count();
  out.von_mises.assign(n, 0.0);
  for (std::size_t c = 0; c < n; ++c) {
    const int dim = g.dim, shears = shear_count(dim);
    const workbench::SymmetricTensor s{out.sigma[dim * c], out.sigma[dim * c + 1], dim == 3 ? out.sigma[3 * c + 2] : 0.0,
                                       out.shear[shears * c], dim == 3 ? out.shear[3 * c + 1] : 0.0,
                                       dim == 3 ? out.shear[3 * c + 2] : 0.0};
    out.von_mises[c] = agent_von_mises(s, dim);
  }
}

/// What one step of directional_stress_components reads: the march axis a and a lateral axis l
/// (which: 0 for l0, 1 for l1), the shear component of (a, l), and the loads' exit side.
struct AxisPair {
  int a, l, which, component, exit_side;
};

/// The balance's shear along (a, l), subtracted from out.shear: tau = -d Q / d(along a), Q its
/// sigma_a integrated along l; its force at an agent is slope x (position - the layer's mean
/// position), in agents (as the transfer). Leaves the derivative in scratch.second.
void add_balance_shear(const Lines& lines, const AxisPair& p, const double* slopes, double window,
                       StressComponents& out, Scratch& scratch) {
  const Grid& g = lines.g;
  const std::size_t n = g.count();
  const int shears = shear_count(g.dim), a = p.a, l = p.l;
  const double area = g.face_area(a), h_l = g.size[l];
  std::vector<double>& field = scratch.first;
  std::vector<double>& derivative = scratch.second;
  std::vector<double> sum_layer(std::size_t(g.cells[a]), 0.0), count_layer(std::size_t(g.cells[a]), 0.0);
  // (whole numbers of agents: their sums do not depend on the order they are taken in)
  lines.along(l, [&](const Run& run, std::size_t k) {
    const auto& first = lines.first(l, k);
    for (std::size_t i = 0; i < run.size(); ++i) sum_layer[first[a]] += lines.position(l, first[l] + int(i));
    count_layer[first[a]] += double(run.size());
  });
  field.assign(n, 0.0);
  lines.along(l, [&](const Run& run, std::size_t k) {
    const auto& first = lines.first(l, k);
    const int j = first[a];
    const double slope = slopes[2 * j + p.which];
    if (slope == 0) return;
    double q = 0;
    for (std::size_t i = 0; i < run.size(); ++i) {
      const double s = -slope * (lines.position(l, first[l] + int(i)) - sum_layer[j] / count_layer[j]) / area * h_l;
      field[run[i]] = q + 0.5 * s;
      q += s;
    }
  });
  derivative_along(lines, a, field, 1, 0, window, derivative);  // the balance's shear
  for (std::size_t c = 0; c < n; ++c) out.shear[c * shears + p.component] -= derivative[c];
}

/// 2D, the turning paths' components along (a, l) after the balance's shear (stress_components.h):
/// each hole's shear, then the tie (horizontal equilibrium scanned along each run of l) and the
/// bonded rigid face's layer; with k.closed_forms left out the tie alone.
void add_tie_and_layer(const Lines& lines, const AxisPair& p, const std::vector<double>& normal,
                       const DirectionalCoefficients& k, double poisson, StressComponents& out, Scratch& scratch) {
  const Grid& g = lines.g;
  const std::size_t n = g.count();
  const int a = p.a, l = p.l;
  const double h_l = g.size[l];
  std::vector<double>& derivative = scratch.second;
  // Kirsch's shear and the half-plane's layer are closed forms (k.closed_forms leaves them out)
  const bool closed_forms = k.closed_forms == ClosedForms::Added;
  if (closed_forms) {  // a hole's corners: the shear of the load going round it, before the tie reads it
    const std::vector<double> holes = hole_shear(g, a, normal);
    for (std::size_t c = 0; c < n; ++c) out.shear[c] += holes[c];
  }
  // The tie: d sigma_l / d(along l) = -d tau / d(along a), scanned from each run's lower end.
  // (Loads along both axes: each tie reads every packet's shear.)
  derivative_along(lines, a, out.shear, 1, 0, k.window_length / g.size[a], derivative);
  const std::vector<double>& dtau = derivative;
  std::vector<double> faces;
  lines.along(l, [&](const Run& run, std::size_t) {
    const std::size_t count = run.size();
    faces.assign(count + 1, 0.0);
    for (std::size_t i = 0; i < count; ++i) faces[i + 1] = faces[i] - h_l * dtau[run[i]];
    const double rest = faces[count];  // the round-off of an unbalanced row: taken out linearly
    for (std::size_t i = 0; i <= count; ++i) faces[i] -= rest * double(i) / double(count);
    for (std::size_t i = 0; i < count; ++i) out.sigma[run[i] * 2 + l] += 0.5 * (faces[i] + faces[i + 1]);
  });
  if (!closed_forms) return;  // the agents alone: no layer
  half_plane_layer(lines, a, l, p.exit_side, normal, poisson, scratch.second, scratch.first);
  add_layer(lines, a, l, p.exit_side, scratch.second, scratch.third, out.sigma, out.shear, 1, 0);
}

/// A window of a quarter agent fits its quadratic through an entry and its two neighbours: the
/// centred difference (one-sided at a run's ends).
constexpr double kCentred = 0.25;

/// 3D, march axis a: each layer of agents across a answers the march's sigma_a and the body force
/// its shears leave (d tau_al / d(along a), centred) with the in-plane stresses of least
/// complementary energy (LayerSolver). They add to sigma_l0 and sigma_l1 and replace the packets'
/// shear in the layer's plane where no other march owns that pair (`replace_shear`).
void layer_stresses(const Lines& lines, int a, const std::vector<double>& normal, double poisson, bool replace_shear,
                    StressComponents& out, Scratch& scratch) {
  const Grid& g = lines.g;
  const LateralAxes lat = lateral_axes(a);
  derivative_along(lines, a, out.shear, 3, shear_pair(a, lat.l0), kCentred, scratch.first);
  derivative_along(lines, a, out.shear, 3, shear_pair(a, lat.l1), kCentred, scratch.second);
  LayerBox box{g.cells[lat.l0], g.cells[lat.l1], g.size[lat.l0], g.size[lat.l1], {}};
  const std::size_t m = std::size_t(box.n0) * std::size_t(box.n1);
  LayerFields f{std::vector<double>(m), std::vector<double>(m), std::vector<double>(m),
                std::vector<double>(m), std::vector<double>(m), std::vector<double>(m)};
  std::vector<std::size_t> slot(m);
  LayerSolver solver(poisson);
  const int in_plane = shear_pair(lat.l0, lat.l1);
  for (int j = 0; j < g.cells[a]; ++j) {
    box.solid.assign(m, 0);
    for (std::size_t cell = 0; cell < m; ++cell) {
      std::array<int, 3> c{0, 0, 0};
      c[a] = j;
      c[lat.l0] = int(cell % std::size_t(box.n0));
      c[lat.l1] = int(cell / std::size_t(box.n0));
      slot[cell] = g.index(c[0], c[1], c[2]);
      if (slot[cell] == Grid::npos || g.is_air(slot[cell])) continue;
      box.solid[cell] = 1;
      f.normal[cell] = normal[slot[cell] * 3 + a];
      f.body0[cell] = scratch.first[slot[cell]];
      f.body1[cell] = scratch.second[slot[cell]];
    }
    if (std::find(box.solid.begin(), box.solid.end(), 1) == box.solid.end()) continue;
    solver.solve(box, f);
    for (std::size_t cell = 0; cell < m; ++cell) {
      if (!box.solid[cell]) continue;
      const std::size_t s = slot[cell];
      out.sigma[s * 3 + lat.l0] += f.sigma0[cell];
      out.sigma[s * 3 + lat.l1] += f.sigma1[cell];
      double& tau = out.shear[s * 3 + in_plane];
      tau = (replace_shear ? 0.0 : tau) + f.tau01[cell];
    }
  }
}

/// The turning paths' components of the march along a after the balance's shear
/// (stress_components.h): in 2D the tie and the half-plane's layer (add_tie_and_layer); in 3D the
/// layers' stresses (layer_stresses), then the bonded rigid face's local layer across each lateral
/// axis.
void turning_path_stresses(const Lines& lines, int a, int exit_side, const std::vector<double>& normal,
                           const DirectionalCoefficients& k, double poisson, bool replace_shear, StressComponents& out,
                           Scratch& scratch) {
  const Grid& g = lines.g;
  const LateralAxes lat = lateral_axes(a);
  if (g.dim == 2) {
    add_tie_and_layer(lines, AxisPair{a, lat.l0, 0, 0, exit_side}, normal, k, poisson, out, scratch);
    return;
  }
  layer_stresses(lines, a, normal, poisson, replace_shear, out, scratch);
  for (const int l : {lat.l0, lat.l1}) {
    // The bonded face holds every lateral strain: sigma_l = nu / (1 - nu) sigma_a in 3D.
    local_layer(lines, a, l, exit_side, normal, k.base_layer_3d, poisson / (1 - poisson), scratch.second, scratch.first);
    add_layer(lines, a, l, exit_side, scratch.second, scratch.third, out.sigma, out.shear, 3, shear_pair(a, l));
  }
}

/// What a path type adds along a after the balance's shear, per Paths value (kPathNames' order):
/// the turning paths the tie or the layers and the bonded face's layer; the mirror paths nothing.
using PathStresses = void (*)(const Lines&, int, int, const std::vector<double>&, const DirectionalCoefficients&,
                              double, bool, StressComponents&, Scratch&);
void mirror_path_stresses(const Lines&, int, int, const std::vector<double>&, const DirectionalCoefficients&, double,
                          bool, StressComponents&, Scratch&) {}
constexpr PathStresses kPathStresses[] = {turning_path_stresses, mirror_path_stresses};
static_assert(std::size(kPathStresses) == std::size(kPathNames), "a stress step per path type");

}  // namespace

StressComponents normal_stress_components(const Grid& g, const std::vector<double>& normal) {
  StressComponents out;
  out.sigma = normal;
  out.shear.assign(g.count() * shear_count(g.dim), 0.0);
  fill_von_mises(g, out);
  return out;
}

StressComponents stress_components_with_shear(const Grid& g, const std::vector<double>& normal,
                                              const std::vector<double>& shear) {
  StressComponents out;
  out.sigma = normal;
  out.shear = shear;
  fill_von_mises(g, out);
  return out;
}

StressComponents directional_stress_components(const Grid& g, const std::vector<double>& normal,
                                               const std::vector<double>& shear, const std::vector<double>& balance,
                                               const DirectionalCoefficients& k, double poisson,
                                               const std::vector<EntryLoad>& loads) {
  const int dim = g.dim;
  StressComponents out;
  out.sigma = normal;
  out.shear = shear;  // the packets'
  const PathStresses path_stresses = kPathStresses[int(k.paths)];
  Scratch scratch;
  const Lines lines(g);
  const auto march_along = [&](int b) {
    return std::find_if(loads.begin(), loads.end(), [&](const EntryLoad& e) { return axis_of(e.dir) == b; });
  };
  for (int a = 0; a < dim; ++a) {
    const auto load = march_along(a);
    if (load == loads.end()) continue;  // no load marches along a: nothing written for it
    const LateralAxes lat = lateral_axes(a);
    const double* slopes = balance.data() + 2 * balance_offset(g, a);
    for (int which = 0; which < dim - 1; ++which) {
      const int l = which == 0 ? lat.l0 : lat.l1;
      add_balance_shear(lines, AxisPair{a, l, which, dim == 3 ? shear_pair(a, l) : 0, load->dir}, slopes,
                        k.window_length / g.size[a], out, scratch);
    }
    // 3D: the in-plane shear is the march's own unless a march along l0 or l1 shares it
    const bool replace_shear = dim == 3 && march_along(lat.l0) == loads.end() && march_along(lat.l1) == loads.end();
    path_stresses(lines, a, load->dir, normal, k, poisson, replace_shear, out, scratch);
  }
  fill_von_mises(g, out);
  return out;
}

}  // namespace agent
