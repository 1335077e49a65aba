#pragma once
// Time stepping, kept apart from the model: per frame (the seed's one step, one image) `substeps`
// substeps of h = dt / substeps, each: prediction with gravity (an acceleration) and the seed's
// node force (v += h (g + w f), x += h v), XPBD multipliers reset to 0, `iterations` Gauss-Seidel
// sweeps over the distance then the angle constraints (colour by colour, a colour in parallel when
// threads > 1), v = (x - x_prev) / h, damping v *= exp(-damping h).
#include <pbd/model.h>

#include <atomic>
#include <cstdint>
#include <memory>
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
  double angle = 0;     ///< max |C| [rad] over every angle constraint (a compliant one's C is its bend)
  double distance = 0;  ///< max |l - l0| / l0 over every distance constraint
  double rigid_angle = 0;          ///< max |C| [rad] over the rigid (compliance 0) angle constraints
  double inextensible_stretch = 0;  ///< max |l - l0| / l0 over the inextensible (compliance 0) edges
  /// True when a constraint that should hold exactly is violated beyond the tolerances below
  /// (a compliant constraint's C is physical, not an error, so it is not counted).
  bool exceeds_tolerance() const;
  static constexpr double kStretchTolerance = 1e-3;  ///< relative
  static constexpr double kAngleTolerance = 1e-3;    ///< [rad]
};

/// Relative error of a compliant angle constraint's steady state left by one Gauss-Seidel sweep
/// per substep that substeps_for_accuracy() aims at (docs/pbd-model.md, "Choosing substeps").
constexpr double kSubstepAccuracy = 1e-2;

/// The substeps per frame of length `dt` that resolve the stiffest compliant angle constraint:
/// one sweep per substep leaves its steady state too soft by 6 h^2 / (m l^2 alpha) (m the
/// vertex's mass, l the shorter edge, alpha the compliance; for a rod 6 (h/T)^2 N^4 with
/// T = sqrt(rho A L^4 / E I)), so h = sqrt(accuracy m l^2 alpha / 6). 1 when no angle constraint is
/// compliant; at most `max_substeps`.
int substeps_for_accuracy(const Model& model, double dt, double accuracy = kSubstepAccuracy, int max_substeps = 1000000);

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
  // The parts of a substep, each run by every thread t of the substep's team (or by one).
  void predict(double h, const StepSettings& settings, int t, int team);
  /// Sweep `it` of `iterations` (Gauss-Seidel): the first starts the multipliers at 0, after the
  /// last they are not needed.
  void project(double h, int it, int iterations, int t, int team);
  void update_velocities(double h, const StepSettings& settings, int t, int team);
  /// Sets thread t's claim on the blocks of phase g (colour g of the sweeps, counted on through the
  /// substep's sweeps), and takes a block from `owner`'s claim (-1: none left).
  void arm(long g, int t, int team);
  long take(long g, int owner, int team, bool from_front);
  /// Splits the particles among `threads` threads by the constraints each thread projects.
  void own_particles(int threads);
  Model& model_;
  std::vector<double> lambda_distance_, lambda_angle_;
  /// The particles of thread t: owned_[owned_begin_[t] .. owned_begin_[t + 1]), made for a team of
  /// owned_threads_ (0: not made yet) and remade when the particle count changes (the split only
  /// places work; any split of all the particles gives the same results).
  std::vector<int> owned_;
  std::vector<std::size_t> owned_begin_;
  int owned_threads_ = 0;
  /// The blocks of a phase not yet taken, per parity and thread: front | back << 32.
  struct alignas(64) Claim {
    std::atomic<std::uint64_t> range{0};
  };
  std::unique_ptr<Claim[]> claims_;
  int claim_threads_ = 0;
};

}  // namespace pbd
