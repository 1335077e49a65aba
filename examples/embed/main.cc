// embed: a program outside the workbench that links its two models through the installed package
// (find_package(workbench)), runs each on a small problem and checks a closed-form answer.
//
//   cmake -S examples/embed -B build-embed -DCMAKE_PREFIX_PATH=/usr/local && build-embed/embed
//
// 1. Agent load transfer (conserving rules) on a 10 x 10 plate on a rigid base: the 2 N must be
//    accounted for, reaction + passed out + dropped + lost, with nothing lost by these rules.
// 2. PBD angle bending: a clamped rod, E I = 1, L = 1, under q = 0.008 N/m: the tip deflection of
//    a 10-segment chain is Euler-Bernoulli's q L^4 / (8 E I) = 1e-3 m, 1 % softer.
// Exits 1 when a check fails.
#include <agent/load_transfer.h>
#include <pbd/model.h>
#include <pbd/solver.h>

#include <cmath>
#include <cstdio>

namespace {

bool agent_plate() {
  agent::Grid grid = agent::Grid::box(2, {10, 10, 1}, Eigen::Vector3d(0.01, 0.01, 1), 0.002);
  grid.set_boundary(grid.box_side(agent::direction(1, false)), agent::Boundary::Rigid);
  agent::LoadTransfer model(grid, agent::Material{}, agent::Coefficients{}, agent::RuleSet::Conserving);
  const std::size_t entry = grid.index(5, 9, 0);  // top row, downwards
  model.solve({{entry, agent::direction(1, false), 2.0}});
  const auto& d = model.diagnostics();
  const double accounted = d.rigid_reaction + d.passed_out + d.dropped + d.lost;
  std::printf("agent: %zu agents reached; reaction %.6f N + passed out %.6f N + dropped %.6f N + lost %.6f N = %.6f N of %.6f N\n",
              d.agents_generated, d.rigid_reaction, d.passed_out, d.dropped, d.lost, accounted, d.applied);
  return std::abs(accounted - d.applied) < 1e-9 * d.applied && std::abs(d.lost) < 1e-9 * d.applied &&
         d.rigid_reaction > 0.5 * d.applied;
}

bool pbd_rod() {
  const int n = 10;
  const double l = 1.0 / n;
  // A pinned ghost node before x = 0 clamps the slope.
  const auto mesh = pbd::Mesh::polyline(pbd::Vec3(-l, 0, 0), pbd::Vec3(1, 0, 0), n + 1);
  pbd::ModelOptions options;
  options.masses = pbd::ModelOptions::Masses::Lumped;
  options.bending_stiffness = 1.0;
  options.planar_axis = pbd::Vec3::UnitZ();
  auto model = pbd::build_model(mesh, {0, 1}, options);
  pbd::Solver solver(model);
  pbd::StepSettings step;
  step.dt = 0.01;
  step.substeps = 5;
  step.iterations = 4;
  step.gravity = pbd::Vec3(0, -0.008, 0);
  step.damping = 2 * 3.516;  // near-critical for the first mode
  for (int frame = 0; frame < 400; ++frame) solver.step(step);
  const double tip = -model.particles.x.back()[1];
  std::printf("pbd: tip deflection %.6e m (Euler-Bernoulli 1.0e-03 m, 10-segment chain 1.00998e-03 m)\n", tip);
  return std::abs(tip - 1.00998e-3) < 1e-6;
}

}  // namespace

int main() {
  const bool agent_ok = agent_plate();
  const bool pbd_ok = pbd_rod();
  std::printf("%s\n", agent_ok && pbd_ok ? "embed: both checks passed" : "embed: a check FAILED");
  return agent_ok && pbd_ok ? 0 : 1;
}
