#pragma once
// A scratch folder no other test can touch: ctest runs every test in its own process, in parallel,
// other build trees may run the same tests at the same time, and a test binary run by hand runs
// all its tests in one process, so the folder is named by the test and the process id. It is
// created on a test's first use and removed when the process exits.
// write_file puts a file (a case file, a mesh) there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <unistd.h>

namespace test_support {

inline const std::filesystem::path& scratch_folder() {
  struct Folder {
    std::filesystem::path path;
    explicit Folder(const std::string& name)
        : path(std::filesystem::temp_directory_path() / ("workbench_test_" + name + "_" + std::to_string(::getpid()))) {
      std::filesystem::create_directories(path);
    }
    Folder(const Folder&) = delete;
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  // One folder per test, also when several tests run in one process (a test binary run by hand).
  static std::map<std::string, Folder> folders;
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = test ? std::string(test->test_suite_name()) + "." + test->name() : "no_test";
  return folders.try_emplace(name, name).first->second.path;
}

/// The whole content of `file` ("" when it cannot be read).
inline std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Writes `text` to the scratch folder's file `name` and returns its path.
inline std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const std::filesystem::path file = scratch_folder() / name;
  std::ofstream(file) << text;
  return file;
}

}  // namespace test_support
