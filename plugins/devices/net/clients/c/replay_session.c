/* Replays a recorded device session (a device log CSV: `tacta run SCENE --record log.csv`) to a
 * Tacta simulation's `net` device as if it were hardware: one STATE per logged sample at its
 * logged time, the forces that come back rendered through the passivity filter, as a real
 * bridge would hand them to the vendor SDK. A template for a bridge: swap the CSV for the SDK.
 *
 *   tacta_net_replay LOG.csv [HOST] [PORT]
 *
 * Prints what it sent and received. Exit 0, or 2 with the file and line of a bad log. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>

#include "tacta_net_device.h"

static void sleep_until_ns(uint64_t deadline) {
  struct timespec t;
  t.tv_sec = (time_t)(deadline / 1000000000ull);
  t.tv_nsec = (long)(deadline % 1000000000ull);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, NULL) == EINTR) {
  }
}

/* One log row: time_s,px,py,pz,qw,qx,qy,qz,vx,vy,vz,buttons,fx,fy,fz. 1 read, 0 end, -1 bad. */
static int read_row(FILE* in, double* time, tnet_state* s) {
  double force[3];
  unsigned buttons;
  const int n = fscanf(in, " %lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%u,%lf,%lf,%lf", time,
                       &s->position[0], &s->position[1], &s->position[2], &s->orientation[0],
                       &s->orientation[1], &s->orientation[2], &s->orientation[3], &s->velocity[0],
                       &s->velocity[1], &s->velocity[2], &buttons, &force[0], &force[1], &force[2]);
  if (n == EOF) return 0;
  if (n != 15) return -1;
  s->buttons = buttons;
  s->flags = 0;
  return 1;
}

int main(int argc, char** argv) {
  const char* host = argc > 2 ? argv[2] : "127.0.0.1";
  const unsigned port = argc > 3 ? (unsigned)strtoul(argv[3], NULL, 10) : TNET_DEFAULT_PORT;
  tnet_hello caps = {{-0.08, 0.06, -0.035}, {0.08, 0.18, 0.105}, 3.3, 0.88, 1000.0, 1000.0, 6, 3};
  tacta_net_device dev;
  char error[256], header[256];
  double first_time = 0.0, last_time = 0.0, peak = 0.0;
  long line = 1, sent = 0;
  uint64_t start;
  FILE* in;
  if (argc < 2) {
    fprintf(stderr, "usage: %s LOG.csv [HOST] [PORT]\n", argv[0]);
    return 2;
  }
  in = fopen(argv[1], "r");
  if (in == NULL || fgets(header, sizeof header, in) == NULL) {
    fprintf(stderr, "%s: cannot read the header line\n", argv[1]);
    return 2;
  }
  if (tacta_net_open(&dev, host, (uint16_t)port, &caps, error, sizeof error) != 0) {
    fprintf(stderr, "%s\n", error);
    return 2;
  }
  start = tacta_net_now_ns();
  for (;;) {
    tnet_state s;
    double t, force[3], dt;
    const int row = read_row(in, &t, &s);
    ++line;
    if (row == 0) break;
    if (row < 0) {
      fprintf(stderr, "%s:%ld: expected 15 comma-separated numbers\n", argv[1], line);
      tacta_net_close(&dev);
      return 2;
    }
    if (sent == 0) first_time = t;
    dt = sent == 0 ? 0.0 : t - last_time;
    last_time = t;
    sleep_until_ns(start + (uint64_t)((t - first_time) * 1e9));
    tacta_net_send_state(&dev, &s);
    ++sent;
    tacta_net_poll(&dev);
    tacta_net_force(&dev, force);
    tacta_net_passivity_filter(&dev.passivity, s.position, s.velocity, dt,
                               tacta_net_remote_budget(&dev), force, caps.peak_force, force);
    {
      const double m = force[0] * force[0] + force[1] * force[1] + force[2] * force[2];
      if (m > peak * peak) peak = sqrt(m);
    }
  }
  fclose(in);
  tacta_net_close(&dev);
  printf(
      "states sent %ld, forces received %llu, dropped %llu, malformed %llu, peak force %.3f N, "
      "last round trip %.3f ms, ledger %.6f J\n",
      sent, (unsigned long long)dev.received, (unsigned long long)dev.dropped,
      (unsigned long long)dev.malformed, peak, dev.round_trip_s * 1e3,
      tacta_net_passivity_ledger(&dev.passivity));
  return 0;
}
