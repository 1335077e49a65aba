// The seed's topology steps: neighbour sets and the max-angle partner of each chain.
#include <pbd/constraints.h>
#include <pbd/topology.h>

#include <algorithm>
#include <tuple>

namespace pbd {

std::vector<std::vector<int>> neighbour_sets(std::size_t node_count, const std::vector<std::pair<int, int>>& edges) {
  std::vector<std::vector<int>> m(node_count);
  for (const auto& [a, b] : edges) {
    m[a].push_back(b);
    m[b].push_back(a);
  }
  for (auto& s : m) {
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
  }
  return m;
}

namespace {
bool lex_less(const Vec3& a, const Vec3& b) {
  return std::tie(a[0], a[1], a[2]) < std::tie(b[0], b[1], b[2]);
}
}  // namespace

int max_angle_partner(const std::vector<Vec3>& x, int i, const std::vector<int>& neighbours, int k) {
  int best = -1;
  double best_angle = -1;
  for (int j : neighbours) {
    if (j == k) continue;
    const double a = angle(x[k], x[j], x[i]);
    if (a > best_angle || (a == best_angle && lex_less(x[j], x[best]))) {
      best = j;
      best_angle = a;
    }
  }
  return best;
}

std::vector<Triple> angle_triples(const std::vector<Vec3>& x, const std::vector<std::vector<int>>& neighbours,
                                  std::size_t* raw_count) {
  std::vector<Triple> out;
  std::size_t raw = 0;
  for (std::size_t i = 0; i < neighbours.size(); ++i) {
    const auto& m = neighbours[i];
    const std::size_t first = out.size();
    for (int k : m) {
      const int best = max_angle_partner(x, int(i), m, k);
      if (best < 0) continue;
      ++raw;
      const int lo = std::min(k, best), hi = std::max(k, best);
      bool seen = false;
      for (std::size_t t = first; t < out.size() && !seen; ++t)
        seen = std::min(out[t].k, out[t].best) == lo && std::max(out[t].k, out[t].best) == hi;
      if (!seen) out.push_back({best, k, int(i)});
    }
  }
  if (raw_count) *raw_count = raw;
  return out;
}

}  // namespace pbd
