#include <workbench/line_log.h>

#include <algorithm>

namespace workbench {

LineLog::LineLog(std::ostream& log, std::mutex& lock) : std::ostream(nullptr), lines_(log, lock) { rdbuf(&lines_); }

LineLog::~LineLog() { lines_.pass_on_rest(); }

int LineLog::Lines::overflow(int ch) {
  if (ch == traits_type::eof()) return traits_type::not_eof(ch);
  const char c = traits_type::to_char_type(ch);
  xsputn(&c, 1);
  return ch;
}

std::streamsize LineLog::Lines::xsputn(const char* s, std::streamsize n) {
  const char* end = s + n;
  for (const char* newline; (newline = std::find(s, end, '\n')) != end; s = newline + 1) pass_on(s, newline + 1);
  line_.append(s, end);
  return n;
}

void LineLog::Lines::pass_on(const char* begin, const char* end) {
  line_.append(begin, end);
  {
    std::lock_guard<std::mutex> hold(lock_);
    log_ << line_ << std::flush;
  }
  line_.clear();
}

void LineLog::Lines::pass_on_rest() {
  if (line_.empty()) return;
  const char newline = '\n';
  pass_on(&newline, &newline + 1);
}

}  // namespace workbench
