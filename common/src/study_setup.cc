// The case-file sections every model shares: mesh, material, boundary, loads, steps.
#include <workbench/study_setup.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace workbench {

namespace {

/// A [[load]]'s direction as (axis, signed share of the force) per axis it acts along: a name
/// ("-y": one axis, share -1) or a vector ([x, y] or [x, y, z], normalised here; zero components
/// dropped).
std::vector<std::pair<int, double>> load_direction(const CaseTable& l) {
  if (!l.is_array("direction")) {
    const std::string dir = l.text("direction", "-y", {"-x", "+x", "-y", "+y", "-z", "+z"});
    return {{dir[1] - 'x', dir[0] == '-' ? -1.0 : 1.0}};
  }
  const auto v = l.numbers("direction", std::nullopt);
  if (v.size() < 2 || v.size() > 3)
    l.fail("direction", "a vector has 2 or 3 components ([x, y] or [x, y, z]), not " + std::to_string(v.size()));
  double norm = 0;
  for (double c : v) norm = std::hypot(norm, c);
  if (!(norm > 0)) l.fail("direction", "the zero vector has no direction");
  std::vector<std::pair<int, double>> out;
  for (std::size_t a = 0; a < v.size(); ++a)
    if (v[a] != 0) out.emplace_back(int(a), v[a] / norm);
  return out;
}

}  // namespace

StudySetup read_study_setup(const CaseTable& root) {
  StudySetup s;
  s.title = root.text("title", "");
  const auto mesh = root.table("mesh");
  s.mesh_file = mesh.path("file", std::nullopt);
  s.mesh_parameters = mesh.number_map("parameters");
  std::vector<std::string> unit_names;
  for (const auto& [name, metres] : mesh_units()) unit_names.push_back(name);
  const std::string unit = mesh.text("unit", "m", unit_names);
  for (const auto& [name, metres] : mesh_units())
    if (name == unit) s.mesh_unit = metres;
  s.agent_size = mesh.number("agent_size", 0.0, Range::positive());
  const auto material = root.table("material");
  s.young = material.number("young", 206e9, Range::positive());
  s.poisson = material.number("poisson", 0.3, Range::open(-1.0, 0.5));
  s.thickness = material.number("thickness", 1.0, Range::positive());
  const auto boundary = root.table("boundary");
  s.rigid_groups = boundary.texts("rigid", std::nullopt);
  s.roller_groups = boundary.texts("rollers", std::vector<std::string>{});
  const auto loads = root.tables("load");
  for (std::size_t i = 0; i < loads.size(); ++i) {
    const auto& l = loads[i];
    const std::string group = l.text("group", std::nullopt);
    if (std::find(s.rigid_groups.begin(), s.rigid_groups.end(), group) != s.rigid_groups.end())
      l.fail("group", "group '" + group + "' is clamped (boundary.rigid): a load on it would carry nothing");
    const double force = l.number("force", std::nullopt, Range::positive());
    for (const auto& [axis, share] : load_direction(l)) s.loads.push_back({group, axis, share < 0 ? -1 : 1, force * std::abs(share), i});
  }
  s.steps = root.table("steps").integer("count", 1, 1, 10000);
  return s;
}

const std::vector<std::pair<std::string, double>>& mesh_units() {
  static const std::vector<std::pair<std::string, double>> units = {{"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}};
  return units;
}

std::string body_size_warning(const std::filesystem::path& mesh, double unit_metres, double longest) {
  if (longest <= kLargestBody && longest >= kSmallestBody) return "";
  std::string unit = "m";
  for (const auto& [name, metres] : mesh_units())
    if (metres == unit_metres) unit = name;
  std::ostringstream s;
  s << mesh.string() << ": the body is " << longest << " m long (its longest side, read with mesh.unit = \""
    << unit << "\"): " << (longest > kLargestBody ? "over " : "under ") << (longest > kLargestBody ? "20 m" : "0.1 mm")
    << "; if the file is in other units, set mesh.unit (\"mm\", \"cm\" or \"m\")";
  return s.str();
}

void check_groups_exist(const CaseFile& file, const StudySetup& setup, const std::vector<std::string>& mesh_groups) {
  std::string have;
  for (const auto& g : mesh_groups) have += (have.empty() ? "" : ", ") + g;
  auto check = [&](const std::string& key, const std::string& group) {
    if (std::find(mesh_groups.begin(), mesh_groups.end(), group) == mesh_groups.end())
      throw Error(file.path().string() + ": " + key + ": group '" + group + "' is not a physical group of " +
                  setup.mesh_file.string() + " (it has: " + (have.empty() ? "none" : have) + ")");
  };
  for (const auto& g : setup.rigid_groups) check("boundary.rigid", g);
  for (const auto& g : setup.roller_groups) check("boundary.rollers", g);
  for (std::size_t i = 0; i < setup.loads.size(); ++i) check(setup.loads[i].key() + ".group", setup.loads[i].group);
}

}  // namespace workbench
