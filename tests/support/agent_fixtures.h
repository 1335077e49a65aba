#pragma once
// What the agent tests share: transfer coefficients by value (the Poisson decay fixed at 0.5 so
// that hand-computed pushes do not follow alpha2), a unit material, a plate of unit squares and
// one face force of a solved model.
#include <agent/grid.h>
#include <agent/load_transfer.h>

#include <Eigen/Core>

#include <vector>

namespace test_support {

/// Face directions in 2D (agent::direction).
constexpr int kMinusX = 0, kPlusX = 1, kMinusY = 2, kPlusY = 3;

/// E = 1 Pa, nu = 0.3.
inline const agent::Material kMaterial{1.0, 0.3};

inline agent::Coefficients coefficients(double a1, double a2, double a3, double beta, double gamma) {
  agent::Coefficients k;
  k.alpha1 = a1;
  k.alpha2 = a2;
  k.alpha3 = a3;
  k.beta = beta;
  k.gamma = gamma;
  k.threshold = agent::Threshold::Absolute;  // the seed's absolute threshold
  k.poisson_decay = 0.5;
  return k;
}

/// A w x h grid of unit squares, thickness 1, its base (-y side) rigid unless asked otherwise,
/// every other outer face free.
inline agent::Grid plate(int w, int h, bool rigid_base = true) {
  agent::Grid g = agent::Grid::box(2, {w, h, 1}, Eigen::Vector3d(1, 1, 1), 1.0);
  if (rigid_base) g.set_boundary(g.box_side(kMinusY), agent::Boundary::Rigid);
  return g;
}

/// The compressive force on face `f` of agent (i, j) of a solved 2D model [N].
inline double face(const agent::LoadTransfer& m, int i, int j, int f) {
  return m.face_forces()[m.grid().index(i, j, 0) * 4 + f];
}

/// Per-slot values of a grid laid out on tiles (`per` values per slot id of `tiled`), put in the
/// slot order of the same body's dense grid; a slot the tiled grid does not store reads `fill`.
/// With `nodes`, per-node values in the dense grid's node order instead.
template <class T>
std::vector<T> in_dense_order(const agent::Grid& dense, const agent::Grid& tiled, const std::vector<T>& values, int per,
                              T fill, bool nodes = false) {
  const std::size_t n = nodes ? dense.node_count() : dense.count();
  std::vector<T> out(n * per, fill);
  for (std::size_t d = 0; d < n; ++d) {
    const auto c = nodes ? dense.node_coords(d) : dense.coords(d);
    const std::size_t t = nodes ? tiled.node_index(c[0], c[1], c[2]) : tiled.index(c[0], c[1], c[2]);
    if (t == agent::Grid::npos) continue;
    for (int k = 0; k < per; ++k) out[d * per + k] = values[t * per + k];
  }
  return out;
}

}  // namespace test_support
