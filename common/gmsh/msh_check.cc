// A reader of ASCII MSH 2.2 / 4.1 that checks a file before gmsh loads it (gmsh 4.8 crashes on
// some bad node tags and accepts non-finite coordinates and duplicated cells).
#include "mesh_checks.h"

#include <workbench/memory_limit.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace workbench {

namespace {

struct ElementType {
  int dim, nodes;
};

/// gmsh element types the workbench's readers can meet (lines, triangles, quadrangles,
/// tetrahedra, hexahedra, prisms, pyramids up to second order, points); {-1, 0} for the others.
ElementType element_type(long long type) {
  static const ElementType table[] = {{-1, 0}, {1, 2},  {2, 3},  {2, 4},  {3, 4},  {3, 8},  {3, 6},  {3, 5},
                                      {1, 3},  {2, 6},  {2, 9},  {3, 10}, {3, 27}, {3, 18}, {3, 14}, {0, 1},
                                      {2, 8},  {3, 20}, {3, 15}, {3, 13}};
  if (type < 1 || type >= static_cast<long long>(std::size(table))) return {-1, 0};
  return table[type];
}

constexpr long long kMaxTag = INT_MAX;  // gmsh 4.8 crashes on larger (and on negative) tags

class MshReader {
 public:
  MshReader(const std::filesystem::path& file, std::string text) : name_(file.string()), text_(std::move(text)) {}

  void check() {
    bool have_format = false, have_nodes = false, have_elements = false;
    while (skip_space(), pos_ < text_.size()) {
      const std::string section = token("a section");
      if (section.size() < 2 || section[0] != '$') fail("expected a $Section, found '" + section.substr(0, 40) + "'");
      if (section == "$MeshFormat") {
        read_format();
        have_format = true;
      } else if (!have_format) {
        fail("does not start with $MeshFormat");
      } else if (section == "$Nodes") {
        if (have_nodes) fail("has two $Nodes sections");
        version_ >= 4 ? read_nodes4() : read_nodes2();
        have_nodes = true;
      } else if (section == "$Elements") {
        if (!have_nodes) fail("$Elements comes before $Nodes");
        if (have_elements) fail("has two $Elements sections");
        version_ >= 4 ? read_elements4() : read_elements2();
        have_elements = true;
      } else {
        skip_section(section.substr(1));
        continue;
      }
      expect("$End" + section.substr(1));
    }
    if (!have_nodes || !have_elements) fail("has no $Nodes or no $Elements section");
    check_duplicated_cells();
    std::vector<double> count(4, 0.0);
    for (const auto& c : cells_) count[c.dim] += 1;
    double bytes = 0;
    for (int d = 0; d <= 3; ++d) bytes += count[d] * bytes_per_element(d);
    check_memory_estimate(name_, std::to_string(cells_.size()) + " elements", bytes);
  }

 private:
  struct Cell {
    long long tag;
    int type, dim;
    std::vector<long long> nodes;  // sorted
  };

  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(name_ + ": " + what); }

  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  std::string token(const char* what) {
    skip_space();
    if (pos_ >= text_.size()) fail(std::string("ends early (truncated?) where ") + what + " should be" + in_section());
    const std::size_t b = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return text_.substr(b, pos_ - b);
  }
  std::string in_section() const { return section_.empty() ? "" : " in $" + section_; }
  void expect(const std::string& word) {
    const std::string got = token(word.c_str());
    if (got != word) fail("expected " + word + ", found '" + got.substr(0, 40) + "' (a count does not match the data?)");
  }
  double real(const char* what) {
    const std::string t = token(what);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end) fail(std::string("bad ") + what + " '" + t.substr(0, 40) + "'" + in_section());
    return v;
  }
  long long integer(const char* what, long long lo, long long hi) {
    const std::string t = token(what);
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if (end == t.c_str() || *end || errno == ERANGE || v < lo || v > hi)
      fail(std::string("bad ") + what + " '" + t.substr(0, 40) + "'" + in_section() + " (must be an integer in [" +
           std::to_string(lo) + ", " + std::to_string(hi) + "])");
    return v;
  }
  void skip_section(const std::string& name) {
    const std::string end = "$End" + name;
    const std::size_t at = text_.find(end, pos_);
    if (at == std::string::npos) fail("section $" + name + " has no " + end + " (truncated?)");
    pos_ = at + end.size();
  }

  void read_format() {
    section_ = "MeshFormat";
    const std::string v = token("the version");
    if (v == "4.1") version_ = 4;
    else if (v.rfind("2.", 0) == 0) version_ = 2;
    else fail("MSH version " + v + " is not read (save it as MSH 4.1 or 2.2)");
    if (integer("file type", 0, 1) != 0) fail("is a binary MSH file; save it as ASCII (gmsh option Mesh.Binary = 0)");
    if (integer("data size", 1, 64) != 8) fail("$MeshFormat data size must be 8");
  }

  void add_node(long long tag, double x, double y, double z) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      fail("node " + std::to_string(tag) + " has a non-finite coordinate");
    node_tags_.push_back(tag);
  }
  void finish_nodes() {
    std::sort(node_tags_.begin(), node_tags_.end());
    const auto dup = std::adjacent_find(node_tags_.begin(), node_tags_.end());
    if (dup != node_tags_.end()) fail("node tag " + std::to_string(*dup) + " appears twice");
    section_.clear();
  }

  void read_nodes2() {
    section_ = "Nodes";
    const long long n = integer("the node count", 0, kMaxTag);
    for (long long i = 0; i < n; ++i) {
      const long long tag = integer("node tag", 1, kMaxTag);
      const double x = real("coordinate"), y = real("coordinate"), z = real("coordinate");
      add_node(tag, x, y, z);
    }
    finish_nodes();
  }

  void read_nodes4() {
    section_ = "Nodes";
    const long long blocks = integer("the entity block count", 0, kMaxTag);
    const long long n = integer("the node count", 0, kMaxTag);
    const long long lo = integer("the smallest node tag", 0, kMaxTag), hi = integer("the largest node tag", 0, kMaxTag);
    std::vector<long long> tags;
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = integer("entity dimension", 0, 3);
      integer("entity tag", -kMaxTag, kMaxTag);
      const long long parametric = integer("parametric flag", 0, 1);
      const long long m = integer("the block's node count", 0, n - (long long)node_tags_.size());
      tags.clear();
      for (long long i = 0; i < m; ++i) tags.push_back(integer("node tag", std::max(1LL, lo), hi));
      for (long long i = 0; i < m; ++i) {
        const double x = real("coordinate"), y = real("coordinate"), z = real("coordinate");
        for (long long k = 0; k < (parametric ? dim : 0); ++k) real("parametric coordinate");
        add_node(tags[i], x, y, z);
      }
    }
    if ((long long)node_tags_.size() != n)
      fail("$Nodes declares " + std::to_string(n) + " nodes and holds " + std::to_string(node_tags_.size()));
    finish_nodes();
  }

  void add_cell(long long tag, long long type, const ElementType& t, std::vector<long long> nodes) {
    for (long long v : nodes)
      if (!std::binary_search(node_tags_.begin(), node_tags_.end(), v))
        fail("element " + std::to_string(tag) + " refers to node " + std::to_string(v) + ", which does not exist");
    std::sort(nodes.begin(), nodes.end());
    if (std::adjacent_find(nodes.begin(), nodes.end()) != nodes.end())
      fail("element " + std::to_string(tag) + " repeats a node");
    cells_.push_back({tag, int(type), t.dim, std::move(nodes)});
  }
  ElementType known_type(long long type) {
    const ElementType t = element_type(type);
    if (t.dim < 0) fail("element type " + std::to_string(type) + " is not one the workbench reads");
    return t;
  }

  void read_elements2() {
    section_ = "Elements";
    const long long n = integer("the element count", 0, kMaxTag);
    for (long long e = 0; e < n; ++e) {
      const long long tag = integer("element tag", 1, kMaxTag);
      const long long type = integer("element type", 1, 1000);
      const ElementType t = known_type(type);
      const long long ntags = integer("the tag count", 0, 100);
      for (long long k = 0; k < ntags; ++k) integer("element tag value", -kMaxTag, kMaxTag);
      std::vector<long long> nodes;
      for (int k = 0; k < t.nodes; ++k) nodes.push_back(integer("element node tag", 1, kMaxTag));
      add_cell(tag, type, t, std::move(nodes));
    }
    section_.clear();
  }

  void read_elements4() {
    section_ = "Elements";
    const long long blocks = integer("the entity block count", 0, kMaxTag);
    const long long n = integer("the element count", 0, kMaxTag);
    integer("the smallest element tag", 0, kMaxTag);
    integer("the largest element tag", 0, kMaxTag);
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = integer("entity dimension", 0, 3);
      integer("entity tag", -kMaxTag, kMaxTag);
      const long long type = integer("element type", 1, 1000);
      const ElementType t = known_type(type);
      if (t.dim != dim) fail("an element block of dimension " + std::to_string(dim) + " holds type " + std::to_string(type));
      const long long m = integer("the block's element count", 0, n - (long long)cells_.size());
      for (long long e = 0; e < m; ++e) {
        const long long tag = integer("element tag", 1, kMaxTag);
        std::vector<long long> nodes;
        for (int k = 0; k < t.nodes; ++k) nodes.push_back(integer("element node tag", 1, kMaxTag));
        add_cell(tag, type, t, std::move(nodes));
      }
    }
    if ((long long)cells_.size() != n)
      fail("$Elements declares " + std::to_string(n) + " elements and holds " + std::to_string(cells_.size()));
    section_.clear();
  }

  /// Two cells of the top dimension on the same nodes: a duplicated element (MSH 2.2 repeats
  /// lower-dimensional elements once per physical group, so only the body's cells are checked).
  void check_duplicated_cells() const {
    int top = -1;
    for (const auto& c : cells_) top = std::max(top, c.dim);
    std::vector<const Cell*> body;
    for (const auto& c : cells_)
      if (c.dim == top) body.push_back(&c);
    std::sort(body.begin(), body.end(), [](const Cell* a, const Cell* b) {
      return std::tie(a->type, a->nodes, a->tag) < std::tie(b->type, b->nodes, b->tag);
    });
    for (std::size_t k = 1; k < body.size(); ++k)
      if (body[k]->type == body[k - 1]->type && body[k]->nodes == body[k - 1]->nodes)
        fail("elements " + std::to_string(body[k - 1]->tag) + " and " + std::to_string(body[k]->tag) +
             " are the same element (duplicated: same type, same nodes)");
  }

  std::string name_, text_;
  std::size_t pos_ = 0;
  int version_ = 4;
  std::string section_;
  std::vector<long long> node_tags_;
  std::vector<Cell> cells_;
};

}  // namespace

void check_msh_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot open the mesh file");
  std::ostringstream text;
  text << in.rdbuf();
  MshReader(file, text.str()).check();
}

}  // namespace workbench
