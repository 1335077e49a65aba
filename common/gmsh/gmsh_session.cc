// The process's one gmsh session: every .geo/.msh load starts from a fresh gmsh, after the
// checks of mesh_checks.h (gmsh aborts or crashes on some bad input instead of reporting it). A
// .geo is parsed and meshed in a child process (workbench-geo-mesher), whose crash is one error.
#include "gmsh_session.h"

#include "mesh_checks.h"

#include <gmsh.h>

#include <workbench/child_process.h>
#include <workbench/interruption.h>
#include <workbench/output_file.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace workbench {

namespace {

bool initialised = false;

/// A fresh gmsh: options a previous .geo set (Mesh.ElementOrder, ...) and the parsing state gmsh
/// 4.8 keeps after an Error() survive gmsh::clear() and go only with finalize(); the .geo
/// parser's variables survive finalize() and go only with clear().
void fresh_gmsh() {
  if (initialised) {
    gmsh::logger::stop();
    gmsh::finalize();
  }
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::clear();
  gmsh::onelab::clear();
  initialised = true;
}

std::string last_error() {
  std::string error;
  gmsh::logger::getLastError(error);
  return error.empty() ? "gmsh failed" : error;
}

struct LoadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The checks every load starts with (no gmsh involved).
void check_load_request(const std::filesystem::path& file, const std::map<std::string, double>& parameters) {
  const std::string name = file.string();
  if (!std::filesystem::is_regular_file(file)) throw std::runtime_error(name + ": no such mesh file");
  const std::string ext = file.extension().string();
  if (ext != ".geo" && ext != ".msh") throw std::runtime_error(name + ": a mesh must be a gmsh .geo or .msh file");
  if (ext == ".msh" && !parameters.empty()) throw std::runtime_error(name + ": mesh parameters apply to .geo files only");
  for (const auto& [key, value] : parameters)
    if (!std::isfinite(value)) throw std::runtime_error(name + ": mesh parameter '" + key + "' is not a finite number");
}

/// Throws LoadError "name: <what>" for the first Error() gmsh logged since logger::start().
void throw_logged_error(const std::string& name) {
  std::vector<std::string> log;
  gmsh::logger::get(log);
  for (const auto& line : log)
    if (line.rfind("Error", 0) == 0) {
      const auto colon = line.find(':');
      throw LoadError(name + ": " + (colon == std::string::npos ? line : line.substr(colon + 2)));
    }
}

/// The load in this process: gmsh parses (and meshes) the file here.
std::vector<std::string> load_here(const std::filesystem::path& file, const std::map<std::string, double>& parameters) {
  const std::string name = file.string();
  const std::string ext = file.extension().string();
  if (ext == ".msh") check_msh_file(file);
  std::vector<std::string> declared;
  try {
    if (ext == ".geo") {
      // The names the .geo declares, read before any is set from outside.
      fresh_gmsh();
      gmsh::open(name);
      std::vector<std::string> names;
      gmsh::onelab::getNames(names);
      for (const auto& n : names)
        if (n.find('/') == std::string::npos) declared.push_back(n);
      for (const auto& [key, value] : parameters)
        if (std::find(declared.begin(), declared.end(), key) == declared.end())
          throw LoadError(name + ": unknown mesh parameter '" + key + "' (the .geo declares none of that name)");
    }
    fresh_gmsh();
    for (const auto& [key, value] : parameters) gmsh::onelab::setNumber(key, {value});
    gmsh::logger::start();
    gmsh::open(name);
    // Error() in a .geo is logged, not always thrown: report the first one.
    throw_logged_error(name);
    if (ext == ".geo") {
      try {
        check_geo_mesh_size(file);
      } catch (const std::runtime_error& e) {  // too large for the memory limit
        throw LoadError(e.what());
      }
      gmsh::model::mesh::generate(gmsh::model::getDimension());
    }
    gmsh::logger::stop();
    std::vector<std::size_t> tags;
    std::vector<double> coords, parametric;
    gmsh::model::mesh::getNodes(tags, coords, parametric);
    for (std::size_t i = 0; i < coords.size(); ++i)
      if (!std::isfinite(coords[i]))
        throw LoadError(name + ": node " + std::to_string(tags[i / 3]) + " has a non-finite coordinate");
  } catch (const LoadError&) {
    throw;
  } catch (...) {
    throw std::runtime_error(name + ": " + last_error());
  }
  return declared;
}

/// Counts of the loaded model's nodes and elements, by which the parent checks the .msh it reads.
std::string model_counts() {
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric);
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes);
  std::size_t elements = 0;
  for (const auto& t : element_tags) elements += t.size();
  return std::to_string(tags.size()) + " " + std::to_string(elements);
}

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

std::optional<int> mesh_in_server(const std::vector<std::string>& request, std::string& report);

/// Meshes the .geo in a child process, one the mesher server forks (start_geo_mesher_server) or else
/// the mesher program `mesher` (workbench-geo-mesher), and loads its .msh.
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
    std::vector<std::string> server_request{std::filesystem::current_path().string(),
                                            (folder.path() / "mesher.log").string(), name, msh.string()};
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

/// Copies what arrives on `in` (a FIFO's read end) into `file` with checked writes until the last
/// writer closes it; returns the first failure's message ("" if none), reading on after a failure
/// so that the writer never blocks.
std::string copy_fifo(int in, const std::string& file) {
  std::string error;
  std::optional<OutputFile> out;
  try {
    out.emplace(file);
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::vector<char> buffer(1 << 16);
  for (ssize_t n; (n = ::read(in, buffer.data(), buffer.size())) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return file + ": read failed (" + std::strerror(errno) + ")";
    if (error.empty()) try {
        out->write({buffer.data(), std::size_t(n)});
      } catch (const std::exception& e) {
        error = e.what();
      }
  }
  if (error.empty()) try {
      out->close();
    } catch (const std::exception& e) {
      error = e.what();
    }
  return error;
}

/// gmsh::write(msh) with its writes checked: gmsh ignores a failed write (a full disk, a file-size
/// limit would leave a short .msh), so it writes into a FIFO beside `msh`, from which a thread
/// copies the bytes with checked writes. Throws "<msh>: write failed (<reason>)".
void write_checked(const std::string& msh) {
  const std::string fifo = (std::filesystem::path(msh).parent_path() / "gmsh-output.msh").string();
  if (::mkfifo(fifo.c_str(), 0600) != 0) throw std::runtime_error(fifo + ": cannot create (" + std::strerror(errno) + ")");
  // This process holds a write end until gmsh is done, so the copier sees the end only then.
  const int in = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  const int hold = in < 0 ? -1 : ::open(fifo.c_str(), O_WRONLY | O_CLOEXEC);
  if (in < 0 || hold < 0) throw std::runtime_error(fifo + ": cannot open (" + std::strerror(errno) + ")");
  ::fcntl(in, F_SETFL, ::fcntl(in, F_GETFL) & ~O_NONBLOCK);
  std::string copy_error;
  std::thread copier([&] { copy_error = copy_fifo(in, msh); });
  std::string write_error;
  try {
    gmsh::write(fifo);
  } catch (...) {
    write_error = msh + ": " + last_error();
  }
  ::close(hold);
  copier.join();
  ::close(in);
  if (!write_error.empty()) throw std::runtime_error(write_error);
  if (!copy_error.empty()) throw std::runtime_error(copy_error);
}

/// Sends all of `text` on socket `fd` (never a SIGPIPE); false when the other end is gone.
bool send_all(int fd, const std::string& text) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::send(fd, text.data() + done, text.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += std::size_t(n);
  }
  return true;
}

/// Receives exactly `size` bytes from `fd`; false at the end of input or on an error.
bool receive_all(int fd, char* data, std::size_t size) {
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = ::recv(fd, data + done, size - done, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += std::size_t(n);
  }
  return true;
}

/// A message between the workbench and the mesher server: a count of strings, then each string
/// with its length before it.
bool send_message(int fd, const std::vector<std::string>& parts) {
  std::string text;
  const auto put = [&](std::uint64_t n) { text.append(reinterpret_cast<const char*>(&n), sizeof n); };
  put(parts.size());
  for (const auto& p : parts) {
    put(p.size());
    text += p;
  }
  return send_all(fd, text);
}

bool receive_message(int fd, std::vector<std::string>& parts) {
  std::uint64_t count = 0;
  if (!receive_all(fd, reinterpret_cast<char*>(&count), sizeof count) || count > 4096) return false;
  parts.assign(count, {});
  for (auto& p : parts) {
    std::uint64_t size = 0;
    if (!receive_all(fd, reinterpret_cast<char*>(&size), sizeof size) || size > (std::uint64_t(1) << 32)) return false;
    p.resize(size);
    if (!receive_all(fd, p.data(), size)) return false;
  }
  return true;
}

/// The mesher's work, in the mesher program or in a process the server forked: GEO loaded as
/// gmsh_load does in this process, the meshed model written to MSH (binary MSH 4.1, every element);
/// the report ("ok NODES ELEMENTS" and the declared names, or "error" and the message) sent on
/// socket `report`. Returns the exit status: 0, or kMesherRefused.
int mesh_and_report(int report_fd, const std::string& geo, const std::string& msh,
                    const std::map<std::string, double>& parameters) {
  std::signal(SIGXFSZ, SIG_IGN);  // a file-size limit is a failed write (EFBIG), as in the workbench
  try {
    check_load_request(geo, parameters);
    const auto declared = load_here(geo, parameters);
    // Binary, so that every coordinate comes back exactly; every element, not only those of
    // physical groups; no scaling a .geo may have asked for (the in-process load had none).
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 1);
    gmsh::option::setNumber("Mesh.SaveAll", 1);
    gmsh::option::setNumber("Mesh.SaveParametric", 0);
    gmsh::option::setNumber("Mesh.ScalingFactor", 1);
    write_checked(msh);
    std::string report = "ok " + model_counts() + "\n";
    for (const auto& n : declared) report += n + "\n";
    send_all(report_fd, report);
    return 0;
  } catch (const std::exception& e) {
    send_all(report_fd, std::string("error\n") + e.what() + "\n");
    return kMesherRefused;
  }
}

/// The mesher server (start_geo_mesher_server): its channel to the workbench, its pid.
int server_channel = -1;
pid_t server_pid = 0;
int server_requests = 0;  // answered
std::mutex server_mutex;  // one request at a time

/// The exit status as ChildProcess::wait gives it: 128 + signal when a signal ended the process.
int exit_status(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

/// A process forked for one .geo by the server: it ends with the server; its output goes to the
/// log, its report to `report_fd`. Never returns.
[[noreturn]] void mesher_worker(const std::vector<std::string>& request, int report_fd, pid_t server) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != server) ::_exit(1);
  // request: the workbench's folder, the log, GEO, MSH, NAME VALUE...
  if (::chdir(request[0].c_str()) != 0) ::_exit(71);
  // Its scratch files (the size estimate's unrolled .geo) in the workbench's folder for this load,
  // which the workbench removes, also when an interruption ends this process half-way.
  ::setenv("TMPDIR", std::filesystem::path(request[1]).parent_path().c_str(), 1);
  const int log = ::open(request[1].c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log >= 0) {
    ::dup2(log, 1);
    ::dup2(log, 2);
    ::close(log);
  }
  std::map<std::string, double> parameters;
  for (std::size_t i = 4; i + 1 < request.size(); i += 2) parameters[request[i]] = std::strtod(request[i + 1].c_str(), nullptr);
  const int code = mesh_and_report(report_fd, request[2], request[3], parameters);
  std::fflush(nullptr);
  ::_exit(code);  // no exit handlers: they belong to the workbench this process was forked from
}

/// The server's loop: a request in, a process forked to mesh it, its exit status and report out.
/// It ends when the workbench closes the channel (or ends: PR_SET_PDEATHSIG).
[[noreturn]] void serve(int channel) {
  for (std::vector<std::string> request; receive_message(channel, request);) {
    std::vector<std::string> reply{"71", ""};  // EX_OSERR: could not fork
    int ends[2];
    if (request.size() >= 4 && ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) == 0) {
      const pid_t server = ::getpid();
      const pid_t pid = ::fork();
      if (pid == 0) {
        ::close(ends[0]);
        ::close(channel);
        mesher_worker(request, ends[1], server);
      }
      ::close(ends[1]);
      if (pid > 0) {
        char text[4096];
        for (ssize_t n; (n = ::recv(ends[0], text, sizeof text, 0)) != 0;) {
          if (n < 0 && errno == EINTR) continue;
          if (n < 0) break;
          reply[1].append(text, std::size_t(n));
        }
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        reply[0] = std::to_string(exit_status(status));
      }
      ::close(ends[0]);
    }
    if (!send_message(channel, reply)) break;
  }
  ::_exit(0);
}

/// Meshes through the server: `request` as mesher_worker reads it; the worker's exit status and its
/// report, or nothing when no server runs (it was not started, or it ended: then none is used again).
std::optional<int> mesh_in_server(const std::vector<std::string>& request, std::string& report) {
  const std::lock_guard<std::mutex> lock(server_mutex);
  if (server_channel < 0) return std::nullopt;
  std::vector<std::string> reply;
  const bool answered = send_message(server_channel, request) && receive_message(server_channel, reply) && reply.size() == 2;
  while (interruption_under_way()) ::pause();  // the watcher ended the server and ends this process
  if (!answered) {  // the server ended (killed from outside): reaped, not used again
    ::close(server_channel);
    server_channel = -1;
    ::waitpid(server_pid, nullptr, WNOHANG);
    forget_child_group(server_pid);
    server_pid = 0;
    return std::nullopt;
  }
  ++server_requests;
  report = reply[1];
  return std::stoi(reply[0]);
}

}  // namespace

std::vector<std::string> gmsh_load(const std::filesystem::path& file, const std::map<std::string, double>& parameters) {
  check_load_request(file, parameters);
  if (file.extension() == ".geo") {
    bool served;
    {
      const std::lock_guard<std::mutex> lock(server_mutex);
      served = server_channel >= 0;
    }
    if (served) return load_geo_in_child({}, file, parameters);
    if (const auto mesher = find_beside_program(kGeoMesherPath); !mesher.empty())
      return load_geo_in_child(mesher, file, parameters);
  }
  return load_here(file, parameters);
}

int start_geo_mesher_server() {
  if (server_pid > 0) return server_pid;
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0) return 0;
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Its own process group (the terminal's Ctrl-C goes to the workbench, whose interruption ends
    // this group); it ends with the workbench; nothing of the workbench's open but its channel.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(0);
    ::prctl(PR_SET_NAME, "geo-mesher");
    if (const int null = ::open("/dev/null", O_RDWR); null >= 0)
      for (int fd = 0; fd < 3; ++fd) ::dup2(null, fd);
    ::dup2(ends[1], 3);
    ::close_range(4, ~0U, 0);
    serve(3);
  }
  ::close(ends[1]);
  if (pid < 0) {
    ::close(ends[0]);
    return 0;
  }
  ::setpgid(pid, pid);  // here too, so that the group exists when it is registered
  server_channel = ends[0];
  server_pid = pid;
  return pid;
}

void register_geo_mesher_server() {
  const auto lock = hold_interruptions();
  if (server_pid > 0) add_child_group(server_pid);
}

int geo_mesher_server_pid() {
  const std::lock_guard<std::mutex> lock(server_mutex);
  return server_pid;
}

int geo_mesher_server_requests() {
  const std::lock_guard<std::mutex> lock(server_mutex);
  return server_requests;
}

int geo_mesher_main(int argc, char** argv) {
  if (argc < 3 || argc % 2 == 0) {
    std::fprintf(stderr, "usage: %s GEO MSH [NAME VALUE]...  (run by the workbench, which reads the MSH)\n", argv[0]);
    return 64;
  }
  std::map<std::string, double> parameters;
  for (int i = 3; i + 1 < argc; i += 2) parameters[argv[i]] = std::strtod(argv[i + 1], nullptr);
  // The report goes back on standard input, a socket (workbench/child_process.h).
  return mesh_and_report(0, argv[1], argv[2], parameters);
}

std::map<std::string, std::vector<GroupElement>> gmsh_physical_groups(int dim) {
  std::map<std::string, std::vector<GroupElement>> out;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  for (const auto& [gdim, gtag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(gdim, gtag, name);
    if (name.empty()) name = std::to_string(gtag);
    auto& elements = out[name];
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(gdim, gtag, entities);
    for (int entity : entities) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> tags, nodes;
      gmsh::model::mesh::getElements(types, tags, nodes, gdim, entity);
      for (std::size_t t = 0; t < types.size(); ++t) {
        const std::size_t n = nodes[t].size() / tags[t].size();
        for (std::size_t e = 0; e < tags[t].size(); ++e)
          elements.push_back({types[t], std::vector<std::size_t>(nodes[t].begin() + e * n, nodes[t].begin() + (e + 1) * n)});
      }
    }
  }
  return out;
}

}  // namespace workbench
