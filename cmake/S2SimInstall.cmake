# What `cmake --install` adds besides the targets' own install rules (the apps in bin/, the
# plugins in lib/s2sim/plugins/, the headers in include/, libs2sim.so in lib/): the CMake
# package (S2SimConfig.cmake, its version file, the exported S2Sim::sdk and S2Sim::s2sim,
# s2sim_add_plugin), the pkg-config file, and the Debian package (cpack -G DEB). Every path in
# them is relative to the prefix, so an install can be moved or unpacked anywhere.
include(CMakePackageConfigHelpers)

set(S2SIM_CMAKE_INSTALL_DIR lib/cmake/S2Sim)
install(EXPORT S2SimTargets NAMESPACE S2Sim:: DESTINATION ${S2SIM_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/S2SimConfig.cmake.in
  ${PROJECT_BINARY_DIR}/S2SimConfig.cmake
  INSTALL_DESTINATION ${S2SIM_CMAKE_INSTALL_DIR})
# 0.x: a minor version changes the plugin ABI, so only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/S2SimConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/S2SimConfig.cmake ${PROJECT_BINARY_DIR}/S2SimConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/S2SimPlugin.cmake
  DESTINATION ${S2SIM_CMAKE_INSTALL_DIR})

configure_file(${PROJECT_SOURCE_DIR}/cmake/s2sim.pc.in ${PROJECT_BINARY_DIR}/s2sim.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/s2sim.pc DESTINATION lib/pkgconfig)

# The scenes, the examples and the docs, so that an install runs without the source tree:
# `s2sim-run default` finds <prefix>/share/s2sim/scenes/default (apps/common/scene_search.hpp),
# and the Python examples, in share/s2sim/examples/python, find the scenes two folders up as in
# the source tree.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION share/s2sim/scenes)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/ DESTINATION share/s2sim/examples)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/python/examples/ DESTINATION share/s2sim/examples/python)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION share/doc/s2sim)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION share/doc/s2sim/docs)

# The Debian package: `cpack -G DEB --config build/CPackConfig.cmake` (README, "Install").
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME s2sim)
set(CPACK_PACKAGE_VENDOR "S2Sim")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "S2Sim robot simulator: runner, viewer, plugins, SDK and the embeddable library")
set(CPACK_PACKAGE_CONTACT "S2Sim developers <s2sim@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
# The package and cpack's staging install go to build/package wherever cpack is run from (the
# README runs it from the source tree, which it must leave untouched); -B chooses another.
set(CPACK_PACKAGE_DIRECTORY ${PROJECT_BINARY_DIR}/package)
# The runtime libraries (Simbody, FCL, Boost, GLFW, assimp...) as dpkg-shlibdeps finds them.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# What dpkg-shlibdeps cannot see: the Python module is built for one CPython (its ABI tag) and
# imports numpy; SimTwo projects' scripts compile with Free Pascal (addr2line from binutils
# names a script's failing line). CPack adds the libraries' dependencies to these.
if(TARGET s2sim_python)
  find_package(Python COMPONENTS Interpreter REQUIRED)
  set(S2SIM_PYTHON_MINOR ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR})
  math(EXPR S2SIM_PYTHON_NEXT_MINOR "${Python_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= ${S2SIM_PYTHON_MINOR}), python3 (<< ${Python_VERSION_MAJOR}.${S2SIM_PYTHON_NEXT_MINOR}), python3-numpy")
  set(CPACK_DEBIAN_PACKAGE_SUGGESTS "python3-dask, python3-distributed")
endif()
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "fpc, binutils")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
include(CPack)
