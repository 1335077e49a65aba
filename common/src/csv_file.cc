// CSV tables: one number format, checked writes, no non-finite values.
#include <workbench/csv_file.h>
#include <workbench/error.h>

#include <charconv>
#include <cmath>

namespace workbench {

std::string shortest_decimal(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

CsvFile::CsvFile(std::filesystem::path file) : file_(file), out_(std::move(file)) {}

CsvFile& CsvFile::text(const std::string& s) {
  for (char c : s) {
    if (at_line_start_) {
      comment_line_ = c == '#';
      at_line_start_ = false;
      field_ = 0;
      line_head_.clear();
      if (!header_done_ && !comment_line_) columns_.assign(1, "");
    }
    if (c == '\n') {
      if (!comment_line_) header_done_ = true;
      at_line_start_ = true;
    } else if (!comment_line_ && c == ',') {
      ++field_;
      if (!header_done_) columns_.emplace_back();
    } else if (!comment_line_) {
      if (!header_done_) columns_.back() += c;
      if (field_ == 0) line_head_ += c;
    }
  }
  out_.write(s);
  return *this;
}

CsvFile& CsvFile::operator<<(double v) {
  if (!std::isfinite(v)) {
    const std::string column =
        !header_done_ ? "header" : columns_.empty() ? "?" : columns_[std::min(field_, columns_.size() - 1)];
    // The file's name alone: the folder is the hidden staging folder, which means nothing to a user.
    throw Error(file_.filename().string() + ": column '" + column + "' (row " + (line_head_.empty() ? "?" : line_head_) + "): " +
                shortest_decimal(v) + " is not a finite number");
  }
  return text(shortest_decimal(v));
}

void CsvFile::close() { out_.close(); }

}  // namespace workbench
