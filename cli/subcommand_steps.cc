// What every subcommand does around its study: read the case file, check its output options, name
// the output folder, say what it did.
#include "commands.h"

#include <fem_reference/mpi.h>
#include <workbench/error.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <ostream>

#include <unistd.h>

namespace cli {

namespace {

void check_not_a_folder(const std::string& path) {
  if (std::filesystem::is_directory(path))
    throw workbench::Error(path + ": is a folder, not a case file (give the .toml file inside it)");
}

}  // namespace

workbench::CaseFile read_case_file(const std::string& path) {
  check_not_a_folder(path);
  return workbench::CaseFile(path);
}

std::unique_ptr<workbench::CaseFile> read_case_file_on_every_rank(const std::string& path) {
  std::unique_ptr<workbench::CaseFile> file;
  fem_reference::mpi_collective([&] {
    check_not_a_folder(path);
    file = std::make_unique<workbench::CaseFile>(path);
  });
  return file;
}

void check_writable_file(const std::string& path, const std::string& option) {
  namespace fs = std::filesystem;
  const fs::path file = fs::absolute(path).lexically_normal();
  auto refuse = [&](const std::string& why) { throw workbench::Error(path + ": " + option + ": " + why); };
  std::error_code ec;
  if (file.filename().empty() || fs::is_directory(file, ec)) refuse("is a folder, not a file");
  if (fs::exists(fs::symlink_status(file, ec))) {
    if (!fs::is_regular_file(file, ec)) refuse("exists and is not a regular file");
    if (::access(file.c_str(), W_OK) != 0) refuse("cannot be written (no permission)");
    return;
  }
  fs::path parent = file.parent_path();
  while (!fs::exists(parent, ec)) parent = parent.parent_path();
  if (!fs::is_directory(parent, ec)) refuse(parent.string() + " is not a folder");
  if (::access(parent.c_str(), W_OK | X_OK) != 0) refuse("cannot be created in " + parent.string() + " (no permission)");
}

int checked(const workbench::CaseFile& file, const std::string& subcommand, const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) progress_log() << subcommand << ": warning: " << w << "\n";
  progress_log() << subcommand << ": " << file.path().string() << ": checked, nothing written\n";
  return 0;
}

std::ostream& progress_log() {
  static std::ostream nowhere(nullptr);  // a stream without a buffer drops what it is given
  return !fem_reference::started_by_launcher() || fem_reference::mpi_rank() == 0 ? std::cerr : nowhere;
}

std::string output_folder(const std::string& option, const workbench::CaseFile& file, const std::string& subcommand) {
  return option.empty() ? "out/" + file.path().stem().string() + "/" + subcommand : option;
}

}  // namespace cli
