#include <workbench/error.h>
#include <workbench/staged_directory.h>

#include <system_error>
#include <unistd.h>

namespace workbench {

namespace fs = std::filesystem;

StagedDirectory::StagedDirectory(fs::path target) : target_(fs::absolute(std::move(target)).lexically_normal()) {
  if (target_.filename().empty()) target_ = target_.parent_path();
  staging_ = target_.parent_path() / ("." + target_.filename().string() + ".partial-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) throw Error(target_.string() + ": cannot create the output folder (" + ec.message() + ")");
}

StagedDirectory::~StagedDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

void StagedDirectory::commit() {
  std::error_code ec;
  if (fs::exists(target_)) {
    if (!fs::is_directory(target_)) throw Error(target_.string() + ": exists and is not a folder");
    fs::remove_all(target_, ec);
    if (ec) throw Error(target_.string() + ": cannot replace the old output (" + ec.message() + ")");
  }
  fs::rename(staging_, target_, ec);
  if (ec) throw Error(target_.string() + ": cannot move the output into place (" + ec.message() + ")");
  committed_ = true;
}

}  // namespace workbench
