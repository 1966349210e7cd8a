#include "checkpoint/checkpoint_format.hpp"

#include "tacta/plugin.h"

namespace tacta {

uint64_t engine_abi_id() noexcept { return TACTA_ABI_ID; }

void CheckpointWriter::text(const std::string& s) {
  pod(static_cast<uint64_t>(s.size()));
  bytes_.insert(bytes_.end(), s.begin(), s.end());
}

void CheckpointWriter::blob(std::span<const uint8_t> data) {
  pod(static_cast<uint64_t>(data.size()));
  bytes_.insert(bytes_.end(), data.begin(), data.end());
}

size_t CheckpointWriter::begin_section(uint32_t tag) {
  pod(tag);
  const size_t at = bytes_.size();
  pod(uint64_t{0});
  return at;
}

void CheckpointWriter::end_section(size_t at) {
  const uint64_t length = bytes_.size() - at - sizeof(uint64_t);
  std::memcpy(bytes_.data() + at, &length, sizeof length);
}

void CheckpointReader::fail(const std::string& message) const {
  throw InputError({where_, 0, 0, ""}, context_.empty() ? message : context_ + ": " + message);
}

const uint8_t* CheckpointReader::take(uint64_t n, const char* what) {
  if (n > left())
    fail(std::string("truncated: ") + what + " needs " + std::to_string(n) + " bytes, " +
         std::to_string(left()) + " left");
  const uint8_t* p = bytes_.data() + pos_;
  pos_ += n;
  return p;
}

std::string CheckpointReader::text(const char* what) {
  const uint64_t n = pod<uint64_t>(what);
  if (n > left()) fail(std::string("truncated: ") + what + " is longer than what is left");
  const auto* p = reinterpret_cast<const char*>(take(n, what));
  return std::string(p, p + n);
}

std::span<const uint8_t> CheckpointReader::blob(const char* what) {
  const uint64_t n = pod<uint64_t>(what);
  if (n > left()) fail(std::string("truncated: ") + what + " is longer than what is left");
  return {take(n, what), n};
}

CheckpointReader CheckpointReader::section(uint32_t tag, const std::string& context) {
  const auto found = pod<uint32_t>("a section tag");
  if (tag != kAnySection && found != tag)
    fail("expected section " + std::to_string(tag) + " (" + context + "), found section " +
         std::to_string(found));
  const auto length = pod<uint64_t>("a section length");
  if (length > left())
    fail("truncated: section " + context + " says " + std::to_string(length) + " bytes, " +
         std::to_string(left()) + " left");
  return CheckpointReader(std::span<const uint8_t>(take(length, "a section"), length), where_,
                          context);
}

void CheckpointReader::expect_end() {
  if (left() != 0)
    fail(std::to_string(left()) + " bytes more than this engine reads (another layout)");
}

std::vector<uint8_t> frame_checkpoint(const CheckpointHeader& header,
                                      const std::vector<uint8_t>& payload) {
  CheckpointWriter w;
  for (char c : kCheckpointMagic) w.pod(c);
  w.pod(kCheckpointVersion);
  w.pod(header.engine_abi);
  w.pod(header.fingerprint);
  w.pod(header.tick);
  w.pod(fnv1a64(payload.data(), payload.size()));
  w.pod(static_cast<uint64_t>(payload.size()));
  std::vector<uint8_t> out = std::move(w.bytes());
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

CheckpointHeader read_checkpoint_header(std::span<const uint8_t> bytes, const std::string& where,
                                        std::span<const uint8_t>& payload) {
  CheckpointReader r(bytes, where);
  if (bytes.size() < sizeof kCheckpointMagic ||
      std::memcmp(bytes.data(), kCheckpointMagic, sizeof kCheckpointMagic) != 0)
    r.fail("not a Tacta checkpoint (expected the magic TACTACKP at its start)");
  for (size_t i = 0; i < sizeof kCheckpointMagic; ++i) r.pod<char>("the magic");
  CheckpointHeader h;
  h.version = r.pod<uint32_t>("the format version");
  if (h.version > kCheckpointVersion)
    r.fail("version " + std::to_string(h.version) + " is newer than this engine's " +
           std::to_string(kCheckpointVersion));
  if (h.version != kCheckpointVersion)
    r.fail("version " + std::to_string(h.version) + " is older than this engine's " +
           std::to_string(kCheckpointVersion) + " and no longer read");
  h.engine_abi = r.pod<uint64_t>("the engine ABI id");
  if (h.engine_abi != engine_abi_id())
    r.fail("written by an engine with ABI id " + hex64(h.engine_abi) + ", this engine is " +
           hex64(engine_abi_id()));
  h.fingerprint = r.pod<uint64_t>("the scene fingerprint");
  h.tick = r.pod<uint64_t>("the tick");
  const auto checksum = r.pod<uint64_t>("the checksum");
  const auto length = r.pod<uint64_t>("the payload length");
  if (length != r.left())
    r.fail("truncated or extended: the header says " + std::to_string(length) +
           " bytes of state, the input has " + std::to_string(r.left()));
  payload = bytes.subspan(kCheckpointHeaderBytes);
  if (fnv1a64(payload.data(), payload.size()) != checksum)
    r.fail("damaged: the checksum of its " + std::to_string(length) +
           " bytes of state does not match the header's");
  return h;
}

size_t count_checkpoint_sections(std::span<const uint8_t> payload, const std::string& where) {
  CheckpointReader r(payload, where);
  size_t count = 0;
  while (r.left() > 0) {
    r.section(CheckpointReader::kAnySection, "section " + std::to_string(count));
    ++count;
  }
  return count;
}

}  // namespace tacta
