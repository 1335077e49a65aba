// The stresses in a layer of agents across a 3D march: the in-plane ones that minimise the
// complementary energy given the out-of-plane ones (docs/agent-model.md, "3D lateral stresses").
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <vector>

namespace agent {

/// A layer's box of n0 x n1 cells of h0 x h1 [m] (cell i0 + n0 i1), `solid` where an agent is.
struct LayerBox {
  int n0 = 0, n1 = 0;
  double h0 = 0, h1 = 0;
  std::vector<char> solid;
};

/// Per cell of the box: what the march gives (`normal`: sigma along the march; `body0`, `body1`:
/// d tau_(march, l) / d(along the march) [Pa/m], the in-plane body force the shears leave) and
/// what the layer answers (`sigma0`, `sigma1`, `tau01` [Pa]; 0 on air).
struct LayerFields {
  std::vector<double> normal, body0, body1;
  std::vector<double> sigma0, sigma1, tau01;
};

/// Solves layers in turn. The layer carries the body force and the Poisson strain
/// -nu sigma_normal / E of each agent (the complementary energy's term in sigma_normal) as a
/// plane-stress plate of Q1 cells with every edge free. Each piece of the layer (agents joined
/// through a corner at least) is a free body: the part of its body force a rigid motion would take
/// (net force and moment: the shears' imbalance) is taken out first, as a uniform force and a
/// rotation's over its cells.
/// No coefficient; E drops out. A layer with the same cells as the previous one reuses its
/// factorisation (a prism's layers are all one).
class LayerSolver {
 public:
  explicit LayerSolver(double poisson);
  /// Reads box and fields' normal, body0, body1; writes fields' sigma0, sigma1, tau01.
  void solve(const LayerBox& box, LayerFields& fields);

 private:
  /// The cell's stiffness, its mean strain and the nodal forces of a unit Poisson strain.
  void cell_matrices(const LayerBox& box);
  /// Numbers the nodes some agent touches and finds the pieces; returns the nodes' count.
  int number_nodes(const LayerBox& box);
  /// The box's stiffness, factorised (kept with the box, its nodes and its pieces).
  void factorise(const LayerBox& box);
  /// The nodal forces of the cells' initial strain and of their body force less its imbalance.
  Eigen::VectorXd nodal_load(const LayerBox& box, const LayerFields& fields) const;
  /// What of the body force a piece's rigid motions would take (net force, moment), taken out.
  void take_out_rigid_motions(const LayerBox& box, std::vector<double>& body0, std::vector<double>& body1) const;
  double nu_;
  Eigen::Matrix<double, 8, 8> ke_;
  Eigen::Matrix<double, 3, 8> b_mean_;   ///< the strain's mean over the cell per nodal displacement
  Eigen::Matrix<double, 8, 1> f_poisson_;  ///< nodal forces of a unit initial strain (1, 1, 0) / E
  Eigen::Matrix3d c_;                     ///< plane stress, E = 1
  LayerBox box_;                          ///< the box factorised
  std::vector<int> node_;                 ///< box node -> unknown pair (-1: no agent touches it)
  std::vector<int> piece_;                ///< unknown pair -> its piece
  int pieces_ = 0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

}  // namespace agent
