#pragma once
// The particles of a position-based model: positions, velocities, inverse masses, pinned flags.
// Plain arrays (structure of arrays), so that a game can own and fill them directly.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pbd {

using Vec3 = Eigen::Vector3d;

struct Particles {
  std::vector<Vec3> x;       ///< current positions [m] (the seed's x_i; the start of the next step)
  std::vector<Vec3> v;       ///< velocities [m/s]
  std::vector<Vec3> x_prev;  ///< positions at the start of the (sub)step, for v = (x - x_prev) / h
  std::vector<double> w;     ///< inverse masses [1/kg]; 0 for a pinned particle
  std::vector<std::uint8_t> pinned;

  std::size_t size() const { return x.size(); }
  /// Appends a particle at rest; a pinned particle gets w = 0 whatever its mass.
  void add(const Vec3& position, double mass, bool is_pinned = false) {
    x.push_back(position);
    v.push_back(Vec3::Zero());
    x_prev.push_back(position);
    w.push_back(is_pinned || !(mass > 0) ? 0.0 : 1.0 / mass);
    pinned.push_back(is_pinned ? 1 : 0);
  }
  /// Sum of m v over the free particles [kg m/s].
  Vec3 momentum() const {
    Vec3 p = Vec3::Zero();
    for (std::size_t i = 0; i < size(); ++i)
      if (w[i] > 0) p += v[i] / w[i];
    return p;
  }
  /// Sum of m x over the free particles (their centre of mass times their mass).
  Vec3 mass_moment() const {
    Vec3 p = Vec3::Zero();
    for (std::size_t i = 0; i < size(); ++i)
      if (w[i] > 0) p += x[i] / w[i];
    return p;
  }
  double kinetic_energy() const {
    double e = 0;
    for (std::size_t i = 0; i < size(); ++i)
      if (w[i] > 0) e += 0.5 * v[i].squaredNorm() / w[i];
    return e;
  }
};

}  // namespace pbd
