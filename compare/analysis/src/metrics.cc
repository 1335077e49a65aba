// Comparing fields on the agent grid: sampling, sample lines in each load's frame, the far-field mask, error norms and ratios.
#include <compare/metrics.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace compare {

namespace {
// Index and weight of slot coordinate `s` between sample positions i + offset, i in [0, n).
void bracket(double s, double offset, int n, int& i0, double& t) {
  double f = s - offset;
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
    bracket(g.slot_coordinate(a, p[a]), nodes ? 0.0 : 0.5, g.cells[a] + (nodes ? 1 : 0), i[a], t[a]);
  double sum = 0, weight = 0;
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
    // Cell fields: air slots (also a tiled grid's unstored ones) hold no value; the agents'
    // weights are renormalised. Node fields are 0 at a node of no agent, stored or not.
    if (!nodes && (at == agent::Grid::npos || g.is_air(at))) continue;
    sum += w * (at == agent::Grid::npos ? 0.0 : values[at * comps + comp]);
    weight += w;
  }
  return weight > 0 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

bool in_body(const agent::Grid& g, const Eigen::Vector3d& p) {
  int idx[3] = {0, 0, 0};
  for (int a = 0; a < g.dim; ++a) {
    const double f = std::floor(g.slot_coordinate(a, p[a]));
    if (!(f >= 0 && f < g.cells[a])) return false;
    idx[a] = int(f);
  }
  const std::size_t cell = g.index(idx[0], idx[1], idx[2]);
  return cell != agent::Grid::npos && !g.is_air(cell);
}

std::vector<char> body_nodes(const agent::Grid& g) {
  std::vector<char> nodes(g.node_count(), 0);
  for (std::size_t cell = 0; cell < g.count(); ++cell) {
    if (g.is_air(cell)) continue;
    const auto c = g.coords(cell);
    for (int corner = 0; corner < (1 << g.dim); ++corner)
      nodes[g.node_index(c[0] + (corner & 1), c[1] + ((corner >> 1) & 1), c[2] + (g.dim == 3 ? (corner >> 2) & 1 : 0))] = 1;
  }
  return nodes;
}

namespace {
/// Sorts slot ids (or node ids) of a tiled grid into box order (i fastest); a dense grid's ids
/// are in box order already.
void sort_in_box_order(const agent::Grid& g, std::vector<std::size_t>& ids, bool nodes) {
  if (!g.tiled()) return;
  const auto n = nodes ? g.node_counts() : g.cells;
  auto key = [&](std::size_t id) {
    const auto c = nodes ? g.node_coords(id) : g.coords(id);
    return std::size_t(c[0]) + std::size_t(n[0]) * (std::size_t(c[1]) + std::size_t(n[1]) * std::size_t(c[2]));
  };
  std::sort(ids.begin(), ids.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
}
}  // namespace

std::vector<std::size_t> agent_ids(const agent::Grid& g) {
  std::vector<std::size_t> ids;
  for (std::size_t cell = 0; cell < g.count(); ++cell)
    if (!g.is_air(cell)) ids.push_back(cell);
  sort_in_box_order(g, ids, false);
  return ids;
}

std::vector<std::size_t> body_node_ids(const agent::Grid& g) {
  const auto body = body_nodes(g);
  std::vector<std::size_t> ids;
  for (std::size_t n = 0; n < body.size(); ++n)
    if (body[n]) ids.push_back(n);
  sort_in_box_order(g, ids, true);
  return ids;
}

double sample_cells(const agent::Grid& g, const std::vector<double>& values, int comps, int comp,
                    const Eigen::Vector3d& p) {
  return sample_lattice(g, values, comps, comp, p, false);
}

double sample_nodes(const agent::Grid& g, const std::vector<double>& values, int comps, int comp,
                    const Eigen::Vector3d& p) {
  return sample_lattice(g, values, comps, comp, p, true);
}

namespace {

std::string millimetres(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", 1e3 * metres + 0.0);  // + 0.0: no "-0"
  std::string s;
  for (const char* c = text; *c; ++c) s += *c == '.' ? 'p' : *c == '-' ? 'm' : *c;
  return s;
}

std::string point_name(const Eigen::Vector3d& p, int dim) {
  std::string s;
  for (int a = 0; a < dim; ++a) s += std::string(1, "xyz"[a]) + millimetres(p[a]);
  return s;
}

Eigen::Vector3d box_hi(const agent::Grid& g) {
  Eigen::Vector3d hi = g.origin;
  for (int a = 0; a < g.dim; ++a) hi[a] = g.plane(a, g.cells[a]);
  return hi;
}

std::string format(const char* pattern, double a, double b = 0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

/// Nearest point of the outer face `side` of `cell` to `p`, and its distance.
double distance_to_face(const agent::Grid& g, const agent::BoundaryFace& f, const Eigen::Vector3d& p) {
  const Eigen::Vector3d c = g.centre(f.cell);
  const int axis = agent::axis_of(f.side);
  double d2 = 0;
  for (int a = 0; a < g.dim; ++a) {
    double lo = c[a] - 0.5 * g.size[a], hi = c[a] + 0.5 * g.size[a];
    if (a == axis) lo = hi = c[a] + (f.side % 2 ? 0.5 : -0.5) * g.size[a];
    const double q = std::clamp(p[a], lo, hi);
    d2 += (p[a] - q) * (p[a] - q);
  }
  return std::sqrt(d2);
}

}  // namespace

std::string line_name(const Eigen::Vector3d& from, const Eigen::Vector3d& to, int dim) {
  return "line_" + point_name(from, dim) + "_" + point_name(to, dim);
}

Line make_line(const agent::Grid& g, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
               const std::string& description, const std::string& kind) {
  Line l;
  l.kind = kind;
  l.from = from;
  l.to = to;
  double agents = 0;  // agents crossed along the line's main axis (slots on a compressed grid)
  Eigen::Vector3d s_from = from, s_to = to;
  for (int a = 0; a < g.dim; ++a) {
    if (g.compressed()) s_from[a] = g.slot_coordinate(a, from[a]), s_to[a] = g.slot_coordinate(a, to[a]);
    agents = std::max(agents, g.compressed() ? std::abs(s_to[a] - s_from[a]) : std::abs(to[a] - from[a]) / g.size[a]);
  }
  l.samples = std::max(2, int(std::lround(agents)) + 1);
  for (int i = 0; i < l.samples; ++i) {
    const double t = double(i) / (l.samples - 1);
    if (!g.compressed()) {
      l.points.push_back(from + (to - from) * t);
    } else {
      Eigen::Vector3d p = from + (to - from) * t;  // the true line along an axis it does not cross
      for (int a = 0; a < g.dim; ++a)
        if (s_to[a] != s_from[a]) p[a] = g.position(a, s_from[a] + (s_to[a] - s_from[a]) * t);
      l.points.push_back(p);
    }
  }
  for (int i = 0; i < l.samples; ++i)
    if (in_body(g, l.point(i))) l.body_samples.push_back(i);
  l.name = line_name(from, to, g.dim);
  l.description = description;
  return l;
}

std::vector<LoadFrame> load_frames(const agent::ImportedMesh& mesh, const std::vector<workbench::LoadSpec>& loads) {
  const auto& g = mesh.grid;
  std::vector<LoadFrame> frames;
  for (std::size_t i = 0; i < loads.size(); ++i) {
    LoadFrame f;
    f.axis = loads[i].axis;
    f.sign = loads[i].sign;
    f.label = "load " + std::to_string(i + 1) + " (group " + loads[i].group + ", " + loads[i].direction_name() + ")";
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double area = 0;
    for (const auto& face : mesh.face_groups.at(loads[i].group)) {
      const int axis = agent::axis_of(face.side);
      Eigen::Vector3d c = g.centre(face.cell);
      c[axis] += (face.side % 2 ? 0.5 : -0.5) * g.size[axis];
      const double a = g.face_area(axis);
      sum += a * c;
      area += a;
    }
    f.centre = sum / area;
    const auto& faces = mesh.face_groups.at(loads[i].group);
    if (!faces.empty() && faces.front().side == agent::direction(f.axis, f.sign > 0)) f.sign = -f.sign;  // a pull
    frames.push_back(f);
  }
  return frames;
}

std::vector<Line> load_lines(const agent::Grid& g, const std::vector<LoadFrame>& loads, const std::vector<double>& depths) {
  const Eigen::Vector3d lo = g.origin, hi = box_hi(g);
  std::vector<Line> lines;
  auto add = [&](Line l) {
    for (const auto& other : lines)
      if (other.name == l.name) return;
    lines.push_back(std::move(l));
  };
  for (const auto& load : loads) {
    const int ax = load.axis, across = ax == 0 ? 1 : 0;
    const double h = g.size[ax];
    // The loaded face is the body's side the load enters: the high side for a negative push.
    const double entry = load.sign < 0 ? hi[ax] : lo[ax], exit = load.sign < 0 ? lo[ax] : hi[ax];
    std::string slice;
    if (g.dim == 3) {
      const int third = 3 - ax - across;
      slice = std::string(", slice ") + "xyz"[third] + " = " + format("%.4g mm", 1e3 * load.centre[third]);
    }
    Eigen::Vector3d from = load.centre, to = load.centre;
    from[ax] = entry + load.sign * 0.5 * h;
    to[ax] = exit - load.sign * 0.5 * h;
    add(make_line(g, from, to,
                  load.label + ": along the load, " + std::string(1, "xyz"[across]) + " = " +
                      format("%.4g mm", 1e3 * load.centre[across]) + slice,
                  "along"));
    for (double depth : depths) {
      Eigen::Vector3d a = load.centre, b = load.centre;
      a[ax] = b[ax] = entry + load.sign * depth * (hi[ax] - lo[ax]);
      a[across] = lo[across] + 0.5 * g.size[across];
      b[across] = hi[across] - 0.5 * g.size[across];
      add(make_line(g, a, b,
                    load.label + ": across at depth " + format("%.4g", depth) + " of the body (" +
                        std::string(1, "xyz"[ax]) + " = " + format("%.4g mm", 1e3 * a[ax]) + ")" + slice,
                    "across"));
    }
  }
  return lines;
}

NearLoad near_load(const agent::ImportedMesh& mesh, const std::vector<workbench::LoadSpec>& loads, double distance) {
  const auto& g = mesh.grid;
  std::vector<agent::BoundaryFace> faces;
  for (const auto& l : loads) {
    const auto& group = mesh.face_groups.at(l.group);
    faces.insert(faces.end(), group.begin(), group.end());
  }
  auto near = [&](const Eigen::Vector3d& p) {
    for (const auto& f : faces)
      if (distance_to_face(g, f, p) < distance) return char(1);
    return char(0);
  };
  NearLoad out;
  out.cells.resize(g.count());
  for (std::size_t c = 0; c < g.count(); ++c) out.cells[c] = near(g.centre(c));
  out.nodes.resize(g.node_count());
  for (std::size_t n = 0; n < g.node_count(); ++n)
    if (g.is_grid_node(n)) {  // a tiled grid has node ids beyond the box
      const auto c = g.node_coords(n);
      out.nodes[n] = near(g.node_position(c[0], c[1], c[2]));
    }
  return out;
}

std::vector<double> component(const std::vector<double>& v, int comps, int c) {
  std::vector<double> out(v.size() / comps);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = v[i * comps + c];
  return out;
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
    if (reference[i] != 0 && std::abs(reference[i]) >= floor) {  // mask 0 still leaves out x / 0
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
