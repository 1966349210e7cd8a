// A model's evolving state as a checkpoint blob (tacta_model_api.save_state / load_state).
//
// A model lists its fields once, in a function of a StateIo&; the same list measures the blob,
// writes it, checks a blob and reads it back, so the saved and the loaded layouts cannot drift
// apart. Every blob opens with a header: a magic word, the model's name, its layout version and
// the node and element counts, so a blob from another model or another mesh is refused with a
// reason. Vectors carry their length and must match the instance's (sized at creation): a load
// never reallocates. Not for the 1 kHz path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace tacta::models {

struct StateHeader {
  const char* model;       // the plugin's name, e.g. "corotational_fem"
  uint32_t version;        // the model's blob layout, raised whenever its field list changes
  uint32_t node_count;     // of the mesh the instance was created on
  uint32_t element_count;  // tets, springs or whatever the model counts; 0 when none
};

// What a blob holds as bytes: trivially copyable types, and Eigen's fixed-size matrices and
// quaternions (plain arrays of their scalars, though Eigen declares its own copy constructors;
// a dynamic matrix owns heap memory and is not trivially destructible, so it is refused).
template <class T>
concept BlobBytes = std::is_trivially_copyable_v<T> || requires {
  typename T::Scalar;
  requires std::is_standard_layout_v<T> && std::is_trivially_destructible_v<T>;
  requires sizeof(T) % sizeof(typename T::Scalar) == 0;
};

class StateIo {
 public:
  enum class Mode { kMeasure, kWrite, kCheck, kRead };

  StateIo(Mode mode, const char* model, void* bytes, size_t size)
      : mode_(mode), model_(model), bytes_(static_cast<unsigned char*>(bytes)), size_(size) {}

  // One trivially copyable value (a counter, a flag, a double).
  template <BlobBytes T>
  void value(T& v, const char* name) {
    raw(&v, sizeof v, name);
  }
  // A vector sized at creation: its length is stored, and a load requires the same length.
  template <BlobBytes T>
  void vector(std::vector<T>& v, const char* name) {
    values(std::span<T>(v), name);
  }
  // The same for any array the instance owns (a matrix's values).
  template <BlobBytes T>
  void values(std::span<T> v, const char* name) {
    uint64_t count = v.size();
    header_value(&count, sizeof count, name);
    if (!ok()) return;
    if (count != v.size()) {
      fail(std::string("'") + name + "' holds " + std::to_string(count) +
           " values in the blob, this instance " + std::to_string(v.size()));
      return;
    }
    raw(v.data(), v.size_bytes(), name);
  }
  // The header: on a check or a read, refuses another model, layout or mesh.
  void header(const StateHeader& expected);
  // Reading: the whole blob must have been consumed.
  void finish();

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  size_t used() const { return used_; }
  const char* model() const { return model_; }
  // Whether this pass sets the instance's state (the fields may reset what the blob omits).
  bool loading() const { return mode_ == Mode::kRead; }

 private:
  void raw(void* data, size_t bytes, const char* name);
  // A value of the blob's own framing (a length, a header word): read in check mode too.
  void header_value(void* data, size_t bytes, const char* name);
  void fail(const std::string& why);
  Mode mode_;
  const char* model_;
  unsigned char* bytes_;
  size_t size_;
  size_t used_ = 0;
  std::string error_;
};

// save_state for a model whose fields(StateIo&) lists its state: returns the blob's size, and
// writes it only when capacity holds all of it.
template <class Fields>
size_t save_state_blob(const StateHeader& header, void* bytes, size_t capacity, Fields&& fields) {
  StateIo measure(StateIo::Mode::kMeasure, header.model, nullptr, 0);
  measure.header(header);
  fields(measure);
  const size_t size = measure.used();
  if (bytes == nullptr || capacity < size) return size;
  StateIo write(StateIo::Mode::kWrite, header.model, bytes, capacity);
  write.header(header);
  fields(write);
  return size;
}

// load_state: checks the whole blob first, then reads it, so a refused blob leaves the instance
// as it was. Throws std::invalid_argument with the reason.
void throw_state_error(const StateIo& io);
template <class Fields>
void load_state_blob(const StateHeader& header, const void* bytes, size_t size, Fields&& fields) {
  void* data = const_cast<void*>(bytes);  // read and check modes only read from it
  StateIo check(StateIo::Mode::kCheck, header.model, data, size);
  check.header(header);
  if (check.ok()) fields(check);
  check.finish();
  if (!check.ok()) throw_state_error(check);
  StateIo read(StateIo::Mode::kRead, header.model, data, size);
  read.header(header);
  fields(read);
  read.finish();
  if (!read.ok()) throw_state_error(read);
}

}  // namespace tacta::models
