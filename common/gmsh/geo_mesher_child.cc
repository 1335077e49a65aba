// The mesher child: a .geo parsed and meshed in a process of its own (the mesher program, or a
// process the mesher server forks), whose crash is one error; the workbench's side reads back its
// .msh (gmsh_session.h, gmsh_load).
#include "gmsh_internal.h"
#include "gmsh_session.h"
#include "gmsh_write.h"
#include "mesher_messages.h"

#include <gmsh.h>

#include <workbench/child_process.h>
#include <workbench/interruption.h>
#include <workbench/output_file.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <pthread.h>
#include <sys/socket.h>
#include <unistd.h>

namespace workbench {

namespace gmsh_detail {

namespace {

/// A folder of our own for the mesher's .msh and log, removed when done or interrupted.
class MesherFolder {
 public:
  explicit MesherFolder(const std::string& name) {
    std::string pattern = (std::filesystem::temp_directory_path() / "workbench-mesh-XXXXXX").string();
    auto lock = hold_interruptions();
    if (!::mkdtemp(pattern.data()))
      throw std::runtime_error(name + ": cannot create a temporary folder in " +
                               std::filesystem::temp_directory_path().string() + " (" + std::strerror(errno) + ")");
    path_ = pattern;
    remove_on_interruption(path_);
  }
  MesherFolder(const MesherFolder&) = delete;
  MesherFolder& operator=(const MesherFolder&) = delete;
  ~MesherFolder() {
    auto lock = hold_interruptions();
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
    forget_on_interruption(path_);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// What ended the mesher, for a message: "killed by signal 11: Segmentation fault", "aborted".
std::string ending_text(int status, const std::filesystem::path& log) {
  if (status == 128 + SIGABRT) return "aborted";
  if (status > 128) return "killed by signal " + std::to_string(status - 128) + ": " + ::strsignal(status - 128);
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return "exit " + std::to_string(status) + (last.empty() ? "" : ": " + last);
}

/// The last .geo meshed in a child process, so that loading it again (a comparison's agent model,
/// FEM reference and error estimate read the same one) reads its .msh without meshing it again.
struct MeshedGeo {
  std::vector<std::string> request;  // the .geo's text and the mesher's parameter arguments
  std::string report, msh;           // the mesher's report and its .msh file
};
std::optional<MeshedGeo> last_meshed;
constexpr std::size_t kMeshedGeoBytes = 64 << 20;  // a larger .msh is not kept

std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The mesher's time limit (a hung gmsh holds no cluster job for ever): the report it sends and
/// where, formatted before the alarm so that the handler only sends it and ends the process.
char time_limit_report[1024];
std::size_t time_limit_report_size = 0;
int time_limit_fd = -1;

extern "C" void on_time_limit(int) {
  if (time_limit_fd >= 0) ::send(time_limit_fd, time_limit_report, time_limit_report_size, MSG_NOSIGNAL);
  ::_exit(kMesherRefused);
}

/// Arms the time limit: WORKBENCH_MESH_TIME_LIMIT seconds (kDefaultMeshTimeLimit unset), after
/// which this process reports that gmsh did not finish and ends (SIGALRM).
void arm_time_limit(int report_fd, const std::string& geo) {
  long seconds = kDefaultMeshTimeLimit;
  if (const char* text = std::getenv("WORKBENCH_MESH_TIME_LIMIT")) {
    char* end = nullptr;
    seconds = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || seconds < 1 || seconds > kMaxMeshTimeLimit)
      throw std::runtime_error(geo + ": WORKBENCH_MESH_TIME_LIMIT: must be a whole number of seconds in [1, " +
                               std::to_string(kMaxMeshTimeLimit) + "] (got '" + text + "')");
  }
  const std::string report = "error\n" + geo + ": gmsh did not finish meshing it within " + std::to_string(seconds) +
                             " s (the time limit; WORKBENCH_MESH_TIME_LIMIT=<seconds> sets it)\n";
  time_limit_report_size = std::min(report.size(), sizeof time_limit_report);
  std::copy_n(report.data(), time_limit_report_size, time_limit_report);
  time_limit_fd = report_fd;
  struct sigaction action {};
  action.sa_handler = on_time_limit;
  ::sigaction(SIGALRM, &action, nullptr);
  sigset_t alarm_only;
  ::sigemptyset(&alarm_only);
  ::sigaddset(&alarm_only, SIGALRM);
  ::pthread_sigmask(SIG_UNBLOCK, &alarm_only, nullptr);  // gmsh's threads inherit this mask
  ::alarm(unsigned(seconds));
}

}  // namespace

std::vector<std::string> load_geo_in_child(std::filesystem::path mesher, const std::filesystem::path& file,
                                           const std::map<std::string, double>& parameters) {
  const std::string name = file.string();
  const MesherFolder folder(name);
  const auto msh = folder.path() / "mesh.msh";
  std::vector<std::string> request{file_text(file)};
  for (const auto& [key, value] : parameters) {
    char text[64];
    std::snprintf(text, sizeof text, "%a", value);  // hexadecimal: the value exactly
    request.insert(request.end(), {key, text});
  }
  // The report: "ok NODES ELEMENTS" and the declared names, a line each; or "error" and the message.
  std::string report;
  const bool meshed_before = last_meshed && last_meshed->request == request;
  if (meshed_before) {
    report = last_meshed->report;
    write_file(msh, last_meshed->msh);
  } else {
    // The time limit as this process's environment says now (the server's is that of its start).
    const char* limit = std::getenv("WORKBENCH_MESH_TIME_LIMIT");
    std::vector<std::string> server_request{std::filesystem::current_path().string(),
                                            (folder.path() / "mesher.log").string(), name, msh.string(),
                                            limit ? limit : ""};
    server_request.insert(server_request.end(), request.begin() + 1, request.end());
    int status = 0;
    if (const auto served = mesh_in_server(server_request, report)) {
      status = *served;
    } else {
      if (mesher.empty()) mesher = find_beside_program(kGeoMesherPath);
      if (mesher.empty()) throw std::runtime_error(name + ": gmsh failed meshing it (the mesher server ended)");
      std::vector<std::string> argv{mesher.string(), name, msh.string()};
      argv.insert(argv.end(), request.begin() + 1, request.end());
      try {
        status = run_child(argv, folder.path() / "mesher.log", &report);
      } catch (const std::runtime_error& e) {  // it could not be started
        throw std::runtime_error(name + ": " + e.what());
      }
    }
    if (status == kMesherRefused && report.rfind("error\n", 0) == 0)
      throw std::runtime_error(report.substr(6, report.find('\n', 6) - 6));
    if (status != 0 || report.rfind("ok ", 0) != 0)
      throw std::runtime_error(name + ": gmsh failed meshing it (" + ending_text(status, folder.path() / "mesher.log") + ")");
  }
  std::istringstream lines(report);
  std::string head;
  std::getline(lines, head);
  std::vector<std::string> declared;
  for (std::string line; std::getline(lines, line);) declared.push_back(line);
  try {
    fresh_gmsh();
    gmsh::logger::start();
    gmsh::open(msh.string());
    throw_logged_error(name);
    gmsh::logger::stop();
  } catch (const LoadError&) {
    throw;
  } catch (...) {
    throw std::runtime_error(name + ": " + last_error());
  }
  if ("ok " + model_counts() != head)
    throw std::runtime_error(name + ": the meshed model read back from " + msh.string() + " is incomplete");
  if (!meshed_before && std::filesystem::file_size(msh) <= kMeshedGeoBytes)
    last_meshed = MeshedGeo{request, report, file_text(msh)};
  return declared;
}

int mesh_and_report(int report_fd, const std::string& geo, const std::string& msh,
                    const std::map<std::string, double>& parameters) {
  std::signal(SIGXFSZ, SIG_IGN);  // a file-size limit is a failed write (EFBIG), as in the workbench
  try {
    arm_time_limit(report_fd, geo);
    check_load_request(geo, parameters);
    const auto declared = load_here(geo, parameters);
    // Binary, so that every coordinate comes back exactly; every element, not only those of
    // physical groups; no scaling a .geo may have asked for (the in-process load had none).
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 1);
    gmsh::option::setNumber("Mesh.SaveAll", 1);
    gmsh::option::setNumber("Mesh.SaveParametric", 0);
    gmsh::option::setNumber("Mesh.ScalingFactor", 1);
    gmsh_write_checked(msh);
    ::alarm(0);
    std::string report = "ok " + model_counts() + "\n";
    for (const auto& n : declared) report += n + "\n";
    send_all(report_fd, report);
    return 0;
  } catch (const std::exception& e) {
    send_all(report_fd, std::string("error\n") + e.what() + "\n");
    return kMesherRefused;
  }
}

}  // namespace gmsh_detail

int geo_mesher_main(int argc, char** argv) {
  if (argc < 3 || argc % 2 == 0) {
    std::fprintf(stderr, "usage: %s GEO MSH [NAME VALUE]...  (run by the workbench, which reads the MSH)\n", argv[0]);
    return 64;
  }
  std::map<std::string, double> parameters;
  for (int i = 3; i + 1 < argc; i += 2) parameters[argv[i]] = std::strtod(argv[i + 1], nullptr);
  // The report goes back on standard input, a socket (workbench/child_process.h).
  return gmsh_detail::mesh_and_report(0, argv[1], argv[2], parameters);
}

}  // namespace workbench
