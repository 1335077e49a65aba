#pragma once
// What the files of the gmsh session share and no other module uses: the gmsh lifecycle
// (gmsh_session.cc), the mesher child (geo_mesher_child.cc), its forking server
// (geo_mesher_server.cc) and the messages between them (mesher_messages.cc).
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace workbench::gmsh_detail {

/// A fresh gmsh: options a previous .geo set (Mesh.ElementOrder, ...) and the parsing state gmsh
/// 4.8 keeps after an Error() survive gmsh::clear() and go only with finalize(); the .geo
/// parser's variables survive finalize() and go only with clear().
void fresh_gmsh();

/// gmsh's last error, or "gmsh failed".
std::string last_error();

/// An error already worded for the user ("<file>: <what>"), passed on as it is.
struct LoadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The checks every load starts with (no gmsh involved).
void check_load_request(const std::filesystem::path& file, const std::map<std::string, double>& parameters);

/// Throws LoadError "name: <what>" for the first Error() gmsh logged since logger::start().
void throw_logged_error(const std::string& name);

/// The load in this process: gmsh parses (and meshes) the file here.
std::vector<std::string> load_here(const std::filesystem::path& file, const std::map<std::string, double>& parameters);

/// Counts of the loaded model's nodes and elements, by which the parent checks the .msh it reads.
std::string model_counts();

/// Meshes the .geo in a child process, one the mesher server forks or else the mesher program
/// `mesher` (found beside the program when empty), and loads its .msh.
std::vector<std::string> load_geo_in_child(std::filesystem::path mesher, const std::filesystem::path& file,
                                           const std::map<std::string, double>& parameters);

/// The mesher child's time limit in seconds, unless WORKBENCH_MESH_TIME_LIMIT sets another (up to
/// kMaxMeshTimeLimit): past it, the child reports "<geo>: gmsh did not finish meshing it within N s"
/// and ends (docs/reliability.md, "Meshes").
inline constexpr long kDefaultMeshTimeLimit = 600;
inline constexpr long kMaxMeshTimeLimit = 7 * 24 * 3600;

/// The mesher's work in a child (the mesher program or a process the server forked): GEO loaded as
/// gmsh_load does in this process, the meshed model written to MSH; the report sent on socket
/// `report_fd`. Returns the exit status: 0, or kMesherRefused.
int mesh_and_report(int report_fd, const std::string& geo, const std::string& msh,
                    const std::map<std::string, double>& parameters);

/// True while the mesher server runs.
bool geo_mesher_server_running();

/// Meshes through the server: `request` = the workbench's folder, the log, GEO, MSH, the time
/// limit (WORKBENCH_MESH_TIME_LIMIT's value, "" unset), NAME VALUE...;
/// the meshing process's exit status and its report, or nothing when no server runs (it was not
/// started, or it ended: then none is used again).
std::optional<int> mesh_in_server(const std::vector<std::string>& request, std::string& report);

}  // namespace workbench::gmsh_detail
