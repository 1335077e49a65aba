#pragma once
// Every stress component of the agents, from what a transfer wrote: the normal stresses of the
// face forces, and a rule set's own shear (TransferResults::shear: the directional packets', the
// columns'), with the directional rule set's row moment balance (TransferResults::balance). With
// turning paths also sigma across the march by the tie scan and the bonded rigid face's layer
// (docs/agent-model.md, "Turning paths"). Each rule type says which it gives (its
// stress_components; LoadTransfer::stress_components calls the one in use).
#include <agent/coefficients.h>
#include <agent/grid.h>
#include <agent/transfer.h>

#include <vector>

namespace agent {

struct StressComponents {
  std::vector<double> sigma;      ///< dim normal stresses per agent [Pa] (slot order)
  std::vector<double> shear;      ///< per agent: 2D tau_xy; 3D tau_xy, tau_yz, tau_xz [Pa]
  std::vector<double> von_mises;  ///< per agent [Pa] (plane stress in 2D)
};

/// The shears in a slot of StressComponents::shear: 1 in 2D, 3 in 3D.
constexpr int shear_count(int dim) { return dim == 3 ? 3 : 1; }

/// What a rule type's stress components are (each rule type's static stress_model): which
/// components it models, and whether its fields include a closed-form layer. A component it does
/// not model (the columns' sigma across the beam, the seed's shears) is written as it is (0), but
/// a comparison marks it "not modelled" rather than scoring it as the model's error. A rule set
/// that combines rule types models the union of theirs (operator|).
struct StressModel {
  /// Bit workbench::kXX + i per normal stress, kXY + i per shear (workbench/symmetric_tensor.h order).
  unsigned modelled = 0;
  /// Its fields include a closed-form layer (2D directional, turning paths: Kirsch's shear round a
  /// hole, the half-plane's layer on a bonded base), left out by closed_forms = "left_out".
  bool closed_forms = false;
  /// Whether stress slot `slot` (a workbench::SymmetricTensor component) is the model's own.
  constexpr bool models(int slot) const { return (modelled >> unsigned(slot)) & 1u; }
  constexpr StressModel operator|(const StressModel& o) const { return {modelled | o.modelled, closed_forms || o.closed_forms}; }
};
/// The bits of the normal stresses and of the shears of a `dim`-D grid.
constexpr unsigned normal_stress_bits(int dim) { return dim == 3 ? 0b000111u : 0b000011u; }
constexpr unsigned shear_bits(int dim) { return dim == 3 ? 0b111000u : 0b001000u; }

/// The normal stresses alone (`normal`: agent_stresses', dim per slot), no shear: the seed's rule sets.
StressComponents normal_stress_components(const Grid& grid, const std::vector<double>& normal);
/// The normal stresses and a shear the transfer wrote (shear_count per slot): the columns rule set.
StressComponents stress_components_with_shear(const Grid& grid, const std::vector<double>& normal,
                                              const std::vector<double>& shear);

/// The directional rule set's stress components of one solve. `normal` is agent_stresses' (dim per
/// slot). `shear` and `balance` are the transfer's (TransferResults::shear, ::balance, sized by
/// DirectionalTransfer::size_results). Per march axis a:
///   tau_(a, l) = the packets' shear + the balance's shear (vertical equilibrium scanned along each
///            row, its derivative along a from a local quadratic fit over k.window_length);
/// and with k.paths == Paths::Turning, in 2D
///   sigma across a += the tie: horizontal equilibrium scanned along each run of agents from its
///            lower end (0 there), what is left at the upper end taken out linearly;
///   the layer on a bonded rigid face the loads march onto (it holds sigma across a = nu sigma_a):
///            the elastic half-plane's answer to that restraint, per run of agents on the face with
///            free ends: nu sigma_a of the face's agents in sine modes of the run's width, mode k
///            reaching height y as (1 - k y / 2) exp(-k y); its shear by horizontal equilibrium;
///   before the tie, each hole's shear (hole_shear), the stress concentration at its corners;
/// in 3D
///   sigma_l0, sigma_l1 and tau_(l0, l1) of each layer of agents across a: the in-plane stresses
///            of least complementary energy given sigma_a and the body force d tau_(a, l) / d(along
///            a) (centred) of the shears above (LayerSolver, agent/layer_stresses.h); they replace
///            the packets' tau_(l0, l1) unless a march along l0 or l1 shares that pair;
///   the bonded rigid face's local layer, nu / (1 - nu) sigma_a max(0, 1 - y / ell)
///            (1 - exp(-d_side / y)) across each lateral axis, ell = k.base_layer_3d x the width of
///            the pressure on that face, its shear by horizontal equilibrium.
/// `loads` give each march axis its direction (which end the rigid face of the layer is at).
StressComponents directional_stress_components(const Grid& grid, const std::vector<double>& normal,
                                               const std::vector<double>& shear, const std::vector<double>& balance,
                                               const DirectionalCoefficients& k, double poisson,
                                               const std::vector<EntryLoad>& loads);

/// A hole of a 2D grid: a component of air slots (4-connected) that touches no side of the box.
struct Hole {
  double area = 0;              ///< [m^2]
  double centre[2] = {0, 0};    ///< its centroid [m]
};
std::vector<Hole> enclosed_holes(const Grid& grid);

/// Kirsch's shear about a circular hole of `radius` in an infinite plate under a uniaxial stress
/// `remote` along the first axis (without the hole the plate has none): tau in the (along, across)
/// frame at offset (along, across) from the hole's centre; at r < radius, r = radius.
double kirsch_shear(double along, double across, double radius, double remote);

/// 2D, loads marching along axis a: per agent the sum over enclosed_holes of kirsch_shear, the
/// hole a circle of its area at its centroid, `remote` the gross stress along a of the row through
/// its centre (the row's force over the row's extent, the hole's width included); only where that
/// row holds at least the radius of body on each side of the hole (Kirsch's plate is infinite: not
/// a ring's inside, whose walls are beams), over the agents within 10 radii of its centre (the
/// disturbance there is a percent of the remote stress). The paths carry
/// the load round a hole (docs/agent-model.md, "Holes and notches"); this is the shear they do not.
std::vector<double> hole_shear(const Grid& grid, int a, const std::vector<double>& normal);

/// d F / d(index) at every entry of a line of `count` values (stride `stride`), from the slope of a
/// least-squares quadratic about each entry with Gaussian weights of standard deviation `window`
/// entries (entries within 4 windows). Two entries: their difference; one: 0.
void fitted_slope(const double* values, std::size_t stride, int count, double window, double* slope);

}  // namespace agent
