#pragma once
// The seed's step 4a/4b: neighbour sets M_i from the mesh and, for each neighbour v_k, the partner
// v_best in M_i with the largest angle between the edges (v_i, v_k) and (v_i, v_best).
#include <pbd/mesh.h>

#include <vector>

namespace pbd {

/// M_i for every node: the nodes that share an edge with it, sorted by index.
std::vector<std::vector<int>> neighbour_sets(std::size_t node_count, const std::vector<std::pair<int, int>>& edges);

/// The seed's v_best for (i, k): the other node of M_i with the largest angle at v_i between the
/// edges to v_k and to it, or -1 when M_i has no other node. Ties (equal angles, e.g. on a
/// symmetric star) go to the candidate with the lexicographically smallest position, so that the
/// choice does not depend on node numbering.
int max_angle_partner(const std::vector<Vec3>& x, int i, const std::vector<int>& neighbours, int k);

/// The seed's chain [v_best, v_k, v_i].
struct Triple {
  int best, k, i;
};

/// All chains of the mesh (steps 4a-4b), deduplicated on (i, min(k, best), max(k, best)): step 4b
/// gives the pair (k, best) and, from best, usually (best, k) again, which would silently double
/// the bending stiffness. `raw_count`, if given, receives the count before deduplication.
std::vector<Triple> angle_triples(const std::vector<Vec3>& x, const std::vector<std::vector<int>>& neighbours,
                                  std::size_t* raw_count = nullptr);

}  // namespace pbd
