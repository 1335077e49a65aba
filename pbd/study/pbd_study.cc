// The PBD model as a workbench study: case reading, mesh and model, frames, output files.
#include "pbd_study.h"

#include <workbench/child_process.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>

namespace pbd_study {

namespace fs = std::filesystem;
using pbd::Vec3;
using workbench::Error;
using workbench::Range;

namespace {

Vec3 read_vector(const workbench::CaseTable& t, const std::string& key, const Vec3& fallback) {
  const auto v = t.numbers(key, std::vector<double>{fallback[0], fallback[1], fallback[2]});
  if (v.size() != 3) t.fail(key, "needs 3 numbers [x, y, z], got " + std::to_string(v.size()));
  return Vec3(v[0], v[1], v[2]);
}

using workbench::open_csv;

std::string frame_name(int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%05d", k);
  return buf;
}

}  // namespace

PbdCase read_pbd_case(const workbench::CaseFile& file) {
  PbdCase c;
  c.case_file = file.path();
  const auto root = file.root();
  c.title = root.text("title", "");
  const auto t = root.table("pbd");
  c.mesh_file = t.path("mesh", std::nullopt);
  c.mesh_parameters = t.number_map("mesh_parameters");
  c.pinned_groups = t.texts("pinned", std::vector<std::string>{});
  c.frames = t.integer("frames", 100, 1, 1000000);
  c.step.dt = t.number("time_step", 0.01, Range::positive());
  c.step.substeps = t.has("substeps") ? t.integer("substeps", std::nullopt, 1, 1000000) : 0;
  c.step.iterations = t.integer("iterations", 1, 1, 100000);
  c.step.gravity = read_vector(t, "gravity", Vec3(0, -9.81, 0));
  c.step.node_force = read_vector(t, "node_force", Vec3::Zero());
  c.step.damping = t.number("damping", 0.0, Range::non_negative());
  c.step.threads = t.integer("threads", 1, 1, 256);
  c.output_every = t.integer("output_every", 1, 1, 1000000);
  const std::string masses = t.text("masses", "seed", {"seed", "lumped"});
  c.model.masses = masses == "seed" ? pbd::ModelOptions::Masses::Seed : pbd::ModelOptions::Masses::Lumped;
  c.model.total_mass = t.number("total_mass", 1.0, Range::positive());
  const bool has_E = t.has("young"), has_I = t.has("second_moment"), has_EI = t.has("bending_stiffness");
  const bool has_alpha = t.has("bending_compliance");
  if (has_E != has_I) t.fail(has_E ? "second_moment" : "young", "young and second_moment go together (E I = young * second_moment)");
  if ((has_E && has_EI) || ((has_E || has_EI) && has_alpha))
    t.fail(has_alpha ? "bending_compliance" : "bending_stiffness",
           "give one of bending_compliance, bending_stiffness, or young with second_moment");
  c.model.bending_compliance = t.number("bending_compliance", 0.0, Range::non_negative());
  if (has_E)
    c.model.bending_stiffness = t.number("young", std::nullopt, Range::positive()) *
                                t.number("second_moment", std::nullopt, Range::positive());
  else
    c.model.bending_stiffness = t.number("bending_stiffness", 0.0, Range::non_negative());
  c.model.stretch = t.flag("stretch", true);
  c.model.stretch_compliance = t.number("stretch_compliance", 0.0, Range::non_negative());
  c.angle_form = t.text("angle_form", "auto", {"auto", "signed", "unsigned"});
  c.animation_format = t.text("animation", "mp4", {"mp4", "gif"});
  c.fps = t.integer("fps", 25, 1, 240);
  return c;
}

PbdStudy load_pbd_study(const workbench::CaseFile& file, PbdCase setup) {
  PbdStudy s;
  s.setup = std::move(setup);
  s.mesh = pbd_io::read_mesh(s.setup.mesh_file, s.setup.mesh_parameters);
  s.pinned = pbd_io::group_nodes(s.mesh, s.setup.mesh_file, s.setup.pinned_groups);
  const auto t = file.root().table("pbd");
  const bool planar = pbd::lies_in_xy_plane(s.mesh.mesh.points);
  const bool in_plane_load = s.setup.step.gravity[2] == 0 && s.setup.step.node_force[2] == 0;
  if (s.setup.angle_form == "signed" && !planar)
    t.fail("angle_form", "'signed' needs a mesh in the x-y plane (" + s.setup.mesh_file.string() + " is not)");
  if (s.setup.angle_form == "signed" && !in_plane_load)
    t.fail("angle_form", "'signed' needs gravity and node_force in the x-y plane (z component 0)");
  const bool use_signed = s.setup.angle_form == "signed" || (s.setup.angle_form == "auto" && planar && in_plane_load);
  s.setup.model.planar_axis = use_signed ? Vec3(Vec3::UnitZ()) : Vec3(Vec3::Zero());
  try {
    s.model = pbd::build_model(s.mesh.mesh, s.pinned, s.setup.model);
  } catch (const std::invalid_argument& e) {
    throw Error(s.setup.mesh_file.string() + ": " + e.what());
  }
  if (s.setup.step.substeps == 0) {
    s.setup.step.substeps = pbd::substeps_for_accuracy(s.model, s.setup.step.dt);
    s.setup.substeps_chosen = true;
  }
  return s;
}

workbench::OutputMesh output_mesh(const pbd::Mesh& mesh, const std::vector<Vec3>& x) {
  workbench::OutputMesh out;
  out.points.reserve(3 * x.size());
  for (const auto& p : x) out.points.insert(out.points.end(), {p[0], p[1], p[2]});
  out.cell_types.assign(mesh.cell_types.begin(), mesh.cell_types.end());
  out.connectivity.assign(mesh.cell_nodes.begin(), mesh.cell_nodes.end());
  out.offsets.assign(mesh.cell_offsets.begin() + 1, mesh.cell_offsets.end());
  return out;
}

std::vector<int> chain_order(const pbd::Mesh& mesh, const std::vector<int>& pinned) {
  const std::size_t n = mesh.points.size();
  for (int t : mesh.cell_types)
    if (t != pbd::kLine) return {};
  const auto nb = pbd::neighbour_sets(n, pbd::mesh_edges(mesh));
  std::vector<int> ends;
  for (std::size_t i = 0; i < n; ++i) {
    if (nb[i].size() > 2 || nb[i].empty()) return {};
    if (nb[i].size() == 1) ends.push_back(int(i));
  }
  if (ends.size() != 2) return {};
  int start = ends[0];
  const auto lex = [&](int a, int b) {
    const auto &p = mesh.points[a], &q = mesh.points[b];
    return std::tie(p[0], p[1], p[2]) < std::tie(q[0], q[1], q[2]);
  };
  // Walk from the lexicographically smaller end; reversed below when the pinned nodes lie nearer
  // the other end, so that the order starts at the clamped end.
  if (lex(ends[1], ends[0])) start = ends[1];
  std::vector<int> order{start};
  int prev = -1, cur = start;
  while (order.size() < n) {
    int next = -1;
    for (int j : nb[cur])
      if (j != prev) next = j;
    if (next < 0) return {};
    order.push_back(next);
    prev = cur;
    cur = next;
  }
  if (!pinned.empty()) {
    std::vector<char> is_pinned(n, 0);
    for (int p : pinned) is_pinned[p] = 1;
    std::size_t first = n, last = n;
    for (std::size_t k = 0; k < n; ++k)
      if (is_pinned[order[k]]) {
        if (first == n) first = k;
        last = k;
      }
    if (first != n && n - 1 - last < first) std::reverse(order.begin(), order.end());
  }
  return order;
}

Centreline centreline(const pbd::Mesh& mesh, const std::vector<int>& pinned) {
  Centreline c;
  c.nodes = chain_order(mesh, pinned);
  const auto& chain = c.nodes;
  if (chain.empty()) return c;
  const std::size_t n = mesh.points.size();
  std::vector<char> is_pinned(n, 0);
  for (int p : pinned) is_pinned[p] = 1;
  std::size_t origin = 0;
  while (origin + 1 < chain.size() && is_pinned[chain[origin]] && is_pinned[chain[origin + 1]]) ++origin;
  std::vector<double> arc(chain.size(), 0.0);
  for (std::size_t k = 1; k < chain.size(); ++k)
    arc[k] = arc[k - 1] + (mesh.points[chain[k]] - mesh.points[chain[k - 1]]).norm();
  c.s.resize(chain.size());
  for (std::size_t k = 0; k < chain.size(); ++k) c.s[k] = arc[k] - arc[origin];
  return c;
}

void write_render_cells(const fs::path& dir, const workbench::OutputMesh& mesh) {
  auto out = open_csv(dir / "cells.csv");
  out << "type,nodes\n";
  long long b = 0;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    out << mesh.cell_types[c];
    for (long long k = b; k < mesh.offsets[c]; ++k) out << ',' << mesh.connectivity[k];
    out << '\n';
    b = mesh.offsets[c];
  }
  out.close();
}

void write_render_frame(const fs::path& file, const std::vector<double>& points, double time,
                        const std::string& field_name, const std::vector<double>& field) {
  auto out = open_csv(file);
  out << "# time=" << time << "\n";
  out << "x,y,z," << field_name << "\n";
  for (std::size_t i = 0; i < points.size() / 3; ++i)
    out << points[3 * i] << ',' << points[3 * i + 1] << ',' << points[3 * i + 2] << ',' << field[i] << '\n';
  out.close();
}

void render_animation(const fs::path& frames_dir, const fs::path& output, int fps, const std::string& field,
                      const std::string& title) {
  std::vector<std::string> args{frames_dir.string(), "-o", output.string(), "--fps", std::to_string(fps), "--field", field};
  if (!title.empty()) args.insert(args.end(), {"--title", title});
  workbench::run_python_script("scripts/render_frames.py", args, frames_dir / "render.log",
                               output.string() + ": rendering the animation");
}

void step_frames(PbdStudy& study, pbd::Solver& solver, const std::function<void(int)>& frame, std::ostream& log) {
  const auto& setup = study.setup;
  auto checked_frame = [&](int f) {
    for (const auto& p : study.model.particles.x)
      if (!p.allFinite())
        throw Error(setup.case_file.string() + ": pbd.gravity, pbd.node_force, pbd.time_step: the simulation diverged "
                    "(a non-finite position at frame " + std::to_string(f) + " of " + std::to_string(setup.frames) +
                    "): the loads or the time step are too large for " + std::to_string(setup.step.substeps) +
                    " substeps per frame");
    frame(f);
  };
  checked_frame(0);
  const int report = std::max(1, setup.frames / 10);
  for (int f = 1; f <= setup.frames; ++f) {
    solver.step(setup.step);  // seed steps 3-5: predict, project, corrected positions start the next step
    if (f % setup.output_every == 0 || f == setup.frames) checked_frame(f);
    if (f % report == 0 || f == setup.frames)
      log << "pbd: frame " << f << "/" << setup.frames << ", t = " << f * setup.step.dt
          << " s, kinetic energy " << study.model.particles.kinetic_energy() << " J\n";
  }
}

void write_pbd_outputs(PbdStudy& study, const fs::path& dir, bool animate, std::ostream& log) {
  auto& model = study.model;
  const auto& mesh = study.mesh.mesh;
  const auto& setup = study.setup;
  const std::size_t n = mesh.points.size();
  pbd::Solver solver(model);
  fs::create_directories(dir / "frames");
  const fs::path render_dir = dir / "render";
  if (animate) fs::create_directories(render_dir);

  log << "pbd: " << n << " nodes, " << model.distances.size() << " distance and " << model.angles.size()
      << " angle constraints (" << model.raw_triple_count << " chains before deduplication), "
      << (model.planar ? "signed angles about z" : "unsigned angles") << ", " << study.pinned.size()
      << " pinned nodes\n";
  const std::string substeps_text =
      std::to_string(setup.step.substeps) + " substeps x " + std::to_string(setup.step.iterations) + " iterations per frame" +
      (setup.substeps_chosen ? " (substeps chosen for the stiffest bending constraint, docs/pbd-model.md)" : "");
  log << "pbd: " << substeps_text << "\n";

  std::vector<double> pinned_field(n, 0.0);
  for (int p : study.pinned) pinned_field[p] = 1.0;
  std::vector<std::pair<double, std::string>> series;
  auto diagnostics = open_csv(dir / "diagnostics.csv");
  diagnostics << "frame,time [s],kinetic_energy [J],max_angle_residual [rad],max_stretch [-],max_displacement [m]\n";

  auto write_frame = [&](int frame) {
    const double time = frame * setup.step.dt;
    const auto& x = model.particles.x;
    const auto out_mesh = output_mesh(mesh, x);
    workbench::Field u{"displacement [m]", 3, {}, {"x", "y", "z"}, {}};
    workbench::Field v{"velocity [m/s]", 3, {}, {"x", "y", "z"}, {}};
    workbench::Field pin{"pinned [-]", 1, pinned_field, {}, {}};
    workbench::Field bend{"bend_angle [rad]", 1, std::vector<double>(n, 0.0), {}, {}};
    std::vector<double> umag(n);
    double umax = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 d = x[i] - mesh.points[i];
      umag[i] = d.norm();
      umax = std::max(umax, umag[i]);
      u.values.insert(u.values.end(), {d[0], d[1], d[2]});
      const Vec3& w = model.particles.v[i];
      v.values.insert(v.values.end(), {w[0], w[1], w[2]});
    }
    for (const auto& a : model.angles) {
      const auto g = pbd::angle_constraint_gradient(x[a.best], x[a.k], x[a.i], std::atan2(a.rest_sin, a.rest_cos),
                                                    model.axis_ptr());
      bend.values[a.i] += std::abs(g.C);
    }
    const std::string name = frame_name(frame);
    // Frame 0 first checks that all frames fit: 0, every output_every-th and the last.
    const std::size_t frames_out = 1 + setup.frames / setup.output_every + (setup.frames % setup.output_every != 0);
    workbench::write_vtu(dir / "frames" / (name + ".vtu"), out_mesh, {u, v, pin, bend}, {}, frame == 0 ? frames_out : 1);
    series.emplace_back(time, "frames/" + name + ".vtu");
    if (animate) {
      if (frame == 0) write_render_cells(render_dir, out_mesh);
      write_render_frame(render_dir / (name + ".csv"), out_mesh.points, time, "displacement magnitude [m]", umag);
    }
    const auto r = solver.residuals();
    diagnostics << frame << ',' << time << ',' << model.particles.kinetic_energy() << ',' << r.angle << ','
                << r.distance << ',' << umax << '\n';
  };

  step_frames(study, solver, write_frame, log);
  workbench::write_pvd(dir / "pbd.pvd", series);
  diagnostics.close();

  const auto& x = model.particles.x;
  {
    const auto r = solver.residuals();
    std::ostringstream warning;
    if (r.exceeds_tolerance())
      warning << "the final constraint residuals exceed their tolerances (stretch of the inextensible edges "
              << r.inextensible_stretch << " > " << pbd::Residuals::kStretchTolerance << " or rigid-angle violation "
              << r.rigid_angle << " rad > " << pbd::Residuals::kAngleTolerance
              << " rad): the result is not converged; raise pbd.substeps or pbd.iterations";
    auto out = open_csv(dir / "summary.txt");
    out << "pbd: " << substeps_text << "\n"
        << "final residuals: inextensible stretch " << r.inextensible_stretch << " (tolerance "
        << pbd::Residuals::kStretchTolerance << "), rigid angle " << r.rigid_angle << " rad (tolerance "
        << pbd::Residuals::kAngleTolerance << " rad); all edges: stretch " << r.distance << ", largest bend " << r.angle
        << " rad\n";
    if (!warning.str().empty()) {
      out << "warning: " << warning.str() << "\n";
      log << "pbd: warning: " << warning.str() << "\n";
    }
    out.close();
  }
  {
    auto out = open_csv(dir / "nodes.csv");
    out << "node,file_node,x0 [m],y0 [m],z0 [m],x [m],y [m],z [m],u_x [m],u_y [m],u_z [m],pinned\n";
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 &p = mesh.points[i], &q = x[i];
      out << i << ',' << study.mesh.node_names[i] << ',' << p[0] << ',' << p[1] << ',' << p[2] << ',' << q[0] << ','
          << q[1] << ',' << q[2] << ',' << q[0] - p[0] << ',' << q[1] - p[1] << ',' << q[2] - p[2] << ','
          << int(pinned_field[i]) << '\n';
    }
    out.close();
  }
  const auto line = centreline(mesh, study.pinned);
  const auto& chain = line.nodes;
  if (!chain.empty()) {
    auto out = open_csv(dir / "centreline.csv");
    out << "s [m],x0 [m],y0 [m],z0 [m],x [m],y [m],z [m],u_x [m],u_y [m],u_z [m]\n";
    for (std::size_t k = 0; k < chain.size(); ++k) {
      const Vec3 &p = mesh.points[chain[k]], &q = x[chain[k]];
      out << line.s[k] << ',' << p[0] << ',' << p[1] << ',' << p[2] << ',' << q[0] << ',' << q[1] << ',' << q[2] << ','
          << q[0] - p[0] << ',' << q[1] - p[1] << ',' << q[2] - p[2] << '\n';
    }
    out.close();
    log << "pbd: centreline.csv: " << chain.size() << " nodes, end displacement ("
        << (x[chain.back()] - mesh.points[chain.back()]).transpose() << ") m\n";
  }
  if (animate) {
    const fs::path file = dir / ("animation." + setup.animation_format);
    log << "pbd: rendering " << file.filename().string() << "\n";
    render_animation(render_dir, file, setup.fps, "displacement magnitude [m]", setup.title);
  }
}

}  // namespace pbd_study
