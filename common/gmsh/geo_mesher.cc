// workbench-geo-mesher: gmsh parses and meshes one .geo here, apart from the workbench, so that a
// crash inside gmsh on a bad .geo ends this process only (gmsh_session.h, gmsh_load).
#include "gmsh_session.h"

int main(int argc, char** argv) { return workbench::geo_mesher_main(argc, argv); }
