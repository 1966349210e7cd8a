/* Tacta net device client: bridge a real haptic device to a Tacta simulation over UDP from the
 * vendor SDK's own loop. Header-only C99 on POSIX sockets, no other dependency. Copy this file
 * and tacta_net_protocol.h next to your bridge; link with -lm (libc's maths). docs/DEVICES.md shows a whole bridge.
 *
 *   tacta_net_device dev;
 *   tnet_hello caps = {...};                       // your device's workspace, peak force, ...
 *   if (tacta_net_open(&dev, "127.0.0.1", 18950, &caps, err, sizeof err) != 0) fail(err);
 *   every servo tick (1 kHz):
 *     tacta_net_send_state(&dev, &state);          // pose, velocity, buttons
 *     tacta_net_poll(&dev);                        // drains forces that arrived
 *     tacta_net_force(&dev, force);                // zero when the simulation fell silent
 *     tacta_net_passivity_filter(&dev.passivity, state.velocity, dt,
 *                                tacta_net_remote_budget(&dev), force, caps.peak_force, force);
 *     vendor_set_force(force);
 *   tacta_net_close(&dev);                         // says BYE
 *
 * Passivity under delay (time-domain passivity on the delayed two-port, after Ryu, Artigas
 * and Preusche, Mechatronics 20(7), 2010): the energy the device returns to the hand is kept
 * below both the energy the hand has put in (one-port ledger, observed with sampled power
 * f(n).v(n) dt as in Hannaford and Ryu 2002) and the energy the simulated environment has
 * returned into the link (`energy_returned` of the newest FORCE datagram, which arrives one
 * delay late). Any excess is removed by a damper along the velocity, just large enough.
 */
#ifndef TACTA_NET_DEVICE_H
#define TACTA_NET_DEVICE_H

#include <arpa/inet.h>
#include <errno.h>
#include <math.h>
#include <netdb.h>
#include <stdio.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "tacta_net_protocol.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tacta_net_passivity {
  double energy_in;   /* J: work the hand did against the device's force */
  double energy_out;  /* J: work the device's force did on the hand */
  double dissipated;  /* J: removed by the controller's damper */
  int use_remote;     /* 1: also bound by the environment's returned energy (two-port) */
} tacta_net_passivity;

typedef struct tacta_net_device {
  int socket;
  struct sockaddr_storage peer;
  socklen_t peer_size;
  uint32_t session, sequence;
  tnet_hello hello;
  uint64_t last_hello_ns;
  tnet_force force;            /* newest accepted FORCE */
  int have_force;
  uint32_t force_sequence;
  uint64_t force_sender_ns;    /* its sender_time_ns, echoed back */
  uint64_t force_received_ns;  /* local clock when it arrived */
  double watchdog_s;           /* silence longer than this: zero force (default 0.05 s) */
  double round_trip_s;         /* newest measured round trip, -1 before any */
  uint64_t sent, received, dropped, malformed;
  tacta_net_passivity passivity;
} tacta_net_device;

static inline uint64_t tacta_net_now_ns(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (uint64_t)t.tv_sec * 1000000000ull + (uint64_t)t.tv_nsec;
}

static inline void tacta_net_passivity_reset(tacta_net_passivity* p) {
  p->energy_in = p->energy_out = p->dissipated = 0.0;
  p->use_remote = 1;
}

/* J, >= 0 at every tick while the controller runs: what the hand put in minus what it got back. */
static inline double tacta_net_passivity_ledger(const tacta_net_passivity* p) {
  return p->energy_in - p->energy_out;
}

/* The force to apply this tick: `desired` (N) with just enough damping along `velocity` (m/s)
 * that the energy returned to the hand stays within budget, then limited to `peak` (N).
 * `remote_budget` (J) is the environment's returned energy (tacta_net_remote_budget). */
static inline void tacta_net_passivity_filter(tacta_net_passivity* p, const double velocity[3], double dt,
                                              double remote_budget, const double desired[3], double peak,
                                              double out[3]) {
  double f[3] = {desired[0], desired[1], desired[2]};
  double bound = p->energy_in, power, speed2, magnitude2, remaining;
  int i;
  if (p->use_remote && remote_budget < bound) bound = remote_budget;
  power = f[0] * velocity[0] + f[1] * velocity[1] + f[2] * velocity[2];
  speed2 = velocity[0] * velocity[0] + velocity[1] * velocity[1] + velocity[2] * velocity[2];
  /* J left to return, aimed a hair under (relative 1e-9, and 1e-12 of |f||v|dt) so that rounding
   * in the damper never takes the ledger below zero */
  remaining = (bound - p->energy_out) * (1.0 - 1e-9) -
              1e-12 * sqrt((f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) * speed2) * dt;
  if (dt > 0.0 && power * dt > remaining) {
    const double excess = power * dt - remaining; /* J, > 0 */
    if (speed2 > 1e-18) {
      const double alpha = excess / (speed2 * dt); /* N s/m */
      for (i = 0; i < 3; ++i) f[i] -= alpha * velocity[i];
      p->dissipated += excess;
    } else {
      f[0] = f[1] = f[2] = 0.0;
    }
  }
  magnitude2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
  if (!(magnitude2 <= peak * peak)) { /* also catches NaN */
    const double scale = magnitude2 > 0.0 && magnitude2 < 1e300 ? peak / sqrt(magnitude2) : 0.0;
    for (i = 0; i < 3; ++i) f[i] *= scale;
  }
  power = f[0] * velocity[0] + f[1] * velocity[1] + f[2] * velocity[2];
  if (power > 0.0) p->energy_out += power * dt;
  else p->energy_in -= power * dt;
  for (i = 0; i < 3; ++i) out[i] = f[i];
}

static inline int tacta_net_send_datagram(tacta_net_device* d, uint32_t type, const void* payload) {
  unsigned char buffer[TNET_MAX_DATAGRAM];
  tnet_header h;
  uint32_t size;
  const uint64_t now = tacta_net_now_ns();
  memset(&h, 0, sizeof h);
  h.type = (uint16_t)type;
  h.session = d->session;
  h.sequence = ++d->sequence;
  h.sender_time_ns = now;
  if (d->have_force) {
    const uint64_t hold = now - d->force_received_ns;
    h.echo_time_ns = d->force_sender_ns;
    h.echo_hold_ns = hold > 0xFFFFFFFFull ? 0xFFFFFFFFu : (uint32_t)hold;
  }
  size = tnet_encode_header(buffer, h);
  if (type == TNET_HELLO) size += tnet_encode_hello(buffer + size, (const tnet_hello*)payload);
  if (type == TNET_STATE) size += tnet_encode_state(buffer + size, (const tnet_state*)payload);
  if (sendto(d->socket, buffer, size, 0, (const struct sockaddr*)&d->peer, d->peer_size) != (ssize_t)size) return -1;
  ++d->sent;
  d->last_hello_ns = type == TNET_HELLO ? now : d->last_hello_ns;
  return 0;
}

/* Opens a non-blocking UDP socket towards the simulation and says HELLO with `capabilities`.
 * 0 on success; -1 with a reason in `error`. */
static inline int tacta_net_open(tacta_net_device* d, const char* host, uint16_t port, const tnet_hello* capabilities,
                                 char* error, size_t error_capacity) {
  struct addrinfo hints, *found = NULL;
  char service[8];
  int status;
  memset(d, 0, sizeof *d);
  d->socket = -1;
  d->hello = *capabilities;
  d->watchdog_s = 0.05;
  d->round_trip_s = -1.0;
  d->session = (uint32_t)(tacta_net_now_ns() ^ ((uint64_t)getpid() << 16)) | 1u;
  tacta_net_passivity_reset(&d->passivity);
  memset(&hints, 0, sizeof hints);
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  snprintf(service, sizeof service, "%u", (unsigned)port);
  status = getaddrinfo(host, service, &hints, &found);
  if (status != 0 || found == NULL) {
    snprintf(error, error_capacity, "cannot resolve %s: %s", host, gai_strerror(status));
    return -1;
  }
  d->socket = socket(found->ai_family, SOCK_DGRAM | SOCK_NONBLOCK, 0);
  memcpy(&d->peer, found->ai_addr, found->ai_addrlen);
  d->peer_size = (socklen_t)found->ai_addrlen;
  freeaddrinfo(found);
  if (d->socket < 0 || tacta_net_send_datagram(d, TNET_HELLO, &d->hello) != 0) {
    snprintf(error, error_capacity, "cannot send to %s:%u: %s", host, (unsigned)port, strerror(errno));
    if (d->socket >= 0) close(d->socket);
    d->socket = -1;
    return -1;
  }
  return 0;
}

/* Sends one STATE (and a HELLO once a second, so a simulation started later still learns the
 * capabilities). 0 on success. */
static inline int tacta_net_send_state(tacta_net_device* d, const tnet_state* state) {
  if (tacta_net_now_ns() - d->last_hello_ns > 1000000000ull) tacta_net_send_datagram(d, TNET_HELLO, &d->hello);
  return tacta_net_send_datagram(d, TNET_STATE, state);
}

/* Handles one received datagram: 1 accepted, 0 dropped (counted). For tests that delay it. */
static inline int tacta_net_accept(tacta_net_device* d, const unsigned char* buffer, size_t size, uint64_t now) {
  tnet_header h;
  tnet_force f;
  int order;
  if (tnet_decode_header(buffer, size, &h) != TNET_OK || h.type != TNET_FORCE ||
      tnet_decode_force(buffer + TNET_HEADER_SIZE, &f) != TNET_OK || h.session != d->session) {
    ++d->malformed;
    return 0;
  }
  order = tnet_sequence_check(h.sequence, d->force_sequence, d->have_force);
  if (order <= 0) {
    ++d->dropped;
    return 0;
  }
  d->force = f;
  d->have_force = 1;
  d->force_sequence = h.sequence;
  d->force_sender_ns = h.sender_time_ns;
  d->force_received_ns = now;
  if (h.echo_time_ns != 0 && now > h.echo_time_ns + h.echo_hold_ns)
    d->round_trip_s = (double)(now - h.echo_time_ns - h.echo_hold_ns) * 1e-9;
  ++d->received;
  return 1;
}

/* Drains every datagram waiting on the socket; returns how many forces were accepted. */
static inline int tacta_net_poll(tacta_net_device* d) {
  unsigned char buffer[256];
  int accepted = 0;
  for (;;) {
    const ssize_t n = recv(d->socket, buffer, sizeof buffer, 0);
    if (n < 0) break;
    accepted += tacta_net_accept(d, buffer, (size_t)n, tacta_net_now_ns());
  }
  return accepted;
}

/* The force to render (N): the newest one, or zero when none arrived within the watchdog or the
 * simulation says it is not connected. Returns 1 when the link is live, 0 when silent. */
static inline int tacta_net_force(const tacta_net_device* d, double force[3]) {
  const int live = d->have_force && d->force.device_state == 0 &&
                   (double)(tacta_net_now_ns() - d->force_received_ns) * 1e-9 <= d->watchdog_s;
  int i;
  for (i = 0; i < 3; ++i) force[i] = live ? d->force.force[i] : 0.0;
  return live;
}

/* J: the environment's returned energy, the two-port bound of the passivity filter. */
static inline double tacta_net_remote_budget(const tacta_net_device* d) {
  return d->have_force ? d->force.energy_returned : 0.0;
}

static inline void tacta_net_close(tacta_net_device* d) {
  if (d->socket < 0) return;
  tacta_net_send_datagram(d, TNET_BYE, NULL);
  close(d->socket);
  d->socket = -1;
}

#ifdef __cplusplus
}
#endif

#endif /* TACTA_NET_DEVICE_H */
