#pragma once
// One log written by two threads at once (the agent model beside the FEM reference): each thread
// writes through a LineLog of its own, which passes every finished line to the log whole, under a
// lock all LineLogs of that log share, so that no two lines are mixed.
//
//   std::mutex lock;
//   workbench::LineLog agent_log(log, lock), fem_log(log, lock);  // one per thread
//
// A line is passed on at its newline (flushing the log); what is left without one when the LineLog
// is destroyed is passed on then, with a newline. The log itself may then be written again directly.
#include <mutex>
#include <ostream>
#include <streambuf>
#include <string>

namespace workbench {

class LineLog : public std::ostream {
 public:
  LineLog(std::ostream& log, std::mutex& lock);
  LineLog(const LineLog&) = delete;
  LineLog& operator=(const LineLog&) = delete;
  ~LineLog() override;

 private:
  class Lines : public std::streambuf {
   public:
    Lines(std::ostream& log, std::mutex& lock) : log_(log), lock_(lock) {}
    void pass_on_rest();

   protected:
    int overflow(int ch) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;

   private:
    void pass_on(const char* begin, const char* end);  // the line so far, then [begin, end) with its newline
    std::ostream& log_;
    std::mutex& lock_;
    std::string line_;
  };
  Lines lines_;
};

}  // namespace workbench
