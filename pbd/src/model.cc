// Builds the PBD model from a mesh: masses, distance and seed angle constraints, colouring.
#include <pbd/model.h>
#include <pbd/topology.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

namespace pbd {

namespace {

using Key = std::tuple<double, double, double>;
Key key(const Vec3& p) { return {p[0], p[1], p[2]}; }
/// The two keys, smaller first (by value: std::minmax of temporaries would dangle).
std::pair<Key, Key> sorted_keys(const Vec3& a, const Vec3& b) {
  Key ka = key(a), kb = key(b);
  return ka < kb ? std::make_pair(ka, kb) : std::make_pair(kb, ka);
}

double cell_measure(const Mesh& mesh, std::size_t c) {
  const int* v = &mesh.cell_nodes[mesh.cell_offsets[c]];
  const auto& x = mesh.points;
  switch (mesh.cell_types[c]) {
    case kLine: return (x[v[1]] - x[v[0]]).norm();
    case kTriangle: return 0.5 * (x[v[1]] - x[v[0]]).cross(x[v[2]] - x[v[0]]).norm();
    case kQuad: return 0.5 * (x[v[2]] - x[v[0]]).cross(x[v[3]] - x[v[1]]).norm();
    default: return 0;
  }
}

/// Cuts `count` constraints (given by their particle lists) into blocks of `block_size`, colours
/// the blocks greedily (a colour may not touch a particle twice) and returns the permutation that
/// orders the blocks by colour, each block's constraints unchanged in order.
template <class Nodes>
std::vector<std::size_t> colour_blocks(std::size_t count, std::size_t particles, Nodes nodes, std::size_t block_size,
                                       Colouring& out) {
  const std::size_t blocks = (count + block_size - 1) / block_size;
  std::vector<std::vector<int>> used(particles);  // colours already touching each particle
  std::vector<int> colour(blocks);
  int colours = 0;
  std::vector<char> taken;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t lo = b * block_size, hi = std::min(count, lo + block_size);
    taken.assign(colours + 1, 0);
    for (std::size_t c = lo; c < hi; ++c)
      for (int p : nodes(c))
        for (int u : used[p]) taken[u] = 1;
    int col = 0;
    while (taken[col]) ++col;
    colour[b] = col;
    colours = std::max(colours, col + 1);
    for (std::size_t c = lo; c < hi; ++c)
      for (int p : nodes(c))
        if (used[p].empty() || used[p].back() != col) used[p].push_back(col);
  }
  std::vector<std::size_t> block_order(blocks);
  std::iota(block_order.begin(), block_order.end(), std::size_t(0));
  std::stable_sort(block_order.begin(), block_order.end(), [&](std::size_t a, std::size_t b) { return colour[a] < colour[b]; });
  std::vector<std::size_t> order;
  order.reserve(count);
  out.block_begin.assign(1, 0);
  out.colour_begin.assign(colours + 1, 0);
  // Inside a block, constraints are ordered by a local greedy colouring too: consecutive
  // projections then touch different particles, so the processor overlaps them (a chain of
  // dependent projections is latency-bound, ~2x slower), and the block stays in L1.
  std::vector<int> local(block_size);
  std::vector<std::size_t> in_block;
  std::unordered_map<int, std::vector<int>> local_used;
  for (std::size_t b : block_order) {
    const std::size_t lo = b * block_size, hi = std::min(count, lo + block_size);
    local_used.clear();
    int local_colours = 0;
    for (std::size_t c = lo; c < hi; ++c) {
      taken.assign(local_colours + 1, 0);
      for (int p : nodes(c))
        for (int u : local_used[p]) taken[u] = 1;
      int col = 0;
      while (taken[col]) ++col;
      local[c - lo] = col;
      local_colours = std::max(local_colours, col + 1);
      for (int p : nodes(c)) local_used[p].push_back(col);
    }
    in_block.resize(hi - lo);
    std::iota(in_block.begin(), in_block.end(), lo);
    std::stable_sort(in_block.begin(), in_block.end(),
                     [&](std::size_t x, std::size_t y) { return local[x - lo] < local[y - lo]; });
    order.insert(order.end(), in_block.begin(), in_block.end());
    out.block_begin.push_back(order.size());
    ++out.colour_begin[colour[b] + 1];
  }
  for (int k = 0; k < colours; ++k) out.colour_begin[k + 1] += out.colour_begin[k];
  return order;
}

template <class T>
void permute(std::vector<T>& v, const std::vector<std::size_t>& order) {
  std::vector<T> out;
  out.reserve(v.size());
  for (std::size_t i : order) out.push_back(v[i]);
  v.swap(out);
}

}  // namespace

bool lies_in_xy_plane(const std::vector<Vec3>& points) {
  if (points.empty()) return true;
  Vec3 lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return hi[2] - lo[2] <= 1e-12 * std::max((hi - lo).norm(), 1e-300);
}

void colour_constraints(Model& model, int block_size) {
  const std::size_t n = model.particles.size();
  const std::size_t bs = std::size_t(std::max(1, block_size));
  auto& d = model.distances;
  auto od = colour_blocks(d.size(), n, [&](std::size_t c) { return std::array<int, 2>{d[c].a, d[c].b}; }, bs,
                          model.distance_colouring);
  permute(d, od);
  auto& a = model.angles;
  auto oa = colour_blocks(a.size(), n, [&](std::size_t c) { return std::array<int, 3>{a[c].best, a[c].k, a[c].i}; },
                          bs, model.angle_colouring);
  permute(a, oa);
}

Model build_model(const Mesh& mesh, const std::vector<int>& pinned, const ModelOptions& options) {
  const std::size_t n = mesh.points.size();
  Model model;
  std::vector<char> is_pinned(n, 0);
  for (int p : pinned) {
    if (p < 0 || std::size_t(p) >= n) throw std::invalid_argument("pinned node index " + std::to_string(p) + " out of range");
    is_pinned[p] = 1;
  }
  if (!(options.total_mass > 0)) throw std::invalid_argument("total mass must be positive");

  // Masses (seed step 2: m_i = 1/n; or lumped by cell size).
  std::vector<double> mass(n, options.total_mass / double(n));
  if (options.masses == ModelOptions::Masses::Lumped) {
    std::fill(mass.begin(), mass.end(), 0.0);
    double total = 0;
    for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
      const int b = mesh.cell_offsets[c], e = mesh.cell_offsets[c + 1];
      bool any_free = false;
      for (int k = b; k < e; ++k) any_free = any_free || !is_pinned[mesh.cell_nodes[k]];
      if (!any_free) continue;
      const double m = cell_measure(mesh, c);
      total += m;
      for (int k = b; k < e; ++k) mass[mesh.cell_nodes[k]] += m / (e - b);
    }
    if (!(total > 0)) throw std::invalid_argument("the mesh has no free cell of non-zero size to carry mass");
    for (auto& m : mass) m *= options.total_mass / total;
  }
  for (std::size_t i = 0; i < n; ++i) model.particles.add(mesh.points[i], mass[i], is_pinned[i]);

  model.planar = options.planar_axis.squaredNorm() > 0;
  if (model.planar) model.axis = options.planar_axis.normalized();
  const auto& x = mesh.points;

  const auto edges = mesh_edges(mesh);
  if (options.stretch)
    for (const auto& [a, b] : edges) {
      if (is_pinned[a] && is_pinned[b]) continue;
      model.distances.push_back({a, b, (x[a] - x[b]).norm(), options.stretch_compliance});
    }

  const auto triples = angle_triples(x, neighbour_sets(n, edges), &model.raw_triple_count);
  for (const auto& t : triples) {
    if (is_pinned[t.best] && is_pinned[t.k] && is_pinned[t.i]) continue;
    // cos and sin of the rest angle straight from the edge vectors (exact for a straight chain:
    // (-1, 0), where sin(double(pi)) would leave 1.2e-16).
    const Vec3 ua = (x[t.best] - x[t.i]).normalized(), ub = (x[t.k] - x[t.i]).normalized();
    const Vec3 cr = ua.cross(ub);
    const double rc = ua.dot(ub), rs = model.planar ? model.axis.dot(cr) : cr.norm(), r = std::hypot(rc, rs);
    double compliance = options.bending_compliance;
    if (options.bending_stiffness > 0) {
      double lv = 0;
      if (!(is_pinned[t.best] && is_pinned[t.i])) lv += 0.5 * (x[t.best] - x[t.i]).norm();
      if (!(is_pinned[t.k] && is_pinned[t.i])) lv += 0.5 * (x[t.k] - x[t.i]).norm();
      compliance = lv / options.bending_stiffness;
    }
    model.angles.push_back({t.best, t.k, t.i, rc / r, rs / r, compliance});
  }

  // Order by rest positions, not node numbers (numbering-independent Gauss-Seidel order).
  auto& d = model.distances;
  std::sort(d.begin(), d.end(), [&](const DistanceConstraint& p, const DistanceConstraint& q) {
    return sorted_keys(x[p.a], x[p.b]) < sorted_keys(x[q.a], x[q.b]);
  });
  for (auto& c : d)
    if (key(x[c.b]) < key(x[c.a])) std::swap(c.a, c.b);
  auto& a = model.angles;
  std::sort(a.begin(), a.end(), [&](const AngleConstraint& p, const AngleConstraint& q) {
    const auto pp = sorted_keys(x[p.k], x[p.best]), qq = sorted_keys(x[q.k], x[q.best]);
    return std::make_pair(key(x[p.i]), pp) < std::make_pair(key(x[q.i]), qq);
  });
  // Orient each chain so that v_best is the lexicographically smaller end (the angle is symmetric;
  // the signed form flips the sign of theta0 with the orientation).
  for (auto& c : a)
    if (key(x[c.k]) < key(x[c.best])) {
      std::swap(c.k, c.best);
      if (model.planar) c.rest_sin = -c.rest_sin;
    }
  colour_constraints(model, options.block_size);
  return model;
}

}  // namespace pbd
