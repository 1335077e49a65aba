#pragma once
// gmsh::write with its writes checked: gmsh ignores a failed write, so a full disk or a file-size
// limit would leave a short file without an error.
#include <filesystem>

namespace workbench {

/// Writes gmsh's current model to `file` (the format by its extension, as gmsh::write) through a
/// FIFO beside it (a hidden `.NAME.fifo-PID.EXT`, removed afterwards), from which a thread copies
/// the bytes with the project's checked writes (workbench/output_file.h). Throws
/// std::runtime_error "<file>: write failed (<reason>)", or "<file>: <gmsh's error>".
void gmsh_write_checked(const std::filesystem::path& file);

}  // namespace workbench
