// The shared library test_absent_dependency links against; never on the loader's path.
int tacta_test_absent_dep_value() { return 7; }
