// Algebraic multigrid for elasticity (see amg.h): the rigid body modes and the ML parameters.
#include "amg.h"

#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <memory>

namespace fem_reference {

using namespace dealii;

ModeFrame ModeFrame::of_nodes(const std::vector<double>& nodes, int dim) {
  std::array<double, 3> lo{1e308, 1e308, 1e308}, hi{-1e308, -1e308, -1e308};
  for (std::size_t i = 0; i < nodes.size() / 3; ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], nodes[3 * i + a]);
      hi[a] = std::max(hi[a], nodes[3 * i + a]);
    }
  ModeFrame frame;
  frame.size = 0;
  for (int a = 0; a < dim; ++a) {
    frame.centre[a] = 0.5 * (lo[a] + hi[a]);
    frame.size = std::max(frame.size, hi[a] - lo[a]);
  }
  return frame;
}

void set_rigid_body_modes(int dim, const double* x, unsigned component, std::size_t row, std::size_t n_local,
                          std::vector<double>& modes) {
  modes[component * n_local + row] = 1;  // translations
  if (dim == 2) {
    modes[2 * n_local + row] = component == 0 ? -x[1] : x[0];
  } else {
    const double rx[3] = {0, -x[2], x[1]}, ry[3] = {x[2], 0, -x[0]}, rz[3] = {-x[1], x[0], 0};
    modes[3 * n_local + row] = rx[component];
    modes[4 * n_local + row] = ry[component];
    modes[5 * n_local + row] = rz[component];
  }
}

void initialize_elasticity_ml(TrilinosWrappers::PreconditionAMG& amg, const TrilinosWrappers::SparseMatrix& matrix,
                              int dim, int degree, std::vector<double>& modes) {
  TrilinosWrappers::PreconditionAMG::AdditionalData data;
  data.elliptic = true;
  data.higher_order_elements = degree > 1;
  data.smoother_sweeps = 2;
  data.aggregation_threshold = 0.02;
  Teuchos::ParameterList list;
  std::unique_ptr<Epetra_MultiVector> constant_modes;
  data.set_parameters(list, constant_modes, matrix);
  list.set("PDE equations", dim);
  list.set("null space: type", "pre-computed");
  list.set("null space: dimension", dim == 2 ? 3 : 6);
  list.set("null space: vectors", modes.data());
  list.set("ML output", 0);
  amg.initialize(matrix, list);
}

}  // namespace fem_reference
