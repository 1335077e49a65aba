// The [compare] section: the options a comparison reads from its case file.
#include <schema/compare_options.h>

#include <workbench/error.h>

#include <cmath>
#include <optional>

namespace schema {

namespace fs = std::filesystem;

std::string ReferenceOptions::describe() const {
  const std::string on = mesh.empty() ? "the agents' mesh" : "the true geometry " + mesh.filename().string();
  return "FEM Q" + std::to_string(degree) +
         (refine == 0 ? " on " + on : ", " + on + " refined " + std::to_string(refine) + (refine == 1 ? " time" : " times"));
}

CompareOptions read_compare_options(const workbench::CaseTable& root) {
  const auto t = root.table("compare");
  CompareOptions o;
  o.model = t.text("model", o.model, {"agent", "pbd"});
  if (o.model == "agent") {  // the PBD comparison has no sample lines nor ratios: its case rejects these keys
    o.depths = t.numbers("depths", o.depths, workbench::Range::open(0.0, 1.0));
    o.mask = t.number("mask", o.mask, workbench::Range{0.0, 1.0, false, true});
    const auto r = t.table("reference");
    o.reference.degree = r.integer("degree", o.reference.degree, 1, 2);
    if (r.has("refine")) o.reference.refine = r.integer("refine", std::nullopt, 0, ReferenceOptions::kMaxRefine);
    o.reference.tolerance = r.number("tolerance", o.reference.tolerance, workbench::Range{0.0, 1.0, true, false});
    if (r.has("tolerance") && (o.reference.refine >= 0 || o.reference.degree == 1))
      r.fail("tolerance", std::string("the reference converges to a tolerance only without ") +
                              (o.reference.refine >= 0 ? "refine (refine fixes the level)" : "degree = 1 (Q1 stays on its mesh)"));
    o.reference.algebraic_share =
        r.number("algebraic_share", o.reference.algebraic_share, workbench::Range{0.0, 1.0, false, true});
    if (r.has("mesh")) {
      o.reference.mesh = r.path("mesh", std::nullopt);
      if (!fs::is_regular_file(o.reference.mesh)) r.fail("mesh", o.reference.mesh.string() + ": no such mesh file");
    }
    t.refuse_renamed("far_distance_mm", "far_distance", "in metres: far_distance_mm / 1000");
    o.far_distance = t.number("far_distance", o.far_distance, workbench::Range::non_negative());
    o.min_reaction_share = t.number("min_reaction_share", o.min_reaction_share, workbench::Range::closed(0.0, 1.0));
    for (const auto& line : t.tables("line")) {
      std::array<Eigen::Vector3d, 2> ends{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
      const char* keys[] = {"from", "to"};
      for (int e = 0; e < 2; ++e) {
        const auto p = line.numbers(keys[e], std::nullopt);
        if (p.size() < 2 || p.size() > 3) line.fail(keys[e], "a point is 2 or 3 coordinates [m]");
        for (std::size_t a = 0; a < p.size(); ++a) ends[e][a] = p[a];
      }
      if ((ends[1] - ends[0]).norm() == 0) line.fail("to", "the line's ends are the same point");
      o.lines.push_back(ends);
    }
  }
  o.gate = t.number_map("gate");
  for (const auto& [name, limit] : o.gate)
    if (!(limit >= 0) || !std::isfinite(limit)) t.fail("gate." + name, "a limit must be a finite number >= 0");
  o.better_than_zero = t.texts("better_than_zero", std::vector<std::string>{});
  o.figures = t.flag("figures", true);
  o.figure_formats = t.texts("figure_formats", o.figure_formats);
  if (o.figure_formats.empty()) t.fail("figure_formats", "name at least one format (\"png\", \"pdf\")");
  for (const auto& f : o.figure_formats)
    if (f != "png" && f != "pdf") t.fail("figure_formats", "unknown format \"" + f + "\" (\"png\" or \"pdf\")");
  return o;
}

}  // namespace schema
