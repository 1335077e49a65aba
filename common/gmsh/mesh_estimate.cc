// How many elements a loaded .geo will mesh into, estimated before gmsh meshes it, so that a
// problem too large for the memory limit is refused up front instead of exhausting the machine.
#include "gmsh_write.h"
#include "mesh_checks.h"

#include <workbench/memory_limit.h>

#include <gmsh.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace workbench {

namespace fs = std::filesystem;

double bytes_per_element(int dim) {
  // `workbench fem` on the seed plate: 305 MB at 4e4 Q1 cells, 648 MB at 1.6e5 (2.9 kB per cell);
  // a 3D cell carries about four times the unknowns and matrix entries of a 2D one.
  static const double table[] = {256, 1024, 4096, 16384};
  return table[std::clamp(dim, 0, 3)];
}

namespace {

constexpr double kNoSize = 1e21;  // gmsh writes 1e22 for a point without a mesh size

/// Mesh sizes of the points and divisions of the transfinite curves, from gmsh's unrolled .geo
/// (the only place gmsh 4.8's API shows them).
struct GeoSizes {
  std::map<int, double> point_size;
  std::map<int, double> curve_points;  // transfinite: number of nodes on the curve
};

double evaluate(const std::string& text, const std::map<std::string, double>& names) {
  auto it = names.find(text);
  if (it != names.end()) return it->second;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' ? v : kNoSize;
}

std::vector<int> tag_list(const std::string& text) {
  std::vector<int> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    char* end = nullptr;
    const long v = std::strtol(text.c_str() + pos, &end, 10);
    if (end == text.c_str() + pos) {
      ++pos;
      continue;
    }
    out.push_back(int(std::labs(v)));
    pos = std::size_t(end - text.c_str());
  }
  return out;
}

GeoSizes read_unrolled(const fs::path& file) {
  GeoSizes out;
  std::map<std::string, double> names;
  std::ifstream in(file);
  const std::regex assign(R"(^(\w+) = ([^;]+);)");
  const std::regex point(R"(^Point\((\d+)\) = \{([^}]*)\};)");
  const std::regex transfinite(R"(^Transfinite (?:Line|Curve) \{([^}]*)\} = ([^ ;]+))");
  std::string line;
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_search(line, m, point)) {
      const std::string coords = m[2];
      const auto comma = coords.rfind(',');
      std::string size = comma == std::string::npos ? "" : coords.substr(comma + 1);
      size.erase(0, size.find_first_not_of(' '));
      out.point_size[std::stoi(m[1])] = comma == std::string::npos ? kNoSize : evaluate(size, names);
    } else if (std::regex_search(line, m, transfinite)) {
      const double n = evaluate(m[2], names);
      for (int tag : tag_list(m[1])) out.curve_points[tag] = n;
    } else if (std::regex_search(line, m, assign)) {
      names[m[1]] = evaluate(m[2], names);
    }
  }
  return out;
}

/// A folder of our own for the unrolled .geo, removed when done.
struct ScratchFile {
  fs::path dir, file;
  ScratchFile() {
    std::string pattern = (fs::temp_directory_path() / "workbench-geo-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder in " + fs::temp_directory_path().string());
    dir = pattern;
    file = dir / "model.geo_unrolled";
  }
  ~ScratchFile() {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
};

struct Box {
  double d[3] = {0, 0, 0};
  double diagonal() const { return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]); }
};

Box box_of(int dim, int tag) {
  double x0, y0, z0, x1, y1, z1;
  gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
  Box b;
  b.d[0] = std::max(0.0, x1 - x0), b.d[1] = std::max(0.0, y1 - y0), b.d[2] = std::max(0.0, z1 - z0);
  return b;
}

std::vector<int> boundary(int dim, int tag) {
  gmsh::vectorpair out;
  gmsh::model::getBoundary({{dim, tag}}, out, false, false, false);
  std::vector<int> tags;
  for (const auto& [d, t] : out) tags.push_back(std::abs(t));
  return tags;
}

}  // namespace

void check_geo_mesh_size(const fs::path& file) {
  ScratchFile scratch;
  gmsh_write_checked(scratch.file);  // a short file would count too few elements
  const GeoSizes sizes = read_unrolled(scratch.file);

  double factor = 1, size_min = 0, size_max = 1e22;
  gmsh::option::getNumber("Mesh.MeshSizeFactor", factor);
  gmsh::option::getNumber("Mesh.MeshSizeMin", size_min);
  gmsh::option::getNumber("Mesh.MeshSizeMax", size_max);
  double x0, y0, z0, x1, y1, z1;
  gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
  const double model_size = std::hypot(x1 - x0, y1 - y0, z1 - z0);

  // Curves: a transfinite curve has its divisions; another, its length over its points' size.
  std::map<int, std::pair<double, double>> curve;  // tag -> (segments, length)
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities, 1);
  for (const auto& [d, tag] : entities) {
    const double length = box_of(1, tag).diagonal();
    double segments;
    if (auto it = sizes.curve_points.find(tag); it != sizes.curve_points.end()) {
      segments = it->second - 1;
    } else {
      double size = kNoSize;
      for (int p : boundary(1, tag))
        if (auto s = sizes.point_size.find(p); s != sizes.point_size.end()) size = std::min(size, s->second);
      if (size >= kNoSize) size = model_size;
      size = std::clamp(size * factor, size_min, size_max);
      segments = size > 0 ? std::ceil(length / size) : INFINITY;
    }
    if (!(segments >= 1)) segments = std::isnan(segments) ? INFINITY : 1;
    curve[tag] = {segments, length};
  }

  // gmsh keeps a division count in an int: a count beyond it wraps to a few, and the transfinite
  // surface then throws from inside an OpenMP region, which ends the process. A curve whose
  // spacing is a million times its neighbours' is such a wrapped count.
  double finest = INFINITY, coarsest = 0;
  int coarse_curve = 0;
  for (const auto& [tag, c] : curve)
    if (sizes.curve_points.count(tag) && c.second > 0) {
      const double spacing = c.second / c.first;
      finest = std::min(finest, spacing);
      if (spacing > coarsest) coarsest = spacing, coarse_curve = tag;
    }
  if (coarsest > 1e6 * finest) {
    char what[200];
    std::snprintf(what, sizeof what, "curve %d would need about %.2g transfinite divisions", coarse_curve,
                  curve[coarse_curve].second / finest);
    throw std::runtime_error(file.string() + ": " + what + ", beyond what gmsh can count (check the mesh parameters)");
  }

  // Surfaces and volumes: their extent over the mean segment length of their curves (triangles,
  // tetrahedra: about 2 A / l^2 and 6 V / l^3; quadrangles and hexahedra fewer).
  auto edge_length = [&](const std::vector<int>& curves) {
    double segments = 0, length = 0;
    for (int c : curves)
      if (auto it = curve.find(c); it != curve.end()) segments += it->second.first, length += it->second.second;
    return segments > 0 ? length / segments : model_size;
  };
  std::vector<double> count(4, 0.0);
  for (const auto& [tag, c] : curve) count[1] += c.first;
  gmsh::model::getEntities(entities, 2);
  for (const auto& [d, tag] : entities) {
    const Box b = box_of(2, tag);
    const double area = std::sqrt(b.d[0] * b.d[0] * b.d[1] * b.d[1] + b.d[1] * b.d[1] * b.d[2] * b.d[2] +
                                  b.d[2] * b.d[2] * b.d[0] * b.d[0]);
    const double l = edge_length(boundary(2, tag));
    count[2] += l > 0 ? 2 * area / (l * l) : INFINITY;
  }
  gmsh::model::getEntities(entities, 3);
  for (const auto& [d, tag] : entities) {
    const Box b = box_of(3, tag);
    std::vector<int> curves;
    for (int s : boundary(3, tag))
      for (int c : boundary(2, s)) curves.push_back(c);
    const double l = edge_length(curves);
    count[3] += l > 0 ? 6 * b.d[0] * b.d[1] * b.d[2] / (l * l * l) : INFINITY;
  }
  double bytes = 0, total = 0;
  for (int dim = 1; dim <= 3; ++dim) bytes += count[dim] * bytes_per_element(dim), total += count[dim];
  char size[160];
  std::snprintf(size, sizeof size, "about %.2g elements (estimated from the .geo's curve divisions and mesh sizes)", total);
  check_memory_estimate(file.string(), size, bytes);
}

}  // namespace workbench
