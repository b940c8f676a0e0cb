// A valid shared library that is not an S2Sim plugin: it exports a function, but not the
// descriptor entry point.

extern "C" __attribute__((visibility("default"))) int s2sim_test_not_a_plugin(void) {
  return 42;
}
