#pragma once
// One case file describes one study for every model: each subcommand (and the Python module)
// checks every section with its module's reader, then rejects whatever no module knows.
#include <workbench/case_file.h>

namespace schema {

/// Reads (and so checks) the shared study sections, [agent], [fem], [compare] and [pbd] of `file`,
/// then throws for any key no reader took (workbench::Error "file: key: reason").
void check_every_section(const workbench::CaseFile& file);

}  // namespace schema
