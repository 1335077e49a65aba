#pragma once
// Time stepping, kept apart from the model: per frame (the seed's one step, one image) `substeps`
// substeps of h = dt / substeps, each: prediction with gravity (an acceleration) and the seed's
// node force (v += h (g + w f), x += h v), XPBD multipliers reset to 0, `iterations` Gauss-Seidel
// sweeps over the distance then the angle constraints (colour by colour, a colour in parallel when
// threads > 1), v = (x - x_prev) / h, damping v *= exp(-damping h).
#include <pbd/model.h>

#include <vector>

namespace pbd {

struct StepSettings {
  double dt = 1.0 / 60;  ///< frame time step [s]
  int substeps = 1;
  int iterations = 1;
  Vec3 gravity = Vec3(0, -9.81, 0);  ///< [m/s^2], acts on every free node
  Vec3 node_force = Vec3::Zero();    ///< the seed's f_ext [N] on every free node (v += h w f)
  double damping = 0;                ///< [1/s]
  int threads = 1;                   ///< > 1: colours in parallel (needs OpenMP)
};

/// Largest constraint violations of the current positions.
struct Residuals {
  double angle = 0;     ///< max |C| [rad]
  double distance = 0;  ///< max |l - l0| / l0
};

class Solver {
 public:
  explicit Solver(Model& model);
  /// One frame.
  void step(const StepSettings& settings);
  /// One substep of length h.
  void substep(double h, const StepSettings& settings);
  Residuals residuals() const;
  /// Whether this build runs colours in parallel (OpenMP).
  static bool parallel_available();

 private:
  void project(double h, int threads);
  Model& model_;
  std::vector<double> lambda_distance_, lambda_angle_;
};

}  // namespace pbd
