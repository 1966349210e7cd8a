// A mesh file named by a scene is checked before any reader sees it, so the message names the
// scene's file, line and key and says what is wrong with the path (missing, a directory).
#pragma once

#include <functional>
#include <string>

#include "tacta/error.hpp"

namespace tacta {

// Throws InputError at `where` when `path` is not a readable regular file.
void require_mesh_file(const std::string& path, const SourceLocation& where);

// Runs `load` and rethrows any InputError it throws (whose place is inside the mesh file, or a
// primitive's name) at the scene's `where`, keeping the inner message and its place.
template <class Load>
auto load_at(const SourceLocation& where, Load&& load) -> decltype(load()) {
  try {
    return load();
  } catch (const InputError& e) {
    throw InputError(where, e.what());
  } catch (const std::exception& e) {
    throw InputError(where, std::string("mesh: ") + e.what());
  }
}

}  // namespace tacta
