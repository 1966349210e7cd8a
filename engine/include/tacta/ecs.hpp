// The entity-component-system core: generation-counted entity handles (ecs/entity.hpp), dense
// component pools (ecs/pool.hpp), the Registry that owns them (ecs/registry.hpp) and views over
// one or more component types (ecs/view.hpp). Systems are plain functions over views.
#pragma once

#include "tacta/ecs/entity.hpp"
#include "tacta/ecs/pool.hpp"
#include "tacta/ecs/registry.hpp"
#include "tacta/ecs/view.hpp"
