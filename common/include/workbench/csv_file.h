#pragma once
// The one way the workbench writes a CSV table: numbers in one format (the shortest text that
// reads back as the same double, std::to_chars), every write checked, and a non-finite number
// refused with an error naming the file, the column and the row instead of written.
//
//   auto out = workbench::open_csv(dir / "nodes.csv");
//   out << "node,x,y\n";                      // the first line that is not a comment: the header
//   out << 0 << ',' << 0.1 << ',' << 2.5 << '\n';
//   out.close();                              // throws "<dir>/nodes.csv: write failed (No space left on device)"
//
// Lines starting with '#' are comments. A row may have more fields than the header (the last
// column then holds a list, e.g. a cell's nodes). A value that is undefined on purpose (a ratio
// whose denominator is masked) is written as std::nullopt: an empty field, the one marker of "no
// number here" (pandas and numpy.genfromtxt read it as NaN); a non-finite number is never written.
#include <workbench/output_file.h>

#include <filesystem>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace workbench {

/// `v` as the shortest decimal text that parses back to exactly `v` (e.g. 0.1 -> "0.1").
std::string shortest_decimal(double v);

class CsvFile {
 public:
  /// Throws workbench::Error "<file>: cannot open for writing (<reason>)".
  explicit CsvFile(std::filesystem::path file);
  CsvFile(CsvFile&&) = default;

  /// A finite number; a non-finite one throws "<file name>: column '<name>' (row <first field>): <v> is
  /// not a finite number".
  CsvFile& operator<<(double v);
  CsvFile& operator<<(float v) { return *this << double(v); }
  /// A number where there is one; std::nullopt leaves the field empty (undefined on purpose, see above).
  CsvFile& operator<<(const std::optional<double>& v) { return v ? *this << *v : *this; }
  template <class Int, class = std::enable_if_t<std::is_integral_v<Int> && !std::is_same_v<Int, char>>>
  CsvFile& operator<<(Int v) {
    return text(std::to_string(v));
  }
  CsvFile& operator<<(char c) { return text(std::string(1, c)); }
  CsvFile& operator<<(const char* s) { return text(s); }
  CsvFile& operator<<(const std::string& s) { return text(s); }

  /// Flushes and closes; throws "<file>: write failed (<reason>)" (workbench/output_file.h) as
  /// every write does.
  void close();

 private:
  CsvFile& text(const std::string& s);
  std::filesystem::path file_;
  OutputFile out_;
  std::vector<std::string> columns_;  // from the header
  bool header_done_ = false, at_line_start_ = true, comment_line_ = false;
  std::string line_head_;  // the current line's first field (names the row in messages)
  std::size_t field_ = 0;  // index of the field being written on the current line
};

/// Opens `file` for a CSV table (see CsvFile).
inline CsvFile open_csv(const std::filesystem::path& file) { return CsvFile(file); }

}  // namespace workbench
