#include "tacta/models/state_blob.hpp"

#include <stdexcept>

namespace tacta::models {

namespace {
constexpr uint32_t kMagic = 0x54534D43u;  // "CMST" little-endian: a Tacta model state blob
}

void StateIo::fail(const std::string& why) {
  if (error_.empty()) error_ = why;
}

void StateIo::raw(void* data, size_t bytes, const char* name) {
  if (!ok()) return;
  if (mode_ != Mode::kMeasure && (used_ > size_ || bytes > size_ - used_)) {
    fail(std::string("the blob ends (") + std::to_string(size_) + " bytes) inside '" + name + "'");
    return;
  }
  // An empty field (an unused vector: its data() may be null) copies nothing; memcpy must not see
  // a null pointer even for 0 bytes.
  if (bytes > 0 && mode_ == Mode::kWrite) std::memcpy(bytes_ + used_, data, bytes);
  if (bytes > 0 && mode_ == Mode::kRead) std::memcpy(data, bytes_ + used_, bytes);
  used_ += bytes;
}

void StateIo::header_value(void* data, size_t bytes, const char* name) {
  const Mode mode = mode_;
  if (mode_ == Mode::kCheck) mode_ = Mode::kRead;
  raw(data, bytes, name);
  mode_ = mode;
}

void StateIo::header(const StateHeader& expected) {
  uint32_t magic = kMagic;
  header_value(&magic, sizeof magic, "magic");
  if (ok() && magic != kMagic) return fail("not a model state blob (wrong magic word)");
  const std::string own = expected.model;
  uint32_t name_length = static_cast<uint32_t>(own.size());
  header_value(&name_length, sizeof name_length, "model name");
  if (!ok()) return;
  std::string name = own;
  if (mode_ == Mode::kCheck || mode_ == Mode::kRead) {
    if (name_length > size_ - used_) return fail("the blob ends inside the model name");
    name.assign(reinterpret_cast<const char*>(bytes_ + used_), name_length);
  }
  header_value(name.data(), name.size(), "model name");
  if (ok() && name != own) return fail("the blob holds the state of model '" + name + "'");
  uint32_t fields[3] = {expected.version, expected.node_count, expected.element_count};
  header_value(fields, sizeof fields, "header");
  if (!ok()) return;
  if (fields[0] != expected.version)
    return fail("blob layout version " + std::to_string(fields[0]) + ", this build reads " +
                std::to_string(expected.version));
  if (fields[1] != expected.node_count || fields[2] != expected.element_count)
    return fail("the blob is of a mesh of " + std::to_string(fields[1]) + " nodes and " +
                std::to_string(fields[2]) + " elements, this instance's has " +
                std::to_string(expected.node_count) + " and " +
                std::to_string(expected.element_count));
}

void StateIo::finish() {
  if (ok() && (mode_ == Mode::kCheck || mode_ == Mode::kRead) && used_ != size_)
    fail("the blob has " + std::to_string(size_ - used_) + " bytes past its last field");
}

void throw_state_error(const StateIo& io) {
  throw std::invalid_argument(std::string(io.model()) + " load_state: " + io.error());
}

}  // namespace tacta::models
