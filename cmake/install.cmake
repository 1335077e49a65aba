# Installs the embeddable libraries with exported targets and a package config, so that another
# CMake project can say `find_package(workbench)` and link workbench::agent, workbench::pbd (and,
# with the FEM built, workbench::fem_reference). examples/embed is such a project (ctest
# install_and_consume builds it against an installed copy).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(WORKBENCH_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/workbench)

# The libraries another code embeds, and what they link statically.
set(workbench_exported agent agent_io pbd pbd_io workbench_common workbench_gmsh workbench_tensor)
if(WORKBENCH_WITH_FEM)
  list(APPEND workbench_exported fem_result fem_reference)
endif()
install(TARGETS ${workbench_exported} EXPORT workbenchTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(dir agent/include agent/io/include pbd/include pbd/io/include common/include common/gmsh common/tensor/include fem_reference/include)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.h")
endforeach()
install(EXPORT workbenchTargets NAMESPACE workbench:: DESTINATION ${WORKBENCH_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/workbenchConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/workbenchConfig.cmake
                              INSTALL_DESTINATION ${WORKBENCH_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/workbenchConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/workbenchConfig.cmake ${PROJECT_BINARY_DIR}/workbenchConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FindGmsh.cmake
        DESTINATION ${WORKBENCH_CMAKE_DIR})

# The program; common/CMakeLists.txt installs the scripts it runs (share/workbench/). The .geo
# mesher goes where gmsh_load looks for it (kGeoMesherPath in common/gmsh/gmsh_session.h).
install(TARGETS workbench-geo-mesher RUNTIME DESTINATION libexec/workbench)
if(WORKBENCH_WITH_FEM)
  install(TARGETS workbench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
