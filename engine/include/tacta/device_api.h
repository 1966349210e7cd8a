/* Haptic device plugins (kind TACTA_KIND_DEVICE): the function table and the data it sees.
 *
 * Positions are in the world frame (m); the engine maps nothing. read() and write() run in the
 * 1 kHz path: no allocation, no lock, no throw. A device that cannot deliver a sample reports it
 * through its state; the engine then sends zero force and reports the reason.
 */
#ifndef TACTA_DEVICE_API_H
#define TACTA_DEVICE_API_H

#include "tacta/plugin.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tacta_device_capabilities {
  double workspace_min[3]; /* m, world frame */
  double workspace_max[3]; /* m */
  double peak_force;       /* N, never exceeded by the engine */
  double continuous_force; /* N */
  double usable_stiffness; /* N/m, largest stable rendered stiffness at the nominal rate */
  double nominal_rate;     /* Hz */
  uint32_t dof_in;         /* sensed degrees of freedom (3 position, 6 with orientation) */
  uint32_t dof_out;        /* actuated degrees of freedom (3 force, 6 with torque) */
} tacta_device_capabilities;

typedef struct tacta_device_sample {
  double time;           /* s, the device's timestamp */
  double position[3];    /* m */
  double orientation[4]; /* unit quaternion w, x, y, z */
  double velocity[3];    /* m/s */
  uint32_t buttons;      /* bit i set = button i pressed */
} tacta_device_sample;

typedef struct tacta_device_command {
  double force[3];  /* N, already clamped to peak_force by the engine */
  double torque[3]; /* N m, zero where dof_out < 6 */
} tacta_device_command;

/* Device states, as read() and status() return them. */
typedef int32_t tacta_device_state;
#define TACTA_DEVICE_CONNECTED 0
#define TACTA_DEVICE_DISCONNECTED 1 /* not (or no longer) connected: zero force */
#define TACTA_DEVICE_FAULT 2        /* a fault the device reports: zero force */
#define TACTA_DEVICE_FINISHED 3     /* a replay reached the end of its log */

/* One named figure a device reports for report.json (network devices: packets, drops, round
 * trip). `name` is snake_case with its unit as suffix where it has one ("round_trip_p50_ms"). */
typedef struct tacta_device_counter {
  const char* name; /* static storage in the plugin */
  double value;
} tacta_device_counter;

/* A body's deformed surface as the engine hands it to a device (optional `surface` entry). */
typedef struct tacta_device_surface {
  double time;             /* s, simulated time of the state */
  const char* body;        /* the body's name */
  const double* positions; /* 3 per point, m, world frame: every node of the body, or every
                                  vertex of its embedded surface (tacta/embedded_surface.hpp) */
  uint32_t node_count;
  const uint32_t* triangles; /* 3 per triangle, indices into positions, outward */
  uint32_t triangle_count;
} tacta_device_surface;

typedef struct tacta_device_setup {
  uint32_t struct_size;
  const tacta_param_value* params; /* validated against the schema, schema order */
  uint32_t param_count;
  const char* base_directory; /* the scene's folder: relative TEXT paths resolve against it */
  uint64_t seed;              /* for noise; the same seed gives the same run */
  double tick;                /* s, the haptic period the engine will call at */
} tacta_device_setup;

typedef struct tacta_device_api {
  /* required: may allocate and read files; writes a reason on failure. */
  tacta_status (*create)(const tacta_device_setup* setup, void** instance, char* message,
                         size_t message_capacity);
  /* required */
  void (*destroy)(void* instance);
  /* required */
  tacta_status (*connect)(void* instance, char* message, size_t message_capacity);
  /* required */
  void (*disconnect)(void* instance);
  /* required: the sample for simulated time `time` (s). 1 kHz path. */
  tacta_device_state (*read)(void* instance, double time, tacta_device_sample* sample);
  /* required: the force to render until the next write. 1 kHz path. */
  void (*write)(void* instance, double time, const tacta_device_command* command);
  /* required */
  void (*capabilities)(void* instance, tacta_device_capabilities* capabilities);
  /* optional: current state and, when not connected, why (NUL-terminated). */
  tacta_device_state (*status)(void* instance, char* reason, size_t reason_capacity);
  /* optional: input fed by the host, such as the viewer's mouse; `values` are device-specific
   * (mouse: target x, y, z in m). The engine calls it for one instance (Simulation::device_input)
   * from a host thread (not the haptic one) while read() may run: the plugin makes it
   * lock-free. */
  void (*input)(void* instance, const double* values, uint32_t count);
  /* optional (ABI 1.1): the deformed surface of the body this device touches (the last one it
   * touched, else the first body), at the render rate, from the render task's thread while
   * read() may run. The arrays live only for the call: the plugin copies what it keeps, into
   * storage sized at the first call, and makes the hand-over to its own threads lock-free. */
  void (*surface)(void* instance, const tacta_device_surface* surface);
  /* optional (ABI 1.1): fills up to `capacity` counters, returns how many it has. Called after
   * the run from the host thread, for report.json. */
  uint32_t (*counters)(void* instance, tacta_device_counter* counters, uint32_t capacity);
  /* optional (ABI 1.3), appended: the instance's own evolving state, for checkpoints (a scripted
   * hand's position, velocity and held force; a replay's cursor), as tacta_model_api's entries:
   * save_state writes it into bytes when capacity is enough and returns its size either way;
   * load_state sets it on an instance created from the same setup and connected, or returns an
   * error with a reason. A device without them (a live link) restarts from its connection. Not
   * from the 1 kHz path. */
  size_t (*save_state)(void* instance, void* bytes, size_t capacity);
  tacta_status (*load_state)(void* instance, const void* bytes, size_t size, char* message,
                             size_t message_capacity);
} tacta_device_api;

/* The checkpoint entries of a device table, 0 when the plugin has none or is older. */
static inline int tacta_device_has_state_entries(const tacta_device_api* api, uint32_t api_size) {
  return api_size >= offsetof(tacta_device_api, load_state) + sizeof(void*) &&
         api->save_state != NULL && api->load_state != NULL;
}

#define TACTA_DEVICE_API_FIELD(member, required) \
  { #member, offsetof(tacta_device_api, member), required }

static const tacta_api_field tacta_device_api_fields[] = {
    TACTA_DEVICE_API_FIELD(create, 1),       TACTA_DEVICE_API_FIELD(destroy, 1),
    TACTA_DEVICE_API_FIELD(connect, 1),      TACTA_DEVICE_API_FIELD(disconnect, 1),
    TACTA_DEVICE_API_FIELD(read, 1),         TACTA_DEVICE_API_FIELD(write, 1),
    TACTA_DEVICE_API_FIELD(capabilities, 1), TACTA_DEVICE_API_FIELD(status, 0),
    TACTA_DEVICE_API_FIELD(input, 0),        TACTA_DEVICE_API_FIELD(surface, 0),
    TACTA_DEVICE_API_FIELD(counters, 0),     TACTA_DEVICE_API_FIELD(save_state, 0),
    TACTA_DEVICE_API_FIELD(load_state, 0),
};

#ifdef __cplusplus
}
#endif

#endif /* TACTA_DEVICE_API_H */
