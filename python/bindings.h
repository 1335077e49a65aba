#pragma once
// What the module's files share (python/workbench_module.cc, python/bind_studies.cc): a study's
// case, and running a study without the GIL with its progress lines going to Python.
#include <workbench/case_file.h>

#include <pybind11/pybind11.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <streambuf>
#include <string>

namespace workbench_python {

namespace py = pybind11;
namespace fs = std::filesystem;

/// A study's case: a case file, or TOML text standing for one (built from a dict). A fresh
/// CaseFile is parsed per run, so that every run checks every key.
struct Case {
  fs::path path;     ///< the file, or the name standing for it in messages (its folder resolves paths)
  std::string text;  ///< empty: read `path`
  std::unique_ptr<workbench::CaseFile> open() const {
    return text.empty() ? std::make_unique<workbench::CaseFile>(path)
                        : std::make_unique<workbench::CaseFile>(text, path);
  }
};

/// Sends each line written to it to a Python callable (taking the GIL for the call). An exception
/// raised by the callable is kept and re-raised after the run; later lines are dropped.
class CallbackBuffer : public std::streambuf {
 public:
  explicit CallbackBuffer(py::object callback) : callback_(std::move(callback)) {}
  ~CallbackBuffer() override {
    py::gil_scoped_acquire gil;
    callback_ = py::object();
  }
  void rethrow() {
    flush_line();
    if (error_) {
      py::gil_scoped_acquire gil;
      auto e = std::move(*error_);
      error_.reset();
      e.restore();
      throw py::error_already_set();
    }
  }

 protected:
  int overflow(int ch) override {
    if (ch == '\n')
      flush_line();
    else if (ch != EOF)
      line_ += char(ch);
    return ch;
  }

 private:
  void flush_line() {
    if (line_.empty() || callback_.is_none() || error_) {
      line_.clear();
      return;
    }
    py::gil_scoped_acquire gil;
    try {
      callback_(line_);
    } catch (py::error_already_set& e) {
      error_.emplace(std::move(e));
    }
    line_.clear();
  }
  py::object callback_;
  std::string line_;
  std::optional<py::error_already_set> error_;
};

/// Runs `body(log)` without the GIL, progress lines going to `progress` (None: discarded).
template <class Body>
auto with_progress(const py::object& progress, Body body) {
  CallbackBuffer buffer(progress);
  std::ostream log(&buffer);
  using Result = decltype(body(log));
  std::optional<Result> result;
  {
    py::gil_scoped_release release;
    result.emplace(body(log));
  }
  buffer.rethrow();
  return std::move(*result);
}

/// The studies, one per subcommand of the command line (python/bind_studies.cc).
void bind_studies(py::module_& m);

}  // namespace workbench_python
