// Test plugin: a shared library that exports something, but not tacta_plugin_entry.
#include "tacta/plugin.h"

extern "C" TACTA_EXPORT int tacta_not_the_entry(void) { return 42; }
