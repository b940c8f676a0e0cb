# s2sim_add_plugin(NAME SOURCES...): an S2Sim plugin, a MODULE library `libNAME.so` built
# against the SDK alone, with hidden symbols except the descriptor entry point. The same
# function builds S2Sim's own plugins and, installed with S2SimConfig.cmake, a third party's
# (`find_package(S2Sim)` then `s2sim_add_plugin(my_plugins a.cpp b.cpp)`).
#
# The library lands in S2SIM_PLUGIN_OUTPUT_DIR when set (S2Sim's build: build/plugins), else in
# the current binary folder; `cmake --install` puts it in <prefix>/lib/s2sim/plugins, the
# folder an s2sim-run installed in the same prefix searches.
function(s2sim_add_plugin name)
  add_library(${name} MODULE ${ARGN})
  target_link_libraries(${name} PRIVATE S2Sim::sdk)
  if(TARGET s2sim_warnings)  # S2Sim's own build: its warning set
    target_link_libraries(${name} PRIVATE s2sim_warnings)
  endif()
  set_target_properties(${name} PROPERTIES
    PREFIX "lib"
    SUFFIX ".so"
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  if(S2SIM_PLUGIN_OUTPUT_DIR)
    # $<0:> keeps multi-config generators from appending a per-configuration folder.
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${S2SIM_PLUGIN_OUTPUT_DIR}$<0:>)
  endif()
  install(TARGETS ${name} LIBRARY DESTINATION lib/s2sim/plugins)
endfunction()
