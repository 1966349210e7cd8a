// Runs a function in a forked child process and returns the bytes it produced. For libraries
// with global state that outlives their own reset (Gmsh meshes one surface differently on a
// second call in a process) or that may crash on bad input: the child starts from the parent's
// clean state every time, and a crash or hang there becomes an InputError here.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tacta::mesh_detail {

// work returns its result as bytes, or throws (its message becomes the InputError's). Throws
// InputError naming source when the child fails, crashes, or runs past timeout_s seconds.
std::string call_isolated(const std::function<std::string()>& work, const std::string& source,
                          double timeout_s);

// Flat arrays in and out of a byte string: a count, then the raw elements.
template <class T>
void append_array(std::string& out, const std::vector<T>& values) {
  const uint64_t count = values.size();
  out.append(reinterpret_cast<const char*>(&count), sizeof count);
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}
template <class T>
std::vector<T> take_array(const std::string& in, size_t& at) {
  uint64_t count = 0;
  if (in.size() < at + sizeof count) return {};
  in.copy(reinterpret_cast<char*>(&count), sizeof count, at);
  at += sizeof count;
  if (count > (in.size() - at) / sizeof(T)) return {};
  std::vector<T> values(count);
  in.copy(reinterpret_cast<char*>(values.data()), count * sizeof(T), at);
  at += count * sizeof(T);
  return values;
}

}  // namespace tacta::mesh_detail
