#pragma once
// gmsh keeps global state (models, options a .geo sets, ONELAB parameters, parser variables,
// error counters), shared by every module that meshes in this process. All of them load meshes
// through gmsh_load(), which starts every load from a freshly initialised gmsh.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace workbench {

/// Opens a gmsh .geo (and meshes it in its own dimension) or .msh file into gmsh's current model.
/// A .geo is parsed and meshed in a child process, the mesher program (kGeoMesherPath, found beside
/// the program: workbench/child_process.h), whose .msh is then read here, so that a crash of gmsh on
/// a bad .geo becomes the error "<file>: gmsh failed meshing it (killed by signal 11: ...)"; the
/// model is the one meshing here would give, node and element tags and order included. Without the
/// mesher program (a program embedding the libraries), the .geo is meshed in this process.
/// `parameters` override the .geo's DefineConstant values (ONELAB numbers); a name the .geo does
/// not declare is an error, and so are parameters for a .msh. Returns the names the .geo declares.
/// Before gmsh sees the file: parameters must be finite, a .msh passes check_msh_file(), a .geo's
/// estimated mesh must fit the memory limit (mesh_checks.h); after loading, every node coordinate
/// must be finite. Errors (no such file, a .geo's Error(), these checks, gmsh failures) are
/// std::runtime_error with a one-line message starting with the file name. The model stays
/// loaded until the next gmsh_load(). `unit` (metres per unit of the file, [mesh] unit) scales every
/// node once loaded, so that every reader sees metres.
std::vector<std::string> gmsh_load(const std::filesystem::path& file, const std::map<std::string, double>& parameters,
                                   double unit = 1.0);

/// Starts the mesher server: a child forked from this process (no exec), which has gmsh's
/// libraries loaded already, so that meshing a .geo does not pay for loading them again in the
/// mesher program (docs/performance.md, "Meshing a .geo in a child process"). Each .geo is then
/// meshed in a process the server forks for it, as the mesher program would mesh it: a crash or
/// abort of gmsh ends that process only and is the same one error; the server goes on serving. The
/// server is in a process group of its own, ends with this process, and is ended by an
/// interruption (call register_geo_mesher_server() once handle_interruptions() ran). Call it first
/// in main(), before MPI starts and before any thread (a fork copies the calling thread only);
/// gmsh_load() falls back to the mesher program when the server is not running. Returns its pid
/// (0 if it could not be started).
int start_geo_mesher_server();

/// Adds the server's process group to those an interruption ends (workbench/interruption.h).
void register_geo_mesher_server();

/// The server's pid, 0 when none runs (not started, or it ended).
int geo_mesher_server_pid();

/// How many .geo files the server has meshed (or refused) for this process (tests).
int geo_mesher_server_requests();

/// The mesher program, relative to a folder beside the running program (or up to two above it).
inline constexpr const char* kGeoMesherPath = "libexec/workbench/workbench-geo-mesher";

/// The mesher's exit status when it refused the .geo (the message is in its report).
inline constexpr int kMesherRefused = 2;

/// The mesher program's main(): `workbench-geo-mesher GEO MSH [NAME VALUE]...` loads GEO as
/// gmsh_load does in this process (VALUE in C's %a notation), writes the meshed model to MSH (binary
/// MSH 4.1, every element) and reports on its standard input, a socket: "ok NODES ELEMENTS" and the
/// names the .geo declares, a line each; or "error" and the one-line message (exit kMesherRefused).
int geo_mesher_main(int argc, char** argv);

/// An element of a physical group: its gmsh element type and its node tags.
struct GroupElement {
  int type;
  std::vector<std::size_t> nodes;
};

/// The physical groups of dimension `dim` of the loaded model, by name (an unnamed group by its
/// number), with their elements.
std::map<std::string, std::vector<GroupElement>> gmsh_physical_groups(int dim);

}  // namespace workbench
