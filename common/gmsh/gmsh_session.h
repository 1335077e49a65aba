#pragma once
// gmsh keeps global state (models, ONELAB parameters, parser variables, error counters), shared
// by every module that meshes in this process. All of them go through these two functions.
namespace workbench {

/// Initialises gmsh quietly if needed and starts from an empty model and no ONELAB parameters.
void gmsh_begin();

/// After gmsh reported an error: finalises it, so that the next gmsh_begin() starts afresh
/// (gmsh 4.8 keeps parsing state after an error in a .geo, which breaks later imports).
void gmsh_reset();

}  // namespace workbench
