// The process's one gmsh session: every .geo/.msh load starts from a fresh gmsh, after the
// checks of mesh_checks.h (gmsh aborts or crashes on some bad input instead of reporting it). A
// .geo is parsed and meshed in a child process (geo_mesher_child.cc), whose crash is one error.
#include "gmsh_session.h"

#include "gmsh_internal.h"
#include "mesh_checks.h"

#include <gmsh.h>

#include <workbench/child_process.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace workbench {

namespace gmsh_detail {

namespace {

bool initialised = false;

}  // namespace

void fresh_gmsh() {
  if (initialised) {
    gmsh::logger::stop();
    gmsh::finalize();
  }
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::clear();
  gmsh::onelab::clear();
  initialised = true;
}

std::string last_error() {
  std::string error;
  gmsh::logger::getLastError(error);
  return error.empty() ? "gmsh failed" : error;
}

void check_load_request(const std::filesystem::path& file, const std::map<std::string, double>& parameters) {
  const std::string name = file.string();
  if (!std::filesystem::is_regular_file(file)) throw std::runtime_error(name + ": no such mesh file");
  const std::string ext = file.extension().string();
  if (ext != ".geo" && ext != ".msh") {
    std::string lower = ext;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    const bool cad = lower == ".step" || lower == ".stp" || lower == ".iges" || lower == ".igs" || lower == ".brep";
    throw std::runtime_error(name + ": a mesh must be a gmsh .geo or .msh file" +
                             (cad ? std::string("; a CAD file is read through a .geo that Merges it and names its physical "
                                                "groups (the loads' and supports' faces), e.g. tests/data/step_plate.geo; "
                                                "its unit: [mesh] unit")
                                  : std::string()));
  }
  if (ext == ".msh" && !parameters.empty()) throw std::runtime_error(name + ": mesh parameters ([mesh.parameters], pbd.mesh_parameters) apply to .geo files only: remove them, or name the .geo");
  for (const auto& [key, value] : parameters)
    if (!std::isfinite(value)) throw std::runtime_error(name + ": mesh parameter '" + key + "' is not a finite number");
}

void throw_logged_error(const std::string& name) {
  std::vector<std::string> log;
  gmsh::logger::get(log);
  for (const auto& line : log)
    if (line.rfind("Error", 0) == 0) {
      const auto colon = line.find(':');
      throw LoadError(name + ": " + (colon == std::string::npos ? line : line.substr(colon + 2)));
    }
}

std::vector<std::string> load_here(const std::filesystem::path& file, const std::map<std::string, double>& parameters) {
  const std::string name = file.string();
  const std::string ext = file.extension().string();
  if (ext == ".msh") check_msh_file(file);
  std::vector<std::string> declared;
  try {
    if (ext == ".geo") {
      // The names the .geo declares, read before any is set from outside.
      fresh_gmsh();
      gmsh::open(name);
      std::vector<std::string> names;
      gmsh::onelab::getNames(names);
      for (const auto& n : names)
        if (n.find('/') == std::string::npos) declared.push_back(n);
      for (const auto& [key, value] : parameters)
        if (std::find(declared.begin(), declared.end(), key) == declared.end())
          throw LoadError(name + ": unknown mesh parameter '" + key + "' (the .geo declares none of that name)");
    }
    fresh_gmsh();
    for (const auto& [key, value] : parameters) gmsh::onelab::setNumber(key, {value});
    gmsh::logger::start();
    gmsh::open(name);
    // Error() in a .geo is logged, not always thrown: report the first one.
    throw_logged_error(name);
    if (ext == ".geo") {
      try {
        check_geo_mesh_size(file);
      } catch (const std::runtime_error& e) {  // too large for the memory limit
        throw LoadError(e.what());
      }
      gmsh::model::mesh::generate(gmsh::model::getDimension());
    }
    gmsh::logger::stop();
    std::vector<std::size_t> tags;
    std::vector<double> coords, parametric;
    gmsh::model::mesh::getNodes(tags, coords, parametric);
    for (std::size_t i = 0; i < coords.size(); ++i)
      if (!std::isfinite(coords[i]))
        throw LoadError(name + ": node " + std::to_string(tags[i / 3]) + " has a non-finite coordinate");
  } catch (const LoadError&) {
    throw;
  } catch (...) {
    throw std::runtime_error(name + ": " + last_error());
  }
  return declared;
}

std::string model_counts() {
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric);
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes);
  std::size_t elements = 0;
  for (const auto& t : element_tags) elements += t.size();
  return std::to_string(tags.size()) + " " + std::to_string(elements);
}

}  // namespace gmsh_detail

namespace {

/// Every node of the loaded model times `unit`: the file's coordinates in metres.
void scale_nodes(double unit) {
  if (unit == 1.0) return;
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric, -1, -1, false, false);
  for (std::size_t i = 0; i < tags.size(); ++i)
    gmsh::model::mesh::setNode(tags[i], {unit * coords[3 * i], unit * coords[3 * i + 1], unit * coords[3 * i + 2]}, {});
}

std::vector<std::string> load_unscaled(const std::filesystem::path& file, const std::map<std::string, double>& parameters) {
  gmsh_detail::check_load_request(file, parameters);
  if (file.extension() == ".geo") {
    if (gmsh_detail::geo_mesher_server_running()) return gmsh_detail::load_geo_in_child({}, file, parameters);
    if (const auto mesher = find_beside_program(kGeoMesherPath); !mesher.empty())
      return gmsh_detail::load_geo_in_child(mesher, file, parameters);
  }
  return gmsh_detail::load_here(file, parameters);
}

}  // namespace

std::vector<std::string> gmsh_load(const std::filesystem::path& file, const std::map<std::string, double>& parameters,
                                   double unit) {
  auto declared = load_unscaled(file, parameters);
  scale_nodes(unit);
  return declared;
}

std::map<std::string, std::vector<GroupElement>> gmsh_physical_groups(int dim) {
  std::map<std::string, std::vector<GroupElement>> out;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  for (const auto& [gdim, gtag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(gdim, gtag, name);
    if (name.empty()) name = std::to_string(gtag);
    auto& elements = out[name];
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(gdim, gtag, entities);
    for (int entity : entities) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> tags, nodes;
      gmsh::model::mesh::getElements(types, tags, nodes, gdim, entity);
      for (std::size_t t = 0; t < types.size(); ++t) {
        const std::size_t n = nodes[t].size() / tags[t].size();
        for (std::size_t e = 0; e < tags[t].size(); ++e)
          elements.push_back({types[t], std::vector<std::size_t>(nodes[t].begin() + e * n, nodes[t].begin() + (e + 1) * n)});
      }
    }
  }
  return out;
}

}  // namespace workbench
