/* The far end of the teleoperation tests: a simulated operator's hand on an Omni-class device,
 * bridged with the real C client (tacta_net_device.h) to the simulation's `net` device through a
 * delay line inside this process (a UDP relay on 127.0.0.1 that holds each datagram for half the
 * round trip, plus uniform jitter, and loses a fraction of them).
 *
 *   net_teleop_peer PORT RTT_MS JITTER_MS LOSS SEED PRESS_DURATION_S OUT.csv [unfiltered]
 *
 * The hand (0.1 kg, pulled by a 300 N/m, 11 N s/m spring-damper towards a target) starts 12 mm
 * above the liver's upper surface, its target goes 8 mm below it within PRESS_RAMP_S (1 s) and stays there.
 * The device force, after the two-port passivity filter (or only limited to the peak with
 * `unfiltered`), acts on the hand, held over each 1 ms tick. Timeline zero is the first live
 * force. OUT.csv, a row per tick: t, the position at the tick's start and the force held over it
 * (full double precision, so a reader can recompute the exact work), the filter's ledger;
 * stdout: one summary line. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>

#include "tacta_net_device.h"

#define QUEUE 8192
typedef struct held {
  uint64_t due;
  int to_sim;
  size_t size;
  unsigned char data[TNET_MAX_DATAGRAM];
} held;
static held queue[QUEUE];
static int queued = 0;

static double uniform(unsigned* state) { /* [0, 1) */
  *state = *state * 1103515245u + 12345u;
  return (double)((*state >> 8) & 0xFFFFFF) / 16777216.0;
}

static void sleep_until_ns(uint64_t deadline) {
  struct timespec t = {(time_t)(deadline / 1000000000ull), (long)(deadline % 1000000000ull)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, NULL) == EINTR) {
  }
}

int main(int argc, char** argv) {
  const double pressed_y = 0.147 - 0.008, start_y = 0.147 + 0.012; /* m, at x = -0.049, z = 0.027 */
  const double mass = 0.1, k_hand = 300.0, b_hand = 11.0, dt = 1e-3,
               ramp = 1.0; /* kg, N/m, N s/m, s, s */
  tnet_hello caps = {{-0.13, 0.06, -0.035}, {0.03, 0.18, 0.105}, 3.3, 0.88, 1000.0, 1000.0, 3, 3};
  struct sockaddr_in relay_address = {0}, sim_address = {0}, client_address = {0};
  socklen_t size = sizeof relay_address;
  double x[3] = {-0.049, start_y, 0.027}, v[3] = {0, 0, 0}, f[3] = {0, 0, 0}, last_x[3];
  double min_ledger = 0, exact_ledger = 0, min_exact = 0, peak = 0, rtt_sum = 0;
  double held_force = 0;
  long held_ticks = 0, held_pressing = 0, rtt_count = 0, ticks = 0;
  uint64_t start = 0, next;
  unsigned rng;
  int relay, i;
  char error[256];
  tacta_net_device dev;
  FILE* out;
  if (argc != 8 && !(argc == 9 && strcmp(argv[8], "unfiltered") == 0)) {
    fprintf(stderr,
            "usage: %s PORT RTT_MS JITTER_MS LOSS SEED PRESS_DURATION_S OUT.csv [unfiltered]\n",
            argv[0]);
    return 2;
  }
  const double one_way = atof(argv[2]) * 0.5e-3, jitter = atof(argv[3]) * 1e-3,
               loss = atof(argv[4]);
  const double duration = atof(argv[6]);
  const int filtered = argc == 8;
  rng = (unsigned)strtoul(argv[5], NULL, 10);
  out = fopen(argv[7], "w");
  relay = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
  relay_address.sin_family = AF_INET;
  relay_address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (out == NULL || relay < 0 ||
      bind(relay, (struct sockaddr*)&relay_address, sizeof relay_address) != 0)
    return 2;
  getsockname(relay, (struct sockaddr*)&relay_address, &size);
  sim_address = relay_address;
  sim_address.sin_port = htons((uint16_t)atoi(argv[1]));
  {
    char port[16];
    snprintf(port, sizeof port, "%u", (unsigned)ntohs(relay_address.sin_port));
    if (tacta_net_open(&dev, "127.0.0.1", (uint16_t)atoi(port), &caps, error, sizeof error) != 0)
      return 2;
  }
  size = sizeof client_address;
  getsockname(dev.socket, (struct sockaddr*)&client_address, &size);
  fprintf(out, "t,x,y,z,fx,fy,fz,ledger\n");
  const uint64_t begun = tacta_net_now_ns();
  for (next = begun;; next += 1000000ull) {
    unsigned char buffer[512];
    struct sockaddr_in from;
    double raw[3], target_y, tau;
    uint64_t now;
    sleep_until_ns(next);
    now = tacta_net_now_ns();
    /* The delay line: what arrives at the relay waits for its due time, or is lost. */
    for (;;) {
      socklen_t from_size = sizeof from;
      const ssize_t n =
          recvfrom(relay, buffer, sizeof buffer, 0, (struct sockaddr*)&from, &from_size);
      double delay;
      if (n < 0) break;
      if (uniform(&rng) < loss || queued == QUEUE || (size_t)n > TNET_MAX_DATAGRAM) continue;
      delay = one_way + (2.0 * uniform(&rng) - 1.0) * jitter;
      queue[queued].due = now + (uint64_t)((delay > 0 ? delay : 0) * 1e9);
      queue[queued].to_sim = from.sin_port == client_address.sin_port;
      queue[queued].size = (size_t)n;
      memcpy(queue[queued].data, buffer, (size_t)n);
      ++queued;
    }
    for (i = 0; i < queued;) {
      if (queue[i].due > now) {
        ++i;
        continue;
      }
      sendto(relay, queue[i].data, queue[i].size, 0,
             (struct sockaddr*)(queue[i].to_sim ? &sim_address : &client_address),
             sizeof sim_address);
      queue[i] = queue[--queued];
    }
    /* The bridge's servo tick. */
    tacta_net_poll(&dev);
    const int live = tacta_net_force(&dev, raw);
    if (start == 0 && live) start = now;
    tau = start == 0 ? 0.0 : (double)(now - start) * 1e-9;
    if (start != 0 && tau > duration) break;
    if (start == 0 && now - begun > 60000000000ull) return 3; /* no simulation answered in 60 s */
    if (filtered) {
      tacta_net_passivity_filter(&dev.passivity, x, v, dt, tacta_net_remote_budget(&dev), raw,
                                 caps.peak_force, f);
    } else {
      const double m = sqrt(raw[0] * raw[0] + raw[1] * raw[1] + raw[2] * raw[2]);
      for (i = 0; i < 3; ++i) f[i] = m > caps.peak_force ? raw[i] * caps.peak_force / m : raw[i];
    }
    target_y = start_y + (pressed_y - start_y) * (tau < ramp ? tau / ramp : 1.0);
    memcpy(last_x, x, sizeof x);
    for (i = 0; i < 10; ++i) { /* the hand, 0.1 ms sub-steps, the device force held */
      int a;
      for (a = 0; a < 3; ++a) {
        const double target = a == 1 ? target_y : a == 0 ? -0.049 : 0.027;
        v[a] += (k_hand * (target - x[a]) - b_hand * v[a] + f[a]) / mass * (dt / 10);
        x[a] += v[a] * (dt / 10);
      }
    }
    exact_ledger -=
        f[0] * (x[0] - last_x[0]) + f[1] * (x[1] - last_x[1]) + f[2] * (x[2] - last_x[2]);
    if (start != 0) {
      const double ledger = tacta_net_passivity_ledger(&dev.passivity);
      const double m = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
      min_ledger = ledger < min_ledger ? ledger : min_ledger;
      min_exact = exact_ledger < min_exact ? exact_ledger : min_exact;
      peak = m > peak ? m : peak;
      if (tau > duration - 1.0) { /* the last second: the target has been pressed in for a while */
        ++held_ticks;
        held_pressing += m > 0.2;
        held_force += m;
      }
      if (dev.round_trip_s > 0) {
        rtt_sum += dev.round_trip_s;
        ++rtt_count;
      }
      fprintf(out, "%.4f,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.6g\n", tau, last_x[0], last_x[1],
              last_x[2], f[0], f[1], f[2], ledger);
      ++ticks;
    }
    {
      tnet_state s = {{x[0], x[1], x[2]}, {1, 0, 0, 0}, {v[0], v[1], v[2]}, 0, 0};
      tacta_net_send_state(&dev, &s);
    }
  }
  tacta_net_close(&dev);
  fclose(out);
  printf(
      "ticks %ld min_ledger %.9g min_exact_ledger %.9g peak %.6f held_fraction %.4f held_mean %.6f "
      "rtt_mean_ms %.3f dissipated %.6g forces %llu dropped %llu\n",
      ticks, min_ledger, min_exact, peak, held_ticks ? (double)held_pressing / held_ticks : 0.0,
      held_ticks ? held_force / held_ticks : 0.0, rtt_count ? rtt_sum / rtt_count * 1e3 : -1.0,
      dev.passivity.dissipated, (unsigned long long)dev.received, (unsigned long long)dev.dropped);
  return 0;
}
