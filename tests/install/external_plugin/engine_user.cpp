// Links the installed tacta::engine: makes two entities and reports them with the JSON writer.
#include <iostream>

#include "tacta/ecs.hpp"
#include "tacta/json.hpp"

int main() {
  tacta::ecs::Registry registry;
  registry.create();
  registry.create();
  tacta::JsonWriter json(std::cout, 0);
  json.begin_object().field("entities", static_cast<uint64_t>(registry.alive_count())).end_object();
  return 0;
}
