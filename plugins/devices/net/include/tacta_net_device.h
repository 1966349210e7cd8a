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
 *     tacta_net_passivity_filter(&dev.passivity, state.position, state.velocity, dt,
 *                                tacta_net_remote_budget(&dev), force, caps.peak_force, force);
 *     vendor_set_force(force);
 *   tacta_net_close(&dev);                         // says BYE
 *
 * Passivity under delay (time-domain passivity on the delayed two-port, after Ryu, Artigas
 * and Preusche, Mechatronics 20(7), 2010): the energy the device returns to the hand is kept
 * below both the energy the hand has put in (one-port ledger, observed exactly for a force held
 * over each servo tick: F(n).(x(n+1) - x(n)), not sampled power) and the energy the simulated environment has
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
  double energy_in;  /* J: work the hand did against the device's force (exact, see below) */
  double energy_out; /* J: work the device's force did on the hand */
  double dissipated; /* J: sampled work the controller removed (damper or scaling) */
  double link_out;   /* J: energy returned to the hand in sampled power, for the two-port bound */
  int use_remote;    /* 1: also bound by the environment's returned energy (two-port) */
  int have_last;     /* a force is held since last_position */
  double last_position[3], last_force[3]; /* m, N: the previous tick's position and held force */
  double last_predicted[3];               /* m: the displacement that tick was planned with */
  double last_step[3], curvature[3];      /* m: its v dt, and the newest (actual - v dt) */
  double miss; /* m: recent largest |actual - predicted displacement|, decaying */
} tacta_net_passivity;

typedef struct tacta_net_device {
  int socket;
  struct sockaddr_storage peer;
  socklen_t peer_size;
  uint32_t session, sequence;
  tnet_hello hello;
  uint64_t last_hello_ns;
  tnet_force force; /* newest accepted FORCE */
  int have_force;
  uint32_t force_sequence;
  uint64_t force_sender_ns;   /* its sender_time_ns, echoed back */
  uint64_t force_received_ns; /* local clock when it arrived */
  double watchdog_s;          /* silence longer than this: zero force (default 0.05 s) */
  double round_trip_s;        /* newest measured round trip, -1 before any */
  uint64_t sent, received, dropped, malformed;
  tacta_net_passivity passivity;
} tacta_net_device;

static inline uint64_t tacta_net_now_ns(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (uint64_t)t.tv_sec * 1000000000ull + (uint64_t)t.tv_nsec;
}

static inline void tacta_net_passivity_reset(tacta_net_passivity* p) {
  memset(p, 0, sizeof *p);
  p->use_remote = 1;
}

/* J: what the hand put in minus what it got back, up to the newest position. */
static inline double tacta_net_passivity_ledger(const tacta_net_passivity* p) {
  return p->energy_in - p->energy_out;
}

static inline double tacta_net_dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Scales `f` (N) down to `peak` (N); a non-finite force becomes zero. */
static inline void tacta_net_limit(double f[3], double peak) {
  const double magnitude2 = tacta_net_dot3(f, f);
  int i;
  if (!(magnitude2 <= peak * peak)) { /* also catches NaN */
    const double scale = magnitude2 > 0.0 && magnitude2 < 1e300 ? peak / sqrt(magnitude2) : 0.0;
    for (i = 0; i < 3; ++i) f[i] *= scale;
  }
}

/* The force to apply this tick, given the device's `position` (m) and `velocity` (m/s) now:
 * `desired` (N), damped and scaled just enough that the energy returned to the hand stays within
 * both budgets, and limited to `peak` (N). `remote_budget` (J): tacta_net_remote_budget. The
 * caller must render `out` unchanged until the next call (the ledger charges it over the motion).
 *
 * Observer: the force is held over each servo tick, so its exact work is the held force times
 * the displacement, F(n).(x(n+1) - x(n)), charged when x(n+1) arrives. Controller: the next
 * displacement is unknown, so it plans with v dt plus the previous tick's own departure from
 * v dt (the acceleration's share) and keeps back |F| times twice the largest recent miss of that
 * prediction (which tracks changes of acceleration, servo jitter and encoder noise; decay 0.998
 * per tick, about 0.5 s). A miss beyond that leaves a deficit: zero force until the hand has
 * put it back. */
static inline void tacta_net_passivity_filter(tacta_net_passivity* p, const double position[3],
                                              const double velocity[3], double dt,
                                              double remote_budget, const double desired[3],
                                              double peak, double out[3]) {
  double f[3] = {desired[0], desired[1], desired[2]}, d[3], speed2, sampled, own, worst, planned;
  int i;
  if (!(isfinite(position[0]) && isfinite(position[1]) && isfinite(position[2]))) {
    out[0] = out[1] = out[2] = 0.0; /* no position, no ledger: render nothing, restart the hold */
    p->have_last = 0;
    return;
  }
  if (p->have_last) {
    double moved[3], miss2 = 0.0, work;
    for (i = 0; i < 3; ++i) {
      moved[i] = position[i] - p->last_position[i];
      miss2 += (moved[i] - p->last_predicted[i]) * (moved[i] - p->last_predicted[i]);
      p->curvature[i] = moved[i] - p->last_step[i];
    }
    work = tacta_net_dot3(p->last_force, moved);
    if (work > 0.0)
      p->energy_out += work;
    else
      p->energy_in -= work;
    p->miss = sqrt(miss2) > p->miss * 0.998 ? sqrt(miss2) : p->miss * 0.998;
  }
  /* Two-port: the energy returned to the hand, in sampled power f.v dt as the simulation sums
   * the environment's, stays below what the environment returned (one delay ago); a damper
   * along the velocity removes the excess (Ryu, Artigas and Preusche 2010). */
  speed2 = tacta_net_dot3(velocity, velocity);
  sampled = dt > 0.0 && isfinite(speed2) ? tacta_net_dot3(f, velocity) * dt : 0.0;
  if (p->use_remote && sampled > remote_budget - p->link_out) {
    const double excess = sampled - (remote_budget - p->link_out); /* J, > 0 */
    if (speed2 > 1e-18) {
      for (i = 0; i < 3; ++i) f[i] -= excess / (speed2 * dt) * velocity[i];
    } else {
      f[0] = f[1] = f[2] = 0.0;
    }
  }
  tacta_net_limit(f, peak);
  /* One-port, exact: the worst work over the unsure displacement stays within what the hand put
   * in; scaling the force down never makes it worse (no damper: it would chatter on a hand
   * that barely moves). */
  for (i = 0; i < 3; ++i) {
    p->last_step[i] = dt > 0.0 && isfinite(velocity[i]) ? velocity[i] * dt : 0.0;
    d[i] = p->last_step[i] + (p->have_last ? p->curvature[i] : 0.0);
  }
  own = p->have_last ? p->energy_in - p->energy_out : -1.0; /* first tick: no miss measured yet */
  worst = tacta_net_dot3(f, d) + sqrt(tacta_net_dot3(f, f)) * (2.0 * p->miss + 1e-12) + 1e-15;
  if (worst > own) {
    const double scale = own > 0.0 ? own / worst : 0.0;
    for (i = 0; i < 3; ++i) f[i] *= scale;
  }
  sampled = dt > 0.0 && isfinite(speed2) ? tacta_net_dot3(f, velocity) * dt : 0.0;
  if (sampled > 0.0) p->link_out += sampled;
  planned = tacta_net_dot3(desired, velocity) * dt - sampled;
  if (isfinite(planned) && planned > 0.0) p->dissipated += planned;
  for (i = 0; i < 3; ++i) {
    out[i] = f[i];
    p->last_force[i] = f[i];
    p->last_position[i] = position[i];
    p->last_predicted[i] = d[i];
  }
  p->have_last = 1;
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
  if (sendto(d->socket, buffer, size, 0, (const struct sockaddr*)&d->peer, d->peer_size) !=
      (ssize_t)size)
    return -1;
  ++d->sent;
  d->last_hello_ns = type == TNET_HELLO ? now : d->last_hello_ns;
  return 0;
}

/* Opens a non-blocking UDP socket towards the simulation and says HELLO with `capabilities`.
 * 0 on success; -1 with a reason in `error`. */
static inline int tacta_net_open(tacta_net_device* d, const char* host, uint16_t port,
                                 const tnet_hello* capabilities, char* error,
                                 size_t error_capacity) {
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
    snprintf(error, error_capacity, "cannot send to %s:%u: %s", host, (unsigned)port,
             strerror(errno));
    if (d->socket >= 0) close(d->socket);
    d->socket = -1;
    return -1;
  }
  return 0;
}

/* Sends one STATE (and a HELLO once a second, so a simulation started later still learns the
 * capabilities). 0 on success. */
static inline int tacta_net_send_state(tacta_net_device* d, const tnet_state* state) {
  if (tacta_net_now_ns() - d->last_hello_ns > 1000000000ull)
    tacta_net_send_datagram(d, TNET_HELLO, &d->hello);
  return tacta_net_send_datagram(d, TNET_STATE, state);
}

/* Handles one received datagram: 1 accepted, 0 dropped (counted). For tests that delay it. */
static inline int tacta_net_accept(tacta_net_device* d, const unsigned char* buffer, size_t size,
                                   uint64_t now) {
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
