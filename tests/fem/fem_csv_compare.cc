// fem_csv_compare DIR_A DIR_B REL_TOL: compares fem_cells.csv, fem_nodes.csv and fem_reactions.csv of
// two FEM runs column by column: |a - b| <= REL_TOL * max |a| over the column (over the whole table
// for the reactions). Exit 0 if all agree.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using Table = std::vector<std::vector<std::string>>;

static Table read(const std::string& file) {
  std::ifstream in(file);
  Table t;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> row;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) row.push_back(cell);
    t.push_back(row);
  }
  return t;
}

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: fem_csv_compare DIR_A DIR_B REL_TOL\n");
    return 2;
  }
  const double tol = std::atof(argv[3]);
  bool ok = true;
  for (const char* name : {"fem_cells.csv", "fem_nodes.csv", "fem_reactions.csv"}) {
    const Table a = read(std::string(argv[1]) + "/" + name), b = read(std::string(argv[2]) + "/" + name);
    if (a.empty() || a.size() != b.size() || a[0] != b[0]) {
      std::printf("%s: missing or different shape (%zu vs %zu rows)\n", name, a.size(), b.size());
      ok = false;
      continue;
    }
    // Reactions: one scale for the whole table (a reaction component that should be zero is noise).
    double table_scale = 0;
    if (std::string(name) == "fem_reactions.csv")
      for (std::size_t r = 1; r < a.size(); ++r)
        for (std::size_t c = 2; c < a[r].size(); ++c) table_scale = std::max(table_scale, std::abs(std::atof(a[r][c].c_str())));
    for (std::size_t c = 1; c < a[0].size(); ++c) {
      double scale = table_scale, diff = 0;
      for (std::size_t r = 1; r < a.size(); ++r) {
        if (a[r].size() != a[0].size() || b[r].size() != a[0].size()) { ok = false; break; }
        char* end = nullptr;
        const double x = std::strtod(a[r][c].c_str(), &end);
        if (end == a[r][c].c_str()) {  // text column: must be equal
          if (a[r][c] != b[r][c]) ok = false;
          continue;
        }
        const double y = std::strtod(b[r][c].c_str(), nullptr);
        scale = std::max(scale, std::abs(x));
        diff = std::max(diff, std::abs(x - y));
      }
      const bool same = diff <= tol * scale || diff == 0;
      std::printf("%s %-10s max |a-b| %.3e of %.3e %s\n", name, a[0][c].c_str(), diff, scale, same ? "" : "DIFFERS");
      ok = ok && same;
    }
  }
  return ok ? 0 : 1;
}
