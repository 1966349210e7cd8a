// tacta: the command line. Placeholder until the run, plugins and mesh-info commands land.
int main() { return 0; }
