// The stresses in a layer of agents across a 3D march (layer_stresses.h).
#include <agent/layer_stresses.h>

#include <cmath>
#include <stdexcept>

namespace agent {

namespace {

/// The box node at corner k (0..3, counter-clockwise from the low corner) of cell (i0, i1).
int corner(const LayerBox& box, int i0, int i1, int k) {
  static constexpr int d0[4] = {0, 1, 1, 0}, d1[4] = {0, 0, 1, 1};
  return (i0 + d0[k]) + (box.n0 + 1) * (i1 + d1[k]);
}

/// Union-find root with path halving.
int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

LayerSolver::LayerSolver(double poisson) : nu_(poisson) {
  c_ << 1, nu_, 0, nu_, 1, 0, 0, 0, 0.5 * (1 - nu_);
  c_ /= 1 - nu_ * nu_;
}

void LayerSolver::cell_matrices(const LayerBox& box) {
  // The Q1 cell of h0 x h1, 2 x 2 Gauss points.
  const double g = 1 / std::sqrt(3.0), w = 0.25 * box.h0 * box.h1;
  static constexpr double s0[4] = {-1, 1, 1, -1}, s1[4] = {-1, -1, 1, 1};
  ke_.setZero();
  b_mean_.setZero();
  f_poisson_.setZero();
  const Eigen::Vector3d unit_strain(1, 1, 0);
  for (const double xi : {-g, g})
    for (const double eta : {-g, g}) {
      Eigen::Matrix<double, 3, 8> b = Eigen::Matrix<double, 3, 8>::Zero();
      for (int k = 0; k < 4; ++k) {
        const double dx0 = 0.25 * s0[k] * (1 + s1[k] * eta) * 2 / box.h0;
        const double dx1 = 0.25 * s1[k] * (1 + s0[k] * xi) * 2 / box.h1;
        b(0, 2 * k) = dx0;
        b(1, 2 * k + 1) = dx1;
        b(2, 2 * k) = dx1;
        b(2, 2 * k + 1) = dx0;
      }
      ke_ += w * b.transpose() * c_ * b;
      f_poisson_ += w * b.transpose() * c_ * unit_strain;
      b_mean_ += 0.25 * b;
    }
}

int LayerSolver::number_nodes(const LayerBox& box) {
  // The unknowns: the nodes some agent touches; the pieces: nodes joined through cells.
  const int nodes = (box.n0 + 1) * (box.n1 + 1);
  std::vector<int> parent(std::size_t(nodes), -1);
  for (int i1 = 0; i1 < box.n1; ++i1)
    for (int i0 = 0; i0 < box.n0; ++i0) {
      if (!box.solid[std::size_t(i0 + box.n0 * i1)]) continue;
      for (int k = 0; k < 4; ++k)
        if (parent[corner(box, i0, i1, k)] < 0) parent[corner(box, i0, i1, k)] = corner(box, i0, i1, k);
      const int r = root(parent, corner(box, i0, i1, 0));
      for (int k = 1; k < 4; ++k) parent[root(parent, corner(box, i0, i1, k))] = r;
    }
  node_.assign(std::size_t(nodes), -1);
  int count = 0;
  for (int n = 0; n < nodes; ++n)
    if (parent[n] >= 0) node_[n] = count++;
  piece_.assign(std::size_t(count), 0);
  std::vector<int> piece_of_root(std::size_t(nodes), -1);
  pieces_ = 0;
  for (int n = 0; n < nodes; ++n) {
    if (node_[n] < 0) continue;
    int& p = piece_of_root[root(parent, n)];
    if (p < 0) p = pieces_++;
    piece_[node_[n]] = p;
  }
  return count;
}

void LayerSolver::factorise(const LayerBox& box) {
  box_ = box;
  cell_matrices(box);
  const int count = number_nodes(box);
  if (count == 0) return;  // no agent: nothing to factorise
  // K's lower triangle (what the LDL^T reads), plus a shift of 1e-10 of its largest diagonal: the
  // loads are balanced per piece (solve), so the shift only fixes the rigid motions they no longer
  // excite. A node meets at most 9 nodes: 18 entries a column.
  Eigen::SparseMatrix<double> k(2 * count, 2 * count);
  k.reserve(Eigen::VectorXi::Constant(2 * count, 18));
  for (int i1 = 0; i1 < box.n1; ++i1)
    for (int i0 = 0; i0 < box.n0; ++i0) {
      if (!box.solid[std::size_t(i0 + box.n0 * i1)]) continue;
      for (int c = 0; c < 8; ++c)
        for (int r = 0; r < 8; ++r) {
          const int row = 2 * node_[corner(box, i0, i1, r / 2)] + r % 2;
          const int col = 2 * node_[corner(box, i0, i1, c / 2)] + c % 2;
          if (row >= col) k.coeffRef(row, col) += ke_(r, c);
        }
    }
  const double shift = 1e-10 * ke_.diagonal().maxCoeff();
  for (int i = 0; i < 2 * count; ++i) k.coeffRef(i, i) += shift;
  k.makeCompressed();
  ldlt_.compute(k);
  if (ldlt_.info() != Eigen::Success) throw std::runtime_error("a layer's stiffness could not be factorised");
}

void LayerSolver::solve(const LayerBox& box, LayerFields& f) {
  if (box.n0 != box_.n0 || box.n1 != box_.n1 || box.h0 != box_.h0 || box.h1 != box_.h1 || box.solid != box_.solid)
    factorise(box);
  f.sigma0.assign(box.solid.size(), 0.0);
  f.sigma1.assign(box.solid.size(), 0.0);
  f.tau01.assign(box.solid.size(), 0.0);
  if (piece_.empty()) return;
  const Eigen::VectorXd load = nodal_load(box, f);
  const Eigen::VectorXd displacement = ldlt_.solve(load);
  // Each cell's stress: C (mean strain + nu sigma_normal (1, 1, 0)), the mean over its points.
  const double held = nu_ / (1 - nu_);  // C (1, 1, 0) per component, E = 1
  for (std::size_t cell = 0; cell < box.solid.size(); ++cell) {
    if (!box.solid[cell]) continue;
    const int i0 = int(cell) % box.n0, i1 = int(cell) / box.n0;
    Eigen::Matrix<double, 8, 1> ue;
    for (int k = 0; k < 4; ++k) ue.segment<2>(2 * k) = displacement.segment<2>(2 * node_[corner(box, i0, i1, k)]);
    const Eigen::Vector3d s = c_ * (b_mean_ * ue);
    f.sigma0[cell] = s[0] + held * f.normal[cell];
    f.sigma1[cell] = s[1] + held * f.normal[cell];
    f.tau01[cell] = s[2];
  }
}

Eigen::VectorXd LayerSolver::nodal_load(const LayerBox& box, const LayerFields& f) const {
  std::vector<double> body0 = f.body0, body1 = f.body1;
  take_out_rigid_motions(box, body0, body1);
  Eigen::VectorXd load = Eigen::VectorXd::Zero(2 * Eigen::Index(piece_.size()));
  const double quarter = 0.25 * box.h0 * box.h1;
  for (int i1 = 0; i1 < box.n1; ++i1)
    for (int i0 = 0; i0 < box.n0; ++i0) {
      const std::size_t cell = std::size_t(i0 + box.n0 * i1);
      if (!box.solid[cell]) continue;
      for (int k = 0; k < 4; ++k) {
        const int u = node_[corner(box, i0, i1, k)];
        // the initial strain -nu sigma_normal (E = 1) and a quarter of the cell's body force
        load[2 * u] += -nu_ * f.normal[cell] * f_poisson_[2 * k] + quarter * body0[cell];
        load[2 * u + 1] += -nu_ * f.normal[cell] * f_poisson_[2 * k + 1] + quarter * body1[cell];
      }
    }
  return load;
}

void LayerSolver::take_out_rigid_motions(const LayerBox& box, std::vector<double>& body0,
                                         std::vector<double>& body1) const {
  // Per piece: the net force and the moment about its centroid, where the body forces of the
  // three rigid motions (two uniform, a rotation) are orthogonal; each taken out along its motion.
  // (A cell's force shared equally by its corners keeps both, so the nodes' load is balanced too.)
  struct Piece {
    double cells = 0, x0 = 0, x1 = 0, f0 = 0, f1 = 0, moment = 0, inertia = 0;
  };
  std::vector<Piece> sums(static_cast<std::size_t>(pieces_));
  const auto each_cell = [&](auto&& visit) {
    for (std::size_t cell = 0; cell < box.solid.size(); ++cell) {
      if (!box.solid[cell]) continue;
      const int i0 = int(cell) % box.n0, i1 = int(cell) / box.n0;
      visit(cell, sums[piece_[node_[corner(box, i0, i1, 0)]]], (i0 + 0.5) * box.h0, (i1 + 0.5) * box.h1);
    }
  };
  each_cell([](std::size_t, Piece& p, double x0, double x1) {
    p.cells += 1;
    p.x0 += x0;
    p.x1 += x1;
  });
  each_cell([&](std::size_t cell, Piece& p, double x0, double x1) {
    const double r0 = x0 - p.x0 / p.cells, r1 = x1 - p.x1 / p.cells;
    p.f0 += body0[cell];
    p.f1 += body1[cell];
    p.moment += r0 * body1[cell] - r1 * body0[cell];
    p.inertia += r0 * r0 + r1 * r1;
  });
  each_cell([&](std::size_t cell, Piece& p, double x0, double x1) {
    const double r0 = x0 - p.x0 / p.cells, r1 = x1 - p.x1 / p.cells;
    const double spin = p.inertia > 0 ? p.moment / p.inertia : 0.0;
    body0[cell] -= p.f0 / p.cells - spin * r1;
    body1[cell] -= p.f1 / p.cells + spin * r0;
  });
}

}  // namespace agent
