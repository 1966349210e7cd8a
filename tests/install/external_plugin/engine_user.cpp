// Links the installed tacta::engine: makes two entities and reports how many are alive.
#include <iostream>

#include "tacta/ecs.hpp"

int main() {
  tacta::ecs::Registry registry;
  registry.create();
  registry.create();
  std::cout << "{\"entities\":" << registry.alive_count() << "}\n";
  return 0;
}
