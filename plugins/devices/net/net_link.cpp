#include "net_link.hpp"

#include <algorithm>
#include <arpa/inet.h>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <netdb.h>
#include <poll.h>
#include <stdexcept>
#include <sys/socket.h>
#include <unistd.h>

namespace tacta::net_device {

namespace {

constexpr int kPollMs = 5;  // how often the thread looks at its stop flag

}  // namespace

NetLink::NetLink(const std::string& address, uint16_t port, double watchdog_s, double late_s)
    : watchdog_s_(watchdog_s), late_s_(late_s) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICHOST;
  addrinfo* found = nullptr;
  const std::string service = std::to_string(port);
  const int status = getaddrinfo(address.c_str(), service.c_str(), &hints, &found);
  if (status != 0 || found == nullptr)
    throw std::invalid_argument("net: bind_address '" + address +
                                "' is not a numeric IPv4 or IPv6 address (" + gai_strerror(status) +
                                ")");
  socket_ = socket(found->ai_family, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  const int reuse = 1;
  if (socket_ >= 0) setsockopt(socket_, SOL_SOCKET, SO_REUSEADDR, &reuse, sizeof reuse);
  if (socket_ < 0 || bind(socket_, found->ai_addr, found->ai_addrlen) != 0) {
    const std::string why = std::strerror(errno);
    freeaddrinfo(found);
    if (socket_ >= 0) close(socket_);
    throw std::invalid_argument("net: cannot bind UDP " + address + ":" + service + ": " + why);
  }
  freeaddrinfo(found);
  sockaddr_storage bound{};
  socklen_t size = sizeof bound;
  getsockname(socket_, reinterpret_cast<sockaddr*>(&bound), &size);
  port_ = ntohs(bound.ss_family == AF_INET6 ? reinterpret_cast<sockaddr_in6*>(&bound)->sin6_port
                                            : reinterpret_cast<sockaddr_in*>(&bound)->sin_port);
  thread_ = std::thread([this] { serve(); });
}

NetLink::~NetLink() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  if (socket_ >= 0) close(socket_);
}

bool NetLink::wait_for_hello(double timeout_s, tnet_hello& capabilities) {
  std::unique_lock<std::mutex> lock(hello_mutex_);
  if (!hello_arrived_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                               [this] { return have_hello_; }))
    return false;
  capabilities = hello_;
  return true;
}

void NetLink::serve() noexcept {
  unsigned char buffer[512];
  while (!stop_.load(std::memory_order_relaxed)) {
    pollfd p{socket_, POLLIN, 0};
    if (poll(&p, 1, kPollMs) <= 0) continue;
    sockaddr_storage from{};
    socklen_t from_size = sizeof from;
    const ssize_t n =
        recvfrom(socket_, buffer, sizeof buffer, 0, reinterpret_cast<sockaddr*>(&from), &from_size);
    if (n < 0) continue;
    counts_.packets_in.fetch_add(1, std::memory_order_relaxed);
    handle(buffer, static_cast<size_t>(n), &from, from_size);
  }
}

void NetLink::handle(const unsigned char* data, size_t size, const void* from,
                     uint32_t from_size) noexcept {
  const double arrival = now_seconds();
  tnet_header h{};
  if (tnet_decode_header(data, size, &h) != TNET_OK || h.type == TNET_FORCE || h.session == 0) {
    counts_.malformed.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (h.session != session_) {
    // Another device (or this one restarted): it takes over only a link that is free, said BYE
    // or has been silent past the watchdog, so two bridges never fight over one device.
    const bool free =
        session_ == 0 || session_said_bye_ || arrival - session_arrival_ > watchdog_s_;
    if (!free) {
      counts_.foreign.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    session_ = h.session;
    session_said_bye_ = false;
    sequence_started_ = false;
    fastest_transit_ = 1e30;
    counts_.sessions.fetch_add(1, std::memory_order_relaxed);
  }
  const int order = tnet_sequence_check(h.sequence, newest_sequence_, sequence_started_ ? 1 : 0);
  if (order <= 0) {
    (order == 0 ? counts_.duplicates : counts_.out_of_order)
        .fetch_add(1, std::memory_order_relaxed);
    return;
  }
  const unsigned char* payload = data + TNET_HEADER_SIZE;
  tnet_hello hello{};
  tnet_state s{};
  if ((h.type == TNET_HELLO && tnet_decode_hello(payload, &hello) != TNET_OK) ||
      (h.type == TNET_STATE && tnet_decode_state(payload, &s) != TNET_OK)) {
    counts_.malformed.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  newest_sequence_ = h.sequence;
  sequence_started_ = true;
  session_arrival_ = arrival;
  std::memcpy(peer_, from, std::min<size_t>(from_size, sizeof peer_));
  peer_size_ = std::min<uint32_t>(from_size, sizeof peer_);
  if (h.type == TNET_HELLO) {
    std::lock_guard<std::mutex> lock(hello_mutex_);
    hello_ = hello;
    have_hello_ = true;
    hello_arrived_.notify_all();
    return;
  }
  std::array<double, StateSlot::kSize> v{};
  state_.load(v);  // keeps the last pose through a BYE
  if (h.type == TNET_BYE) {
    session_said_bye_ = true;
    counts_.byes.fetch_add(1, std::memory_order_relaxed);
    v[StateSlot::kBye] = 1.0;
    v[StateSlot::kSession] = static_cast<double>(session_);
    state_.store(v);
    return;
  }
  std::copy(s.position, s.position + 3, v.begin() + StateSlot::kPosition);
  std::copy(s.orientation, s.orientation + 4, v.begin() + StateSlot::kOrientation);
  std::copy(s.velocity, s.velocity + 3, v.begin() + StateSlot::kVelocity);
  v[StateSlot::kButtons] = static_cast<double>(s.buttons);
  v[StateSlot::kArrival] = arrival;
  v[StateSlot::kSession] = static_cast<double>(session_);
  v[StateSlot::kBye] = 0.0;
  state_.store(v);
  // Transit on two clocks: its minimum over the session is the offset plus the fastest path.
  const double transit = arrival - static_cast<double>(h.sender_time_ns) * 1e-9;
  fastest_transit_ = std::min(fastest_transit_, transit);
  if (transit - fastest_transit_ > late_s_) counts_.late.fetch_add(1, std::memory_order_relaxed);
  if (h.echo_time_ns != 0) {
    const uint64_t now = devices::monotonic_ns();
    if (now > h.echo_time_ns + h.echo_hold_ns)
      round_trips_.add(static_cast<double>(now - h.echo_time_ns - h.echo_hold_ns) * 1e-9);
  }
  reply(h, arrival);
}

void NetLink::reply(const tnet_header& to, double arrival) noexcept {
  std::array<double, ForceSlot::kSize> f{};
  tnet_force out{};
  out.device_state = 1;  // tacta_device_state DISCONNECTED: not answered yet
  // A force the 1 kHz path wrote for an earlier session is stale: the device gets zero until
  // the simulation has read this session's pose and answered it.
  if (force_.load(f) && static_cast<uint32_t>(f[ForceSlot::kSession]) == session_) {
    for (int a = 0; a < 3; ++a) out.force[a] = f[ForceSlot::kForce + a];
    out.energy_returned = f[ForceSlot::kReturned];
    out.energy_absorbed = f[ForceSlot::kAbsorbed];
    out.device_state = static_cast<int32_t>(f[ForceSlot::kState]);
  }
  unsigned char buffer[TNET_HEADER_SIZE + TNET_FORCE_SIZE];
  tnet_header h{};
  h.type = TNET_FORCE;
  h.session = session_;
  h.sequence = ++reply_sequence_;
  const uint64_t now = devices::monotonic_ns();
  h.sender_time_ns = now;
  h.echo_time_ns = to.sender_time_ns;
  const double hold = now_seconds() - arrival;
  h.echo_hold_ns = static_cast<uint32_t>(std::clamp(hold, 0.0, 4.0) * 1e9);
  uint32_t size = tnet_encode_header(buffer, h);
  size += tnet_encode_force(buffer + size, &out);
  if (sendto(socket_, buffer, size, 0, reinterpret_cast<const sockaddr*>(peer_), peer_size_) ==
      static_cast<ssize_t>(size))
    counts_.packets_out.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace tacta::net_device
