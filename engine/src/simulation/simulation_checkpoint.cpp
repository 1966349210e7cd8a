// Simulation's checkpoint and restore (simulation.hpp): the header and fingerprint
// (checkpoint/checkpoint_format.hpp), then bodies, devices, haptic channels, clock and records.
#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "checkpoint/checkpoint_format.hpp"
#include "checkpoint/world_state.hpp"
#include "simulation/simulation_impl.hpp"

namespace tacta {

namespace {

constexpr const char* kBytesName = "checkpoint bytes";  // the input's name in errors

}  // namespace

std::vector<uint8_t> Simulation::save_state() const {
  Impl& impl = *impl_;
  const SourceLocation where{impl.world.scene().path, 0, 0, "checkpoint"};
  if (impl.running.load()) throw InputError(where, "save_state between steps only, not in run()");
  ClockSession& session = impl.session();
  CheckpointWriter out;
  save_bodies(out, impl.world, {impl.requested_models, impl.requested_params});
  impl.checkpoint_notes = save_devices(out, impl.world);
  out.pod(static_cast<uint8_t>(impl.haptics != nullptr));
  if (impl.haptics) impl.haptics->save_state(out);
  out.pod(impl.collision ? impl.collision->proxy_counters() : std::array<uint64_t, 3>{});
  session.save_state(out);
  return frame_checkpoint(
      {kCheckpointVersion, engine_abi_id(), scene_fingerprint(impl.world), session.tick()},
      out.bytes());
}

void Simulation::restore_state(std::span<const uint8_t> bytes) {
  Impl& impl = *impl_;
  const std::string& scene = impl.world.scene().path;
  if (impl.running.load())
    throw InputError({scene, 0, 0, "checkpoint"}, "restore_state between steps only, not in run()");
  std::span<const uint8_t> payload;
  const CheckpointHeader header = read_checkpoint_header(bytes, kBytesName, payload);
  const uint64_t fingerprint = scene_fingerprint(impl.world);
  CheckpointReader in(payload, kBytesName);
  if (header.fingerprint != fingerprint)
    in.fail("it is for another scene (fingerprint " + hex64(header.fingerprint) +
            "), this scene '" + impl.world.scene().name + "' (" + scene + ") is " +
            hex64(fingerprint) + ": bodies, devices, models, parameters or rates differ");
  // The session first: building it calls each model's begin(); the saved state comes after and
  // no begin() follows it.
  const bool fresh = !impl.clock || impl.clock->tick() == 0;
  ClockSession& session = impl.session();
  if (fresh && impl.collision) impl.collision->build_as_at_start(dt());
  // The scene's timed events the saved run took (bodies in or out, tool changes), as its ticks
  // took them; the saved presence and state then come over them.
  if (header.tick > 0)
    impl.world.apply_entity_commands(static_cast<double>(header.tick - 1) * dt());
  for (size_t slot :
       load_bodies(in, impl.world, impl.plugins, {impl.requested_models, impl.requested_params})) {
    if (impl.collision) impl.collision->replace_surface(slot);
    if (impl.haptics) impl.haptics->surface_changed(impl.world, slot);
    session.body_reshaped(slot);
  }
  impl.checkpoint_notes = load_devices(in, impl.world);
  const bool had_haptics = in.pod<uint8_t>("whether haptics ran") != 0;
  if (had_haptics != (impl.haptics != nullptr))
    in.fail("haptic channels in the checkpoint and in the scene differ");
  if (impl.haptics) impl.haptics->load_state(in);
  const auto counters = in.pod<std::array<uint64_t, 3>>("the proxy refit counters");
  if (impl.collision) impl.collision->set_proxy_counters(counters);
  session.load_state(in);
  in.expect_end();
  // The saved run had made (or been refused) every cut due by its time: its bodies' shapes came
  // with it.
  impl.scene_cuts->skip_past(session.time());
}

void Simulation::save_state(const std::string& path) const {
  const std::vector<uint8_t> bytes = save_state();
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  if (!file) throw InputError({path, 0, 0, "checkpoint"}, "cannot write the checkpoint file");
}

// Far above any checkpoint a scene that steps at 1 kHz can have (the demo's is 0.3 MB, its records
// included), and below what reading it whole could not allocate.
constexpr uintmax_t kMaxCheckpointBytes = uintmax_t{1} << 30;

void Simulation::restore_state(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw InputError({path, 0, 0, "checkpoint"}, "no checkpoint file there (not a regular file)");
  if (const uintmax_t size = std::filesystem::file_size(path, error);
      !error && size > kMaxCheckpointBytes)
    throw InputError({path, 0, 0, "checkpoint"},
                     "the file is " + std::to_string(size >> 20) +
                         " MiB, larger than any checkpoint (at most 1024 MiB)");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError({path, 0, 0, "checkpoint"}, "cannot open the checkpoint file");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                   std::istreambuf_iterator<char>());
  try {
    restore_state(std::span<const uint8_t>(bytes));
  } catch (const InputError& e) {
    // The file's name in the message instead of the bytes'.
    std::string message = e.what();
    const std::string prefix = std::string(kBytesName) + ": ";
    if (message.starts_with(prefix)) message.erase(0, prefix.size());
    throw InputError({path, 0, 0, ""}, message);
  }
}

const std::vector<std::string>& Simulation::checkpoint_notes() const noexcept {
  return impl_->checkpoint_notes;
}

}  // namespace tacta
