/* Tacta net device protocol, version 1: the UDP datagrams between a device bridge (the vendor
 * SDK's process, on any machine) and the `net` device plugin. Plain C99, header-only, no
 * dependencies; the plugin and both clients (tacta_net_device.h, tacta_net_device.py) use it.
 * docs/DEVICES.md describes it for people; this file is the reference.
 *
 * Every datagram: a 40-byte header, then a payload whose size depends on the type. All fields
 * are little-endian; reals are IEEE 754 binary64. SI units.
 *
 *   offset size  field
 *   0      4     magic "TNET" (0x54454E54 read as a little-endian u32)
 *   4      2     version (1)
 *   6      2     type: 1 HELLO, 2 STATE (device -> simulation), 3 FORCE (simulation -> device),
 *                4 BYE (device -> simulation)
 *   8      4     session: random per device start; the simulation echoes it
 *   12     4     sequence: +1 per datagram the sender sends in this session
 *   16     8     sender_time_ns: the sender's monotonic clock (ns)
 *   24     8     echo_time_ns: sender_time_ns of the newest datagram received from the peer
 *                (0: none yet)
 *   32     4     echo_hold_ns: how long ago (ns) that datagram arrived; the peer's round trip
 *                is its now - echo_time_ns - echo_hold_ns
 *   36     4     payload_size (bytes after the header)
 *
 * HELLO payload (88 bytes): the device's capabilities (tacta_device_capabilities' fields)
 *   f64 workspace_min[3], workspace_max[3] (m), peak_force (N), continuous_force (N),
 *   usable_stiffness (N/m), nominal_rate (Hz); u32 dof_in, dof_out.
 * STATE payload (88 bytes): f64 position[3] (m), orientation[4] (w x y z), velocity[3] (m/s);
 *   u32 buttons (bit i = button i), u32 flags (0).
 * FORCE payload (72 bytes): f64 force[3] (N), torque[3] (N m), energy_returned (J: work the
 *   simulated environment has done on the device's motion since the session began, the
 *   two-port passivity budget of the device side), energy_absorbed (J: work the device's
 *   motion has done on it); i32 device_state (tacta_device_state), u32 reserved (0).
 * BYE: no payload; the simulation zeroes the force and reports the device disconnected.
 */
#ifndef TACTA_NET_PROTOCOL_H
#define TACTA_NET_PROTOCOL_H

#include <stdint.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TNET_MAGIC 0x54454E54u
#define TNET_VERSION 1u
#define TNET_HEADER_SIZE 40u
#define TNET_HELLO 1u
#define TNET_STATE 2u
#define TNET_FORCE 3u
#define TNET_BYE 4u
#define TNET_HELLO_SIZE 88u
#define TNET_STATE_SIZE 88u
#define TNET_FORCE_SIZE 72u
#define TNET_MAX_DATAGRAM (TNET_HEADER_SIZE + TNET_HELLO_SIZE)
#define TNET_DEFAULT_PORT 18950u

typedef struct tnet_header {
  uint16_t version, type;
  uint32_t session, sequence;
  uint64_t sender_time_ns, echo_time_ns;
  uint32_t echo_hold_ns, payload_size;
} tnet_header;

typedef struct tnet_hello {
  double workspace_min[3], workspace_max[3];
  double peak_force, continuous_force, usable_stiffness, nominal_rate;
  uint32_t dof_in, dof_out;
} tnet_hello;

typedef struct tnet_state {
  double position[3], orientation[4], velocity[3];
  uint32_t buttons, flags;
} tnet_state;

typedef struct tnet_force {
  double force[3], torque[3];
  double energy_returned, energy_absorbed;
  int32_t device_state;
  uint32_t reserved;
} tnet_force;

/* Why a datagram was refused (tnet_decode_header). */
typedef enum tnet_error {
  TNET_OK = 0,
  TNET_ERR_SHORT,   /* shorter than its header or than its payload_size says */
  TNET_ERR_MAGIC,   /* not a Tacta net datagram */
  TNET_ERR_VERSION, /* another protocol version */
  TNET_ERR_TYPE,    /* unknown type, or a payload size that does not fit the type */
  TNET_ERR_VALUE    /* a non-finite number, or a quaternion far from unit length */
} tnet_error;

/* ---- little-endian fields ------------------------------------------------------------------ */
static inline void tnet_put_u32(unsigned char* p, uint32_t v) {
  p[0] = (unsigned char)v;
  p[1] = (unsigned char)(v >> 8);
  p[2] = (unsigned char)(v >> 16);
  p[3] = (unsigned char)(v >> 24);
}
static inline uint32_t tnet_get_u32(const unsigned char* p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static inline void tnet_put_u64(unsigned char* p, uint64_t v) {
  tnet_put_u32(p, (uint32_t)v);
  tnet_put_u32(p + 4, (uint32_t)(v >> 32));
}
static inline uint64_t tnet_get_u64(const unsigned char* p) {
  return (uint64_t)tnet_get_u32(p) | (uint64_t)tnet_get_u32(p + 4) << 32;
}
static inline void tnet_put_f64(unsigned char* p, double v) {
  uint64_t bits;
  memcpy(&bits, &v, sizeof bits);
  tnet_put_u64(p, bits);
}
static inline double tnet_get_f64(const unsigned char* p) {
  const uint64_t bits = tnet_get_u64(p);
  double v;
  memcpy(&v, &bits, sizeof v);
  return v;
}
static inline void tnet_put_f64s(unsigned char* p, const double* v, int n) {
  int i;
  for (i = 0; i < n; ++i) tnet_put_f64(p + 8 * i, v[i]);
}
static inline int tnet_get_f64s(const unsigned char* p, double* v,
                                int n) { /* 0: a non-finite value */
  int i, finite = 1;
  for (i = 0; i < n; ++i) {
    v[i] = tnet_get_f64(p + 8 * i);
    finite = finite && v[i] - v[i] == 0.0; /* false for NaN and infinities, no <math.h> needed */
  }
  return finite;
}

/* ---- header -------------------------------------------------------------------------------- */
static inline uint32_t tnet_payload_size(uint32_t type) {
  return type == TNET_HELLO   ? TNET_HELLO_SIZE
         : type == TNET_STATE ? TNET_STATE_SIZE
         : type == TNET_FORCE ? TNET_FORCE_SIZE
                              : 0u;
}

/* Writes the header for `h.type` (version and payload_size filled in); returns the bytes. */
static inline uint32_t tnet_encode_header(unsigned char* out, tnet_header h) {
  tnet_put_u32(out, TNET_MAGIC);
  out[4] = (unsigned char)TNET_VERSION;
  out[5] = 0;
  out[6] = (unsigned char)h.type;
  out[7] = (unsigned char)(h.type >> 8);
  tnet_put_u32(out + 8, h.session);
  tnet_put_u32(out + 12, h.sequence);
  tnet_put_u64(out + 16, h.sender_time_ns);
  tnet_put_u64(out + 24, h.echo_time_ns);
  tnet_put_u32(out + 32, h.echo_hold_ns);
  tnet_put_u32(out + 36, tnet_payload_size(h.type));
  return TNET_HEADER_SIZE;
}

static inline tnet_error tnet_decode_header(const unsigned char* in, size_t size, tnet_header* h) {
  if (size < TNET_HEADER_SIZE) return TNET_ERR_SHORT;
  if (tnet_get_u32(in) != TNET_MAGIC) return TNET_ERR_MAGIC;
  h->version = (uint16_t)(in[4] | in[5] << 8);
  if (h->version != TNET_VERSION) return TNET_ERR_VERSION;
  h->type = (uint16_t)(in[6] | in[7] << 8);
  h->session = tnet_get_u32(in + 8);
  h->sequence = tnet_get_u32(in + 12);
  h->sender_time_ns = tnet_get_u64(in + 16);
  h->echo_time_ns = tnet_get_u64(in + 24);
  h->echo_hold_ns = tnet_get_u32(in + 32);
  h->payload_size = tnet_get_u32(in + 36);
  if (h->type < TNET_HELLO || h->type > TNET_BYE || h->payload_size != tnet_payload_size(h->type))
    return TNET_ERR_TYPE;
  if (size < TNET_HEADER_SIZE + h->payload_size) return TNET_ERR_SHORT;
  return TNET_OK;
}

/* ---- payloads (p points just past the header) ------------------------------------------------ */
static inline uint32_t tnet_encode_hello(unsigned char* p, const tnet_hello* v) {
  tnet_put_f64s(p, v->workspace_min, 3);
  tnet_put_f64s(p + 24, v->workspace_max, 3);
  tnet_put_f64(p + 48, v->peak_force);
  tnet_put_f64(p + 56, v->continuous_force);
  tnet_put_f64(p + 64, v->usable_stiffness);
  tnet_put_f64(p + 72, v->nominal_rate);
  tnet_put_u32(p + 80, v->dof_in);
  tnet_put_u32(p + 84, v->dof_out);
  return TNET_HELLO_SIZE;
}
static inline tnet_error tnet_decode_hello(const unsigned char* p, tnet_hello* v) {
  double reals[10];
  if (!tnet_get_f64s(p, reals, 10)) return TNET_ERR_VALUE;
  memcpy(v->workspace_min, reals, sizeof v->workspace_min);
  memcpy(v->workspace_max, reals + 3, sizeof v->workspace_max);
  v->peak_force = reals[6];
  v->continuous_force = reals[7];
  v->usable_stiffness = reals[8];
  v->nominal_rate = reals[9];
  v->dof_in = tnet_get_u32(p + 80);
  v->dof_out = tnet_get_u32(p + 84);
  if (!(v->peak_force > 0.0) || v->continuous_force < 0.0 || v->usable_stiffness < 0.0 ||
      v->nominal_rate < 0.0)
    return TNET_ERR_VALUE;
  return TNET_OK;
}

static inline uint32_t tnet_encode_state(unsigned char* p, const tnet_state* v) {
  tnet_put_f64s(p, v->position, 3);
  tnet_put_f64s(p + 24, v->orientation, 4);
  tnet_put_f64s(p + 56, v->velocity, 3);
  tnet_put_u32(p + 80, v->buttons);
  tnet_put_u32(p + 84, v->flags);
  return TNET_STATE_SIZE;
}
static inline tnet_error tnet_decode_state(const unsigned char* p, tnet_state* v) {
  double q;
  if (!tnet_get_f64s(p, v->position, 3) || !tnet_get_f64s(p + 24, v->orientation, 4) ||
      !tnet_get_f64s(p + 56, v->velocity, 3))
    return TNET_ERR_VALUE;
  q = v->orientation[0] * v->orientation[0] + v->orientation[1] * v->orientation[1] +
      v->orientation[2] * v->orientation[2] + v->orientation[3] * v->orientation[3];
  if (q < 0.81 || q > 1.21) return TNET_ERR_VALUE; /* |q| within 10 % of 1 */
  v->buttons = tnet_get_u32(p + 80);
  v->flags = tnet_get_u32(p + 84);
  return TNET_OK;
}

static inline uint32_t tnet_encode_force(unsigned char* p, const tnet_force* v) {
  tnet_put_f64s(p, v->force, 3);
  tnet_put_f64s(p + 24, v->torque, 3);
  tnet_put_f64(p + 48, v->energy_returned);
  tnet_put_f64(p + 56, v->energy_absorbed);
  tnet_put_u32(p + 64, (uint32_t)v->device_state);
  tnet_put_u32(p + 68, v->reserved);
  return TNET_FORCE_SIZE;
}
static inline tnet_error tnet_decode_force(const unsigned char* p, tnet_force* v) {
  if (!tnet_get_f64s(p, v->force, 3) || !tnet_get_f64s(p + 24, v->torque, 3)) return TNET_ERR_VALUE;
  v->energy_returned = tnet_get_f64(p + 48);
  v->energy_absorbed = tnet_get_f64(p + 56);
  v->device_state = (int32_t)tnet_get_u32(p + 64);
  v->reserved = tnet_get_u32(p + 68);
  if (!(v->energy_returned - v->energy_returned == 0.0) ||
      !(v->energy_absorbed - v->energy_absorbed == 0.0))
    return TNET_ERR_VALUE;
  return TNET_OK;
}

/* Sequence check for one session: 1 accept, 0 duplicate, -1 older (out of order). `newest` is
 * the last accepted sequence; `started` is 0 before the first. Wraps around at 2^32. */
static inline int tnet_sequence_check(uint32_t sequence, uint32_t newest, int started) {
  int32_t ahead;
  if (!started) return 1;
  ahead = (int32_t)(sequence - newest);
  return ahead > 0 ? 1 : ahead == 0 ? 0 : -1;
}

#ifdef __cplusplus
}
#endif

#endif /* TACTA_NET_PROTOCOL_H */
