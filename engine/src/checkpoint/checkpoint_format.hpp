// The checkpoint's bytes: a versioned header (magic, format version, engine ABI id, the scene's
// fingerprint, a checksum of the rest) and tagged sections with lengths. The writer appends; the
// reader is bounded (a checkpoint is untrusted input): every length is checked against what is
// left and every mismatch is an InputError that says what did not match.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "tacta/error.hpp"
#include "text/digest.hpp"

namespace tacta {

inline constexpr char kCheckpointMagic[8] = {'T', 'A', 'C', 'T', 'A', 'C', 'K', 'P'};
inline constexpr uint32_t kCheckpointVersion = 2;  // 2: cut bodies' shapes, blades' sweeps
// magic, version, engine ABI id, fingerprint, tick, checksum, payload length.
inline constexpr size_t kCheckpointHeaderBytes = 8 + 4 + 8 + 8 + 8 + 8 + 8;

class CheckpointWriter {
 public:
  template <class T>
  void pod(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "raw bytes only for plain data");
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>, "raw bytes only for plain data");
    pod(static_cast<uint64_t>(values.size()));
    const auto* p = reinterpret_cast<const uint8_t*>(values.data());
    bytes_.insert(bytes_.end(), p, p + values.size() * sizeof(T));
  }
  void text(const std::string& s);
  void blob(std::span<const uint8_t> data);
  // A section: a tag, then its length, filled in by end_section.
  size_t begin_section(uint32_t tag);
  void end_section(size_t at);
  std::vector<uint8_t>& bytes() noexcept { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

class CheckpointReader {
 public:
  // `where` names the input in errors (the file, or "checkpoint bytes").
  CheckpointReader(std::span<const uint8_t> bytes, std::string where, std::string context = {})
      : bytes_(bytes), where_(std::move(where)), context_(std::move(context)) {}

  template <class T>
  T pod(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>, "raw bytes only for plain data");
    T value;
    std::memcpy(&value, take(sizeof(T), what), sizeof(T));
    return value;
  }
  template <class T>
  void pod_into(T& value, const char* what) {
    value = pod<T>(what);
  }
  // An array whose length the scene fixes: a different count is refused naming both.
  template <class T>
  void array_exact(std::vector<T>& values, const char* what) {
    const uint64_t n = pod<uint64_t>(what);
    if (n != values.size())
      fail(std::string(what) + ": " + std::to_string(n) + " in the checkpoint, " +
           std::to_string(values.size()) + " in the scene");
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T), what), n * sizeof(T));
  }
  // An array of any length up to `limit` (records, loads that may be empty).
  template <class T>
  std::vector<T> array(const char* what, uint64_t limit) {
    const uint64_t n = pod<uint64_t>(what);
    if (n > limit || n > left() / sizeof(T))
      fail(std::string(what) + ": " + std::to_string(n) + " entries do not fit in what is left");
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T), what), n * sizeof(T));
    return values;
  }
  std::string text(const char* what);
  std::span<const uint8_t> blob(const char* what);
  static constexpr uint32_t kAnySection = 0xffffffffu;
  // The next section, which must carry `tag` (or any, kAnySection); its reader is bounded to its
  // length.
  CheckpointReader section(uint32_t tag, const std::string& context);
  // Everything of this section was read (a longer section is from another layout).
  void expect_end();
  size_t left() const noexcept { return bytes_.size() - pos_; }
  [[noreturn]] void fail(const std::string& message) const;

 private:
  const uint8_t* take(uint64_t n, const char* what);
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
  std::string where_, context_;
};

struct CheckpointHeader {
  uint32_t version = 0;
  uint64_t engine_abi = 0;
  uint64_t fingerprint = 0;
  uint64_t tick = 0;
};

// Checks magic, version, length and checksum; returns the header and the payload after it.
// Throws InputError naming what did not match. Reads nothing past `bytes`.
CheckpointHeader read_checkpoint_header(std::span<const uint8_t> bytes, const std::string& where,
                                        std::span<const uint8_t>& payload);
// Header + payload.
std::vector<uint8_t> frame_checkpoint(const CheckpointHeader& header,
                                      const std::vector<uint8_t>& payload);
// Walks the payload's sections (tag, length) without knowing them: every length within bounds.
// Returns how many there are; throws InputError otherwise. What the fuzzer drives.
size_t count_checkpoint_sections(std::span<const uint8_t> payload, const std::string& where);

uint64_t engine_abi_id() noexcept;

}  // namespace tacta
