# s2sim_add_plugin(NAME SOURCES...): a plugin built exactly as a third party builds one: a
# MODULE library against the SDK alone, with hidden symbols except the descriptor entry point.
function(s2sim_add_plugin name)
  add_library(${name} MODULE ${ARGN})
  target_link_libraries(${name} PRIVATE s2sim::sdk s2sim_warnings)
  set_target_properties(${name} PROPERTIES
    PREFIX "lib"
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY ${S2SIM_PLUGIN_OUTPUT_DIR})
  install(TARGETS ${name} LIBRARY DESTINATION lib/s2sim/plugins)
endfunction()
