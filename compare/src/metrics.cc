#include <compare/metrics.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace compare {

namespace {
// Index and weight of `x` between sample positions origin + (i + offset) * h, i in [0, n).
void bracket(double x, double origin, double h, double offset, int n, int& i0, double& t) {
  double f = (x - origin) / h - offset;
  if (n == 1 || f <= 0) {
    i0 = 0;
    t = 0;
    return;
  }
  if (f >= n - 1) {
    i0 = n - 2;
    t = 1;
    return;
  }
  i0 = int(std::floor(f));
  t = f - i0;
}

/// Multilinear interpolation on the lattice of cell centres (`nodes` false) or of nodes (true).
double sample_lattice(const agent::Grid& g, const std::vector<double>& values, int comps, int comp,
                      const Eigen::Vector3d& p, bool nodes) {
  int i[3] = {0, 0, 0};
  double t[3] = {0, 0, 0};
  for (int a = 0; a < g.dim; ++a)
    bracket(p[a], g.origin[a], g.size[a], nodes ? 0.0 : 0.5, g.cells[a] + (nodes ? 1 : 0), i[a], t[a]);
  double sum = 0;
  for (int c = 0; c < (1 << g.dim); ++c) {
    int idx[3] = {0, 0, 0};
    double w = 1;
    for (int a = 0; a < g.dim; ++a) {
      const int bit = (c >> a) & 1;
      idx[a] = std::min(i[a] + bit, g.cells[a] - (nodes ? 0 : 1));
      w *= bit ? t[a] : 1 - t[a];
    }
    if (w == 0) continue;
    const std::size_t at = nodes ? g.node_index(idx[0], idx[1], idx[2]) : g.index(idx[0], idx[1], idx[2]);
    sum += w * values[at * comps + comp];
  }
  return sum;
}

}  // namespace

double sample_cells(const agent::Grid& g, const std::vector<double>& values, int comps, int comp,
                    const Eigen::Vector3d& p) {
  return sample_lattice(g, values, comps, comp, p, false);
}

double sample_nodes(const agent::Grid& g, const std::vector<double>& values, int comps, int comp,
                    const Eigen::Vector3d& p) {
  return sample_lattice(g, values, comps, comp, p, true);
}

std::vector<Line> standard_lines(const agent::Grid& g, const Eigen::Vector3d& centre, const std::vector<double>& depths) {
  std::vector<Line> lines;
  const Eigen::Vector3d lo = g.origin;
  Eigen::Vector3d hi = g.origin;
  for (int a = 0; a < g.dim; ++a) hi[a] += g.cells[a] * g.size[a];
  char text[160];
  {
    Line l;
    l.name = "vertical";
    l.from = centre;
    l.to = centre;
    l.from[1] = hi[1] - 0.5 * g.size[1];
    l.to[1] = lo[1] + 0.5 * g.size[1];
    l.samples = g.cells[1];
    std::snprintf(text, sizeof text, "vertical line x = %.4g mm under the load", 1e3 * centre[0]);
    l.description = text;
    lines.push_back(l);
  }
  for (double depth : depths) {
    Line l;
    char name[32];
    std::snprintf(name, sizeof name, "depth_%.3g", depth);
    l.name = name;
    const double y = hi[1] - depth * (hi[1] - lo[1]);
    l.from = centre;
    l.to = centre;
    l.from[0] = lo[0] + 0.5 * g.size[0];
    l.to[0] = hi[0] - 0.5 * g.size[0];
    l.from[1] = l.to[1] = y;
    l.samples = g.cells[0];
    std::snprintf(text, sizeof text, "horizontal line y = %.4g mm (depth %.3g H)", 1e3 * y, depth);
    l.description = text;
    lines.push_back(l);
  }
  return lines;
}

Errors relative_errors(const std::vector<double>& model, const std::vector<double>& reference) {
  double diff2 = 0, ref2 = 0, diff_max = 0, ref_max = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double d = model[i] - reference[i];
    diff2 += d * d;
    ref2 += reference[i] * reference[i];
    diff_max = std::max(diff_max, std::abs(d));
    ref_max = std::max(ref_max, std::abs(reference[i]));
  }
  Errors e;
  if (ref2 > 0) e.rel_l2 = std::sqrt(diff2 / ref2);
  else if (diff2 > 0) e.rel_l2 = INFINITY;
  if (ref_max > 0) e.rel_max = diff_max / ref_max;
  else if (diff_max > 0) e.rel_max = INFINITY;
  return e;
}

Ratios ratios(const std::vector<double>& model, const std::vector<double>& reference, double mask) {
  Ratios r;
  double ref_max = 0;
  for (double v : reference) ref_max = std::max(ref_max, std::abs(v));
  const double floor = mask * ref_max;
  r.ratio.assign(reference.size(), 0.0);
  r.masked.assign(reference.size(), 1);
  std::vector<double> kept;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (ref_max > 0 && std::abs(reference[i]) >= floor) {
      r.ratio[i] = model[i] / reference[i];
      r.masked[i] = 0;
      kept.push_back(r.ratio[i]);
    } else {
      ++r.masked_count;
    }
  }
  if (!kept.empty()) {
    std::nth_element(kept.begin(), kept.begin() + kept.size() / 2, kept.end());
    r.median = kept[kept.size() / 2];
  }
  return r;
}

}  // namespace compare
