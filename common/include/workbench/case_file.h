#pragma once
// A study's case file: TOML, read through typed, range-checked getters that remember which keys
// were read, so that a misspelt or unknown key is rejected instead of silently ignored.
//
//   workbench::CaseFile file("cases/seed_plate.toml");
//   auto material = file.root().table("material");
//   double E = material.number("young", {}, workbench::Range::positive());   // required
//   double nu = material.number("poisson", 0.3, workbench::Range::open(-1.0, 0.5));
//   file.reject_unknown_keys();   // throws on any key nobody read
//
// Every error is a workbench::Error with a one-line message "file: key: reason".
#include <workbench/error.h>

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace toml {
inline namespace v3 {
class table;
}
}  // namespace toml

namespace workbench {

/// An interval of admissible values, each end open or closed. No range admits NaN, an infinity,
/// or a non-zero magnitude above kMaxMagnitude or below kMinMagnitude: every quantity of a case
/// file is in SI units (keys renamed when a unit changed: CaseTable::refuse_renamed), where such a value is a typo, and a product or quotient of three of them must stay
/// finite and non-zero.
struct Range {
  static constexpr double kMaxMagnitude = 1e100;
  static constexpr double kMinMagnitude = 1e-100;
  double lo = -kMaxMagnitude, hi = kMaxMagnitude;
  bool lo_open = false, hi_open = false;
  static Range any() { return {}; }
  static Range positive() { return {0.0, kMaxMagnitude, true, false}; }
  static Range non_negative() { return {0.0, kMaxMagnitude, false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  bool contains(double v) const { return problem(v).empty(); }
  /// Why `v` is not admissible ("must be > 0 (got -1)"), or "" when it is.
  std::string problem(double v) const;
  std::string describe() const;
};

class CaseFile;

/// A view of one table of the case file (the root, `[material]`, one `[[load]]` entry, ...).
/// Getters with a default return it when the key is absent; without one the key is required.
class CaseTable {
 public:
  double number(const std::string& key, std::optional<double> fallback, Range range = Range::any()) const;
  int integer(const std::string& key, std::optional<int> fallback, int lo, int hi) const;
  bool flag(const std::string& key, std::optional<bool> fallback) const;
  /// A string; when `choices` is not empty it must be one of them.
  std::string text(const std::string& key, std::optional<std::string> fallback,
                   const std::vector<std::string>& choices = {}) const;
  std::vector<std::string> texts(const std::string& key, std::optional<std::vector<std::string>> fallback) const;
  std::vector<double> numbers(const std::string& key, std::optional<std::vector<double>> fallback,
                              Range range = Range::any()) const;
  /// A table of free-form names mapped to numbers (e.g. [mesh.parameters]); absent gives {}.
  std::map<std::string, double> number_map(const std::string& key) const;
  /// A path, resolved relative to the case file's folder.
  std::filesystem::path path(const std::string& key, std::optional<std::string> fallback) const;
  bool has(const std::string& key) const;
  /// The key is present and holds an array (a key that takes a name or a vector: [[load]] direction).
  bool is_array(const std::string& key) const;
  /// A sub-table; an absent one reads as empty (so its getters return their defaults).
  CaseTable table(const std::string& key) const;
  /// An array of tables ([[load]] entries); absent gives an empty list.
  std::vector<CaseTable> tables(const std::string& key) const;

  /// "file: prefix.key" for messages.
  std::string where(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;
  /// Fails when `old_key` is present: a key renamed when its unit changed, so that an old case is
  /// never read in the wrong unit ("renamed: give NEW_KEY (CONVERSION)").
  void refuse_renamed(const std::string& old_key, const std::string& new_key, const std::string& conversion) const;
  const CaseFile& file() const { return *file_; }

 private:
  friend class CaseFile;
  CaseTable(const CaseFile* file, const toml::table* table, std::string prefix)
      : file_(file), table_(table), prefix_(std::move(prefix)) {}
  std::string full(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }
  const CaseFile* file_;
  const toml::table* table_;  // null for an absent table
  std::string prefix_;
};

class CaseFile {
 public:
  /// Parses the file; a syntax error becomes "file:line:column: message".
  explicit CaseFile(const std::filesystem::path& path);
  /// Parses text (for tests); `name` stands in for the file name in messages.
  CaseFile(const std::string& text, const std::filesystem::path& name);
  ~CaseFile();
  CaseFile(const CaseFile&) = delete;
  CaseFile& operator=(const CaseFile&) = delete;

  CaseTable root() const;
  const std::filesystem::path& path() const { return path_; }
  /// The case as TOML text (every key, comments dropped): what a derived case starts from when the
  /// case came from text rather than a file (workbench/case_edit.h edits it).
  std::string text() const;
  /// Throws for the first key (in file order) that no getter has read.
  void reject_unknown_keys() const;
  /// The dotted keys read so far as paths (CaseTable::path) that the file gives, e.g. "mesh.file".
  std::vector<std::string> path_keys() const { return {paths_.begin(), paths_.end()}; }

 private:
  friend class CaseTable;
  void mark(const std::string& key) const { used_.insert(key); }
  std::filesystem::path path_;
  std::unique_ptr<toml::table> table_;
  mutable std::set<std::string> used_;
  mutable std::set<std::string> paths_;
};

}  // namespace workbench
