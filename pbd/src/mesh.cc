// Mesh helpers of the PBD model: generated polylines and grids, edges, and the checks of a usable mesh.
#include <pbd/mesh.h>

#include <algorithm>
#include <numeric>
#include <sstream>

namespace pbd {

int corner_count(int cell_type) {
  switch (cell_type) {
    case kLine: return 2;
    case kTriangle: return 3;
    case kQuad: return 4;
    default: return 0;
  }
}

Mesh Mesh::polyline(const Vec3& a, const Vec3& b, int segments) {
  Mesh m;
  for (int s = 0; s <= segments; ++s) m.points.push_back(a + (b - a) * (double(s) / segments));
  for (int s = 0; s < segments; ++s) m.add_cell(kLine, {s, s + 1});
  return m;
}

Mesh Mesh::grid(int nx, int ny, double h, bool triangles) {
  Mesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.points.emplace_back(i * h, j * h, 0.0);
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (triangles) {
        m.add_cell(kTriangle, {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.add_cell(kTriangle, {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.add_cell(kQuad, {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return m;
}

std::vector<std::pair<int, int>> mesh_edges(const Mesh& mesh) {
  std::vector<std::pair<int, int>> edges;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const int b = mesh.cell_offsets[c], e = mesh.cell_offsets[c + 1], n = e - b;
    if (n < 2) continue;
    const int sides = n == 2 ? 1 : n;
    for (int s = 0; s < sides; ++s) {
      const int u = mesh.cell_nodes[b + s], v = mesh.cell_nodes[b + (s + 1) % n];
      edges.emplace_back(std::min(u, v), std::max(u, v));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

namespace {
std::string point_text(const Vec3& x) {
  std::ostringstream s;
  s << "(" << x[0] << ", " << x[1] << ", " << x[2] << ")";
  return s.str();
}
}  // namespace

std::string mesh_problem(const Mesh& mesh, double tolerance, const std::vector<long long>* node_names) {
  const std::size_t n = mesh.points.size();
  auto name = [&](int i) { return std::to_string(node_names ? (*node_names)[i] : (long long)i); };
  if (n == 0) return "has no nodes";
  if (mesh.cell_count() == 0) return "has no line, triangle or quadrilateral cells";
  if (mesh.cell_offsets.size() != mesh.cell_count() + 1) return "has an inconsistent cell list";
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const int b = mesh.cell_offsets[c], e = mesh.cell_offsets[c + 1];
    const int want = corner_count(mesh.cell_types[c]);
    if (want == 0) return "cell " + std::to_string(c) + " has unsupported VTK type " + std::to_string(mesh.cell_types[c]);
    if (e - b != want) return "cell " + std::to_string(c) + " has " + std::to_string(e - b) + " nodes, expected " + std::to_string(want);
    for (int k = b; k < e; ++k) {
      const int v = mesh.cell_nodes[k];
      if (v < 0 || std::size_t(v) >= n) return "cell " + std::to_string(c) + " refers to node index " + std::to_string(v) + " out of range";
      for (int l = b; l < k; ++l)
        if (mesh.cell_nodes[l] == v) return "cell " + std::to_string(c) + " repeats node " + name(v);
    }
  }
  Vec3 lo = mesh.points[0], hi = mesh.points[0];
  for (const auto& p : mesh.points) {
    if (!p.allFinite()) return "a node has a non-finite coordinate";
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double eps = tolerance * std::max((hi - lo).norm(), 1e-300);
  for (const auto& [a, b] : mesh_edges(mesh))
    if ((mesh.points[a] - mesh.points[b]).norm() <= eps)
      return "zero-length edge between nodes " + name(a) + " and " + name(b) + " at " + point_text(mesh.points[a]);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return mesh.points[a][0] < mesh.points[b][0]; });
  for (std::size_t s = 0; s < n; ++s)
    for (std::size_t t = s + 1; t < n && mesh.points[order[t]][0] - mesh.points[order[s]][0] <= eps; ++t)
      if ((mesh.points[order[s]] - mesh.points[order[t]]).norm() <= eps) {
        const int a = std::min(order[s], order[t]), b = std::max(order[s], order[t]);
        return "duplicate nodes " + name(a) + " and " + name(b) + " at " + point_text(mesh.points[a]);
      }
  std::vector<char> used(n, 0);
  for (int v : mesh.cell_nodes) used[v] = 1;
  for (std::size_t i = 0; i < n; ++i)
    if (!used[i]) return "isolated node " + name(int(i)) + " at " + point_text(mesh.points[i]) + " (in no cell)";
  return "";
}

}  // namespace pbd
