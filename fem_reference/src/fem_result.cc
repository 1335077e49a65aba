// FemResult's one function (fem_result.h): the plain-data library compare/analysis links alone.
#include <fem_reference/fem_result.h>

namespace fem_reference {

std::array<double, 3> FemResult::displacement_at(const std::array<double, 3>& x) const {
  std::size_t best = 0;
  double best_d = 1e308;
  for (std::size_t i = 0; i < node_count(); ++i) {
    double d = 0;
    for (int a = 0; a < 3; ++a) d += (node_points[3 * i + a] - x[a]) * (node_points[3 * i + a] - x[a]);
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  std::array<double, 3> u{};
  for (int a = 0; a < dim && best < node_count(); ++a) u[a] = node_displacement[dim * best + a];
  return u;
}

}  // namespace fem_reference
