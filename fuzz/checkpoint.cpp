// Fuzzes the checkpoint reader's framing (engine/src/checkpoint/checkpoint_format.hpp): the
// header (magic, version, ABI id, lengths, checksum) and the walk over tagged sections with
// lengths, which every restore goes through before it reads a section's content. The walk is
// driven on the bytes after the header whether or not the checksum matches, so the fuzzer
// reaches it without forging one.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "checkpoint/checkpoint_format.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::span<const uint8_t> bytes(data, size);
  std::span<const uint8_t> payload;
  try {
    (void)tacta::read_checkpoint_header(bytes, "fuzz.ckpt", payload);
  } catch (const tacta::InputError&) {
  }
  try {
    (void)tacta::count_checkpoint_sections(
        bytes.subspan(std::min(size, tacta::kCheckpointHeaderBytes)), "fuzz.ckpt");
  } catch (const tacta::InputError&) {
  }
  return 0;
}
