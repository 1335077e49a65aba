// workbench::LineLog: lines written by two threads at once reach the log whole and in each thread's order.
#include <workbench/line_log.h>

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

// Each line is written in five pieces, so that a log without LineLogs would mix the threads' pieces.
void write_lines(std::ostream& out, char who, int count) {
  for (int i = 0; i < count; ++i) out << who << ": line " << i << " of " << count << "\n";
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST(LineLog, TwoThreadsWriteWholeLinesInTheirOwnOrder) {
  constexpr int kCount = 3000;
  std::ostringstream log;
  std::mutex lock;
  {
    workbench::LineLog a(log, lock), b(log, lock);
    std::thread other([&] { write_lines(b, 'b', kCount); });
    write_lines(a, 'a', kCount);
    other.join();
  }
  const auto lines = lines_of(log.str());
  ASSERT_EQ(lines.size(), 2u * kCount);
  int next[2] = {0, 0};
  for (const auto& line : lines) {
    ASSERT_TRUE(line[0] == 'a' || line[0] == 'b') << line;
    int& i = next[line[0] - 'a'];
    EXPECT_EQ(line, std::string(1, line[0]) + ": line " + std::to_string(i) + " of " + std::to_string(kCount));
    ++i;
  }
  EXPECT_EQ(next[0], kCount);
  EXPECT_EQ(next[1], kCount);
}

TEST(LineLog, PassesOnAtTheNewlineAndTheRestWhenDestroyed) {
  std::ostringstream log;
  std::mutex lock;
  {
    workbench::LineLog out(log, lock);
    out << "first\nsecond" << std::flush;  // a flush passes on no unfinished line
    EXPECT_EQ(log.str(), "first\n");
    out << " part";
  }
  EXPECT_EQ(log.str(), "first\nsecond part\n");
}
