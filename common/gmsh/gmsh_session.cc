#include "gmsh_session.h"

#include <gmsh.h>

namespace workbench {

namespace {
bool initialised = false;
}

void gmsh_begin() {
  if (!initialised) {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    initialised = true;
  }
  gmsh::clear();
  gmsh::onelab::clear();
}

void gmsh_reset() {
  if (!initialised) return;
  gmsh::logger::stop();  // drops the logged messages, errors included
  gmsh::finalize();
  initialised = false;
}

}  // namespace workbench
