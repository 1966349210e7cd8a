/* Tacta plugin ABI: plain C, shared by the engine (host) and every plugin.
 *
 * A plugin is a shared library that exports one function, tacta_plugin_entry. The host calls it
 * with its ABI id; the plugin either refuses (status TACTA_ERR_ABI and a message that names the
 * differing bit) or registers one or more descriptors through the host table. No exception and
 * no C++ type crosses this boundary: status codes, message buffers and plain arrays of doubles.
 *
 * Kind-specific function tables live in model_api.h, collision_api.h and device_api.h; each lists
 * its entries with a required/optional mark (tacta_api_field) so the loader can name a missing one.
 */
#ifndef TACTA_PLUGIN_H
#define TACTA_PLUGIN_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32)
#define TACTA_EXPORT __declspec(dllexport)
#else
#define TACTA_EXPORT __attribute__((visibility("default")))
#endif

/* ---- ABI id: major(16) | minor(16) | build bits(32) ------------------------------------------ */
/* Major must match exactly; a plugin built against a newer minor than the host is refused. */
#define TACTA_ABI_MAJOR 1u
#define TACTA_ABI_MINOR \
  3u /* 1.1: device_api surface and counters entries; 1.2: model_api describe; 1.3: model and \
        device state entries */

#define TACTA_ABI_BIT_SCALAR_DOUBLE (1u << 0) /* state arrays are double, not float */
#define TACTA_ABI_BIT_POINTER_64 (1u << 1)    /* 64-bit pointers */
#define TACTA_ABI_BIT_LITTLE_ENDIAN (1u << 2) /* little-endian byte order */
#define TACTA_ABI_BIT_INDEX_32 (1u << 3)      /* element indices are uint32_t */
#define TACTA_ABI_BIT_COUNT 4u

static inline uint32_t tacta_abi_build_bits(void) {
  uint32_t bits = TACTA_ABI_BIT_INDEX_32;
#ifndef TACTA_SCALAR_FLOAT
  bits |= TACTA_ABI_BIT_SCALAR_DOUBLE;
#endif
  if (sizeof(void*) == 8) bits |= TACTA_ABI_BIT_POINTER_64;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  bits |= TACTA_ABI_BIT_LITTLE_ENDIAN;
#endif
  return bits;
}

static inline uint64_t tacta_abi_make(uint32_t major, uint32_t minor, uint32_t bits) {
  return ((uint64_t)(major & 0xffffu) << 48) | ((uint64_t)(minor & 0xffffu) << 32) | (uint64_t)bits;
}
static inline uint32_t tacta_abi_major(uint64_t id) { return (uint32_t)(id >> 48) & 0xffffu; }
static inline uint32_t tacta_abi_minor(uint64_t id) { return (uint32_t)(id >> 32) & 0xffffu; }
static inline uint32_t tacta_abi_bits(uint64_t id) { return (uint32_t)(id & 0xffffffffu); }

/* The ABI id of whatever is being compiled now (host or plugin). */
#define TACTA_ABI_ID tacta_abi_make(TACTA_ABI_MAJOR, TACTA_ABI_MINOR, tacta_abi_build_bits())

static inline const char* tacta_abi_bit_name(uint32_t bit) {
  switch (bit) {
    case TACTA_ABI_BIT_SCALAR_DOUBLE: return "scalar type (double vs float)";
    case TACTA_ABI_BIT_POINTER_64: return "pointer size (64-bit vs 32-bit)";
    case TACTA_ABI_BIT_LITTLE_ENDIAN: return "byte order (little vs big endian)";
    case TACTA_ABI_BIT_INDEX_32: return "index type (uint32_t)";
    default: return "unknown build bit";
  }
}

/* ---- status codes ----------------------------------------------------------------------------- */
typedef int32_t tacta_status;
#define TACTA_OK 0
#define TACTA_ERR_ABI 1              /* host and plugin ABI ids differ */
#define TACTA_ERR_INVALID_ARGUMENT 2 /* a parameter, mesh or state the plugin cannot accept */
#define TACTA_ERR_OUT_OF_MEMORY 3
#define TACTA_ERR_UNSUPPORTED 4 /* the call is not possible with this instance */
#define TACTA_ERR_IO 5          /* a file the plugin reads or writes */
#define TACTA_ERR_INTERNAL 6
#define TACTA_ERR_DUPLICATE 7 /* host: a descriptor with this name is registered already */

/* ---- kinds ------------------------------------------------------------------------------------ */
typedef int32_t tacta_kind;
#define TACTA_KIND_MODEL 1     /* elastic model: tacta_model_api (model_api.h) */
#define TACTA_KIND_COLLISION 2 /* collision method: tacta_collision_api (collision_api.h) */
#define TACTA_KIND_DEVICE 3    /* haptic device: tacta_device_api (device_api.h) */

static inline const char* tacta_kind_name(tacta_kind kind) {
  switch (kind) {
    case TACTA_KIND_MODEL: return "model";
    case TACTA_KIND_COLLISION: return "collision";
    case TACTA_KIND_DEVICE: return "device";
    default: return "unknown";
  }
}

/* ---- parameter schema ------------------------------------------------------------------------- */
/* The engine validates scene values against this schema (type, range, choices) before create(),
 * and the viewer builds its sliders from it. Values reach the plugin in schema order. */
typedef int32_t tacta_param_type;
#define TACTA_PARAM_REAL 1   /* double within [min_value, max_value] */
#define TACTA_PARAM_INT 2    /* integer within [min_value, max_value] */
#define TACTA_PARAM_BOOL 3   /* 0 or 1 */
#define TACTA_PARAM_CHOICE 4 /* one of choices ("a|b|c"); value.number is the index */
#define TACTA_PARAM_TEXT 5   /* free text, e.g. a file path (relative paths: to the scene file) */
#define TACTA_PARAM_VECTOR 6 /* list of doubles, a multiple of vector_stride long, each in range */

typedef struct tacta_param_spec {
  const char* name; /* snake_case key used in scenes */
  tacta_param_type type;
  const char* unit;         /* SI unit ("Pa", "s", "N/m"), "" when dimensionless */
  double default_value;     /* REAL/INT/BOOL; CHOICE: index of the default choice */
  double min_value;         /* inclusive; REAL/INT/VECTOR elements */
  double max_value;         /* inclusive */
  const char* choices;      /* CHOICE: "a|b|c"; else NULL */
  const char* default_text; /* TEXT default; VECTOR default as space-separated numbers; else NULL */
  uint32_t vector_stride;   /* VECTOR: values come in groups of this size (e.g. 3 for xyz) */
  const char* help;         /* one line for --help, docs and tooltips */
} tacta_param_spec;

typedef struct tacta_param_value {
  double number;        /* REAL, INT, BOOL, CHOICE index */
  const char* text;     /* TEXT; CHOICE: the chosen name; else NULL */
  const double* values; /* VECTOR; else NULL */
  uint32_t count;       /* VECTOR length */
} tacta_param_value;

/* ---- function tables: required and optional entries ------------------------------------------- */
typedef struct tacta_api_field {
  const char* name; /* the member name, as it appears in error messages */
  size_t offset;    /* offsetof within the kind's api struct */
  int required;     /* 1: the loader refuses a descriptor where this pointer is NULL */
} tacta_api_field;

/* ---- descriptor ------------------------------------------------------------------------------- */
typedef struct tacta_descriptor {
  uint32_t struct_size; /* sizeof(tacta_descriptor) as the plugin saw it */
  uint64_t abi;         /* the plugin's TACTA_ABI_ID */
  tacta_kind kind;
  const char* name;        /* unique per kind, snake_case: "tensor_mass", "sim_stylus" */
  uint32_t version;        /* the plugin's own version, major*10000 + minor*100 + patch */
  const char* description; /* one line */
  const tacta_param_spec* params;
  uint32_t param_count;
  const void* api;   /* const tacta_model_api*, tacta_collision_api* or tacta_device_api* */
  uint32_t api_size; /* sizeof of that struct as the plugin saw it */
} tacta_descriptor;

/* ---- the host, as the plugin sees it ---------------------------------------------------------- */
#define TACTA_LOG_DEBUG 0
#define TACTA_LOG_INFO 1
#define TACTA_LOG_WARN 2
#define TACTA_LOG_ERROR 3

typedef struct tacta_host {
  uint32_t struct_size;
  void* context;
  /* Copies nothing: descriptor and everything it points to must live as long as the library. */
  tacta_status (*register_descriptor)(void* context, const tacta_descriptor* descriptor);
  void (*log)(void* context, int32_t level, const char* message); /* not from the 1 kHz path */
} tacta_host;

/* The one exported symbol. Writes a NUL-terminated reason to message when it returns non-zero. */
typedef tacta_status (*tacta_plugin_entry_fn)(uint64_t host_abi, const tacta_host* host,
                                              char* message, size_t message_capacity);
#define TACTA_PLUGIN_ENTRY_SYMBOL "tacta_plugin_entry"

/* Writes into message which build bit or version differs between host and plugin; returns 1 if
 * they are compatible, 0 if not. Used on both sides so both name the bit the same way. */
static inline int tacta_abi_check(uint64_t host, uint64_t plugin, char* message, size_t capacity) {
  uint32_t diff;
  unsigned index;
  if (tacta_abi_major(host) != tacta_abi_major(plugin)) {
    if (message && capacity)
      snprintf(message, capacity, "ABI major version differs (host %u, plugin %u)",
               tacta_abi_major(host), tacta_abi_major(plugin));
    return 0;
  }
  if (tacta_abi_minor(plugin) > tacta_abi_minor(host)) {
    if (message && capacity)
      snprintf(message, capacity, "plugin needs ABI minor version %u, host has %u",
               tacta_abi_minor(plugin), tacta_abi_minor(host));
    return 0;
  }
  diff = tacta_abi_bits(host) ^ tacta_abi_bits(plugin);
  if (diff == 0) return 1;
  for (index = 0; !(diff & (1u << index)); ++index) {
  }
  if (message && capacity)
    snprintf(message, capacity, "build bit %u differs: %s (host %s, plugin %s)", index,
             tacta_abi_bit_name(1u << index),
             (tacta_abi_bits(host) >> index) & 1u ? "set" : "clear",
             (tacta_abi_bits(plugin) >> index) & 1u ? "set" : "clear");
  return 0;
}

#ifdef __cplusplus
}
#endif

#endif /* TACTA_PLUGIN_H */
