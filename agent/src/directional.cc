// The directional rule set (the project's extension): its fan, and the path type its coefficients
// name (turning_paths.cc, mirror_paths.cc; what both share: directional_march.h).
#include "directional_march.h"

#include <cmath>

namespace agent {

Fan entry_fan(const DirectionalCoefficients& k, int dim) {
  const double power = dim == 3 ? k.fan_power_3d : k.fan_power;
  // Angles evenly spaced over (-fan_angle, fan_angle), none straight down (an even count).
  const double pi = std::acos(-1.0);
  Fan fan;
  double total = 0;
  for (int i = 0; i < k.directions; ++i) {
    const double angle = k.fan_angle * pi / 180 * ((2.0 * i + 1) / k.directions - 1);
    fan.slope.push_back(std::tan(angle));
    fan.weight.push_back(std::pow(std::cos(angle), power));
    total += fan.weight.back();
  }
  for (double& w : fan.weight) w /= total;
  return fan;
}

void directional_transfer(const Grid& grid, const DirectionalCoefficients& k, double gamma,
                          const std::vector<EntryLoad>& loads, std::vector<double>& faces,
                          std::vector<std::int32_t>& generation, Diagnostics& diagnostics, std::vector<double>& shear,
                          std::vector<double>& balance) {
  directional::Sinks out{faces, generation, diagnostics, shear.empty() ? nullptr : shear.data(),
                         balance.empty() ? nullptr : balance.data()};
  if (k.paths == Paths::Turning)
    directional::march_turning(grid, k, gamma, loads, out);
  else
    directional::march_mirror(grid, k, gamma, loads, out);
}

int DirectionalTransfer::lateral_reach(const Grid&, const Coefficients& k) {
  return int(std::ceil(std::tan(k.directional.fan_angle * M_PI / 180.0)));
}

DirectionalTransfer::DirectionalTransfer(const Coefficients& k) : k_(k) { check_coefficients(k, RuleSet::Directional); }

void DirectionalTransfer::solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out) {
  out.clear_all();
  directional_transfer(grid, k_.directional, k_.gamma, loads, out.faces, out.generation, out.diagnostics, out.shear,
                       out.balance);
}

}  // namespace agent
