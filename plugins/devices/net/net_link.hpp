// The net device's UDP endpoint and the thread that serves it: receives HELLO, STATE and BYE
// datagrams (tacta_net_protocol.h), drops malformed, duplicate, out-of-order and foreign-session
// ones and counts them, hands the newest state to the 1 kHz path through a lock-free slot, and
// answers every accepted STATE with the newest force the 1 kHz path left in its own slot.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "tacta_devices/monotonic_clock.hpp"
#include "tacta_devices/round_trip_log.hpp"
#include "tacta_devices/seqlock_slot.hpp"
#include "tacta_net_protocol.h"

namespace tacta::net_device {

// Steady (monotonic) clock, s; the same clock the clients stamp with.
inline double now_seconds() noexcept { return devices::monotonic_seconds(); }

// Newest accepted state: position 3, orientation 4, velocity 3, buttons, arrival (s), session,
// said_bye (1 after BYE).
struct StateSlot {
  enum {
    kPosition = 0,
    kOrientation = 3,
    kVelocity = 7,
    kButtons = 10,
    kArrival = 11,
    kSession = 12,
    kBye = 13,
    kSize = 14
  };
};
// Newest force: force 3, energy returned and absorbed (J), device state, session it is for.
struct ForceSlot {
  enum { kForce = 0, kReturned = 3, kAbsorbed = 4, kState = 5, kSession = 6, kSize = 7 };
};

struct LinkCounts {
  std::atomic<uint64_t> packets_in{0}, packets_out{0};
  std::atomic<uint64_t> malformed{0}, duplicates{0}, out_of_order{0}, foreign{0};
  std::atomic<uint64_t> late{0}, sessions{0}, byes{0};
};

class NetLink {
 public:
  // Binds (port 0: an ephemeral one); throws std::invalid_argument naming the address on failure.
  // `watchdog_s`: a silent session may be taken over by another device after it. `late_s`: an
  // accepted STATE whose transit exceeds the session's fastest by more than this is counted late.
  NetLink(const std::string& address, uint16_t port, double watchdog_s, double late_s);
  ~NetLink();
  NetLink(const NetLink&) = delete;
  NetLink& operator=(const NetLink&) = delete;

  uint16_t port() const noexcept { return port_; }
  // Blocks (not the 1 kHz path) until a HELLO arrived or `timeout_s` passed; false on timeout.
  bool wait_for_hello(double timeout_s, tnet_hello& capabilities);

  devices::SeqlockSlot<StateSlot::kSize>& state() noexcept { return state_; }
  devices::SeqlockSlot<ForceSlot::kSize>& force() noexcept { return force_; }
  const LinkCounts& counts() const noexcept { return counts_; }
  const devices::RoundTripLog& round_trips() const noexcept { return round_trips_; }

 private:
  void serve() noexcept;
  void handle(const unsigned char* data, size_t size, const void* from,
              uint32_t from_size) noexcept;
  void reply(const tnet_header& to, double arrival) noexcept;

  int socket_ = -1;
  uint16_t port_ = 0;
  double watchdog_s_, late_s_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  devices::SeqlockSlot<StateSlot::kSize> state_;
  devices::SeqlockSlot<ForceSlot::kSize> force_;
  LinkCounts counts_;
  devices::RoundTripLog round_trips_;
  std::mutex hello_mutex_;
  std::condition_variable hello_arrived_;
  bool have_hello_ = false;
  tnet_hello hello_{};
  // Network thread only: the session it serves and where its datagrams come from.
  uint32_t session_ = 0, newest_sequence_ = 0, reply_sequence_ = 0;
  bool sequence_started_ = false, session_said_bye_ = false;
  double session_arrival_ = 0;     // s, newest accepted datagram of the session
  double fastest_transit_ = 1e30;  // s, sender clock to ours (offset included)
  unsigned char peer_[128] = {0};
  uint32_t peer_size_ = 0;
};

}  // namespace tacta::net_device
