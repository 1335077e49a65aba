#pragma once
// The column rule set (docs/agent-model.md, "Bending: the column rule set"; research:
// bench/research/bending.py, beam_columns.py): a load whose rigid faces lie beside it (a cantilever,
// a beam on end supports) reaches them through shear and bending. The agents are cut into columns
// across the beam axis (the axis along which the rigid faces lie beside the loads); each column's
// area, centroid and second moment come from its own agents (a notch changes them). The section
// resultants are passed column to column from the loads to the clamp or the supports; each column
// spreads its moment linearly over its agents (Navier) and its shear by a scan down the column
// (Jourawski). The deflection is marched from the clamp or the supports. In 3D a column is the
// slab of agents of equal coordinate along the beam axis: a section in t (the load axis) and w.
#include <agent/grid.h>
#include <agent/stress_components.h>
#include <agent/transfer.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace agent {

/// Where the rigid faces hold the beam: a clamp (rigid faces across the beam axis, in one plane at
/// one end of the body) or two supports (rigid faces along the beam axis, in two separate stretches
/// on one side of the body, in one plane).
enum class Holding { Clamp, Supports };

/// How the column rule set carries a set of loads (agent::plan_columns).
struct ColumnPlan {
  int axis = 0;    ///< the beam axis a: the columns are the slots of equal coordinate along it
  int across = 1;  ///< the load axis t
  /// The third axis w (3D: the sections are slabs across a, in t and w; 2D: the thickness, z).
  int width_axis() const { return 3 - axis - across; }
  Holding holding = Holding::Clamp;
  /// Clamp: the clamp plane along a [m] (at [0]) and the side its faces face (-a: the body lies at
  /// larger a). Supports: the centres of the two supports along a [m], increasing.
  std::array<double, 2> at{};
  int clamp_side = 0;
  double support_level = 0;  ///< supports: the plane of their faces along t [m]
  double rigid_area = 0;     ///< area of the rigid faces that take the load [m^2]
};

/// The plan for `loads` (EntryLoad: cell, marching direction; forces are not read) on `grid`, or
/// std::invalid_argument saying in one sentence why the column rule cannot carry them: no load,
/// loads along two axes, no rigid face, rigid faces both across and along the beam axis, clamps at
/// both ends or on several planes, agents beyond the clamp, one support or more than two, supports
/// on both sides or at two levels, a column along the beam axis without agents; in 3D also clamps
/// across two axes and supports apart along both axes across t. The beam axis: in 2D the axis
/// across t; in 3D the rigid faces' normal where it is not t (a clamp), else the axis across t along
/// which the supports lie apart.
ColumnPlan plan_columns(const Grid& grid, const std::vector<EntryLoad>& loads);

/// Whether the columns carry `loads` to a clamp (false: to supports, or not at all).
bool clamped(const Grid& grid, const std::vector<EntryLoad>& loads);

/// How a plan carries its loads, in words: "bending: columns along x to the clamp at x = 0 mm".
std::string describe(const ColumnPlan& plan);

/// The columns of a plan and their section resultants (sign convention: the part of the body at
/// lower a, its cut face's outward normal +a): per column (slot along a), the force across the
/// cut v = int tau dA, the moment m = int sigma_a (t - centroid) dA about the column's centroid and
/// the axial force n = int sigma_a dA.
struct Columns {
  ColumnPlan plan;
  std::vector<double> centre, width;            ///< per column, along a [m]
  std::vector<double> area, centroid, inertia;  ///< per column [m^2], along t [m], [m^4] (about w)
  std::vector<double> centroid_w;               ///< 3D: per column, the centroid along w [m]; 2D: empty
  /// Per column, the rows along t (agent coordinates) of its section: a clamped beam's section
  /// spreads from the free end toward the clamp at 45 degrees (by one column's width a column, each
  /// way: Saint-Venant's spread into a deeper part, as an L-bracket's upright arm above its foot);
  /// the agents beyond it carry nothing. Supports: every agent of the column.
  std::vector<int> first_row, last_row;
  bool in_section(std::size_t column, int row) const { return row >= first_row[column] && row <= last_row[column]; }
  /// Under a clamp, per column, the core of its stresses' section: the rows of the narrowest section
  /// from the free end (the previous column's core clipped to the column's agents, an L-bracket's
  /// foot), whole; and beyond each edge of it the reach of the 45-degree spread from the column where
  /// the agents first extend past it, at this column's clamp-side face [rows] (0: none beyond).
  std::vector<int> core_first, core_last;
  std::vector<double> reach_low, reach_high;
  /// An agent's share in its column's stresses (docs/agent-model.md, "Flamant's fan"): 1 in the
  /// core; beyond it, eta rows past the core's edge with the reach d there, d^4 / (d^2 + eta^2)^2
  /// (Flamant's half-plane under a force along its edge: sigma = -2 P d^3 / (pi b (d^2 + eta^2)^2) on
  /// the section d ahead of it).
  double weight(std::size_t column, int row) const {
    if (row >= core_first[column] && row <= core_last[column]) return 1.0;
    const bool high = row > core_last[column];
    const double q = (high ? row - core_last[column] - 0.5 : core_first[column] - row - 0.5) / (high ? reach_high[column] : reach_low[column]);
    return 1 / ((1 + q * q) * (1 + q * q));
  }
  /// Whether the column's agents extend beyond its core (its section widens there).
  bool widens(std::size_t column) const { return reach_low[column] > 0 || reach_high[column] > 0; }
  std::vector<double> v, m, n;                  ///< per column [N], [N m], [N]
  /// Across the beam axis [N] (signed along +t): clamp: [0] the clamp's; supports: each support's.
  std::array<double, 2> reactions{};
  double clamp_moment = 0;  ///< the clamp's couple on the body [N m], positive turning +a toward +t
  double thrust = 0;        ///< supports: the axial force the supports hold the span with (n = -thrust there) [N]
};

/// The statics of `loads` (forces >= 0 along their direction): each column's area, centroid and
/// second moment from its agents, the reactions from the balance of forces and moments (a clamp
/// takes the force and the couple), and v, m per column. No thrust (supports free to slide).
/// Throws what plan_columns throws.
Columns column_statics(const Grid& grid, const std::vector<EntryLoad>& loads);

/// Supports that hold the body (bonded rigid faces, as the agents' and FEM's are): the face they
/// hold cannot lengthen between them, so they hold the span with a thrust H along a at their level
/// (compatibility, two scans over the span): H = -int m e / I da / int (1 / A + e^2 / I) da, e the
/// column's centroid less the supports' level; n = -H and m += e H in the span. A clamp: nothing.
void add_bonded_thrust(Columns& columns);

/// The fields of the columns into `out` (every slot of the grid; out.faces, generation and shear
/// sized for it): per agent sigma_a = n / A + m (t - centroid) / I as compressive face forces on its
/// two faces across a (between supports sigma_t = sigma_w = 0: its other faces carry nothing; at a
/// clamp the clamp's layer, in 2D also the loads' layer, on its faces across t and w), tau_at = v Q / (I b)
/// in out.shear's a-t slot (Q the first moment of what lies above each level of agents, averaged
/// over their height: a column's shears integrate to v; b the section's width there: the
/// thickness in 2D, the level's agents times their edge in 3D; the other shears 0); per node
/// (out.displacement, dim per node id) the plane sections' displacement marched from the clamp or
/// the supports: rotation by the curvature m / (E I), deflection by the rotation and the column's
/// shear strain (the energy mean of tau / G), axial displacement by n / (E A), the Poisson strain
/// -nu sigma_a / E integrated across t (u_t) and in 3D across w from the column's centroid (u_w,
/// and u_t's anticlastic part nu m (w - w_c)^2 / (2 E I): Saint-Venant's pure bending); zero
/// rotation, axial displacement and deflection of the clamp column's centroid on the clamp plane;
/// zero deflection at both support centres and zero axial displacement at the first, at the
/// supports' plane. Generation: columns from the nearest loaded column (-1 in a column without
/// resultants); the load balance: every load is carried to the rigid faces (rigid_reaction =
/// applied, by the statics).
void column_fields(const Grid& grid, const Material& material, const Columns& columns,
                   const std::vector<EntryLoad>& loads, TransferResults& out);

/// The column rule set as a LoadTransfer rule type: statics, the bonded thrust, the fields. It reads
/// no coefficient and takes no reading; 2D or 3D; the plan is made per solve (std::invalid_argument
/// when the loads cannot be carried).
class ColumnTransfer {
 public:
  ColumnTransfer(const Grid& grid, const Material& material);
  /// Clears the whole result (a column's resultants reach all its agents), then carries `loads`.
  void solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out);
  std::size_t memory_bytes() const { return 0; }  ///< nothing held between solves

  /// The face forces and generations, the shear stress per slot and the node displacements.
  static void size_results(const Grid& grid, TransferResults& out) {
    out.size_forces(grid);
    out.shear.assign(grid.count() * std::size_t(shear_count(grid.dim)), 0.0);
    out.displacement.assign(grid.node_count() * std::size_t(grid.dim), 0.0);
  }
  /// Bending carries a load along the beam to a clamp or supports anywhere in the body: the box's
  /// widest side, in agents.
  static int lateral_reach(const Grid& grid, const Coefficients&) { return std::max({grid.cells[0], grid.cells[1], grid.cells[2]}); }
  /// The normal stresses of the faces and the columns' own shear (TransferResults::shear).
  static StressComponents stress_components(const Grid& grid, const TransferResults& out,
                                            const std::vector<double>& normal, double, const std::vector<EntryLoad>&) {
    return stress_components_with_shear(grid, normal, out.shear);
  }
  /// sigma along the beam axis and the shear in the beam-load plane; under a clamp also the normal
  /// stresses across the beam (the clamp's layer) and in 3D tau_aw (the clamp's shear); between
  /// supports they are 0, not modelled.
  static StressModel stress_model(const Grid& grid, const Coefficients&, const std::vector<EntryLoad>& loads) {
    const unsigned along_load = loads.empty() ? 0u : 1u << unsigned(axis_of(loads.front().dir));
    if (loads.empty()) return {(normal_stress_bits(grid.dim) & ~along_load) | shear_bits(grid.dim), false};
    if (grid.dim == 2) return {(normal_stress_bits(2) & ~(clamped(grid, loads) ? 0u : along_load)) | shear_bits(2), false};
    const ColumnPlan plan = plan_columns(grid, loads);
    const unsigned first_shear = shear_bits(2);  // tau_xy's bit; the 3D shears follow in shear_pair order
    const unsigned normal = plan.holding == Holding::Clamp ? normal_stress_bits(3) : 1u << unsigned(plan.axis);
    const unsigned clamp_shear = plan.holding == Holding::Clamp ? first_shear << unsigned(shear_pair(plan.axis, plan.width_axis())) : 0u;
    return {normal | clamp_shear | (first_shear << unsigned(shear_pair(plan.axis, plan.across))), false};
  }

 private:
  Material material_;
};

}  // namespace agent
