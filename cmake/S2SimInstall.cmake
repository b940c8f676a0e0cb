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
# The runtime libraries (Simbody, FCL, Boost, GLFW, assimp...) as dpkg-shlibdeps finds them.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
include(CPack)
