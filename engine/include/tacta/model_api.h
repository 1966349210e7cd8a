/* Elastic model plugins (kind TACTA_KIND_MODEL): the function table and the data it sees.
 *
 * The engine owns the body state (positions, velocities, forces) so that a body can change model
 * while the scene runs; a model instance owns only what it precomputes (stiffness blocks,
 * factorisations, history). create() may allocate; step() runs in the 1 kHz path and must not
 * allocate, lock or throw: it reports trouble through the returned TACTA_STEP_* bits.
 * Units: SI throughout (m, s, kg, N, Pa, J).
 */
#ifndef TACTA_MODEL_API_H
#define TACTA_MODEL_API_H

#include "tacta/plugin.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Material in SI units; the engine fills both (E, nu) and (lambda, mu) consistently. */
typedef struct tacta_material {
  double youngs_modulus;     /* E, Pa */
  double poisson_ratio;      /* nu, dimensionless, in (-1, 0.5) */
  double density;            /* rho, kg/m^3 (kg/m^2 for planar meshes of unit thickness) */
  double lame_lambda;        /* lambda, Pa */
  double lame_mu;            /* mu (shear modulus), Pa */
  double rayleigh_mass;      /* alpha, 1/s: damping force -alpha M v */
  double rayleigh_stiffness; /* beta, s: damping force -beta K v */
} tacta_material;

/* The rest geometry and topology of a body. Arrays are owned by the engine and outlive the model
 * instance. Any of the element lists may be empty; edges always hold every unique element edge. */
typedef struct tacta_mesh_view {
  uint32_t node_count;
  const double* rest_positions; /* 3 per node, m */
  uint32_t tet_count;
  const uint32_t* tets; /* 4 per tet, positively oriented (det(x1-x0, x2-x0, x3-x0) > 0) */
  uint32_t triangle_count;
  const uint32_t* triangles; /* 3 per triangle: the boundary surface, outward, counter-clockwise */
  uint32_t quad_count;
  const uint32_t* quads; /* 4 per quad, counter-clockwise (planar meshes such as the unit square) */
  uint32_t edge_count;
  const uint32_t* edges; /* 2 per edge, unique and undirected, i < j */
  uint32_t dimension;    /* 3 for volume meshes; 2 for planar meshes (unit thickness, 1 m) */
} tacta_mesh_view;

/* Engine services handed to a model instance (Jolt's job-system model: the engine owns the
 * threads and the memory, a plugin only asks). */
typedef struct tacta_host_services {
  uint32_t struct_size;
  /* threads parallel_for runs on, the calling thread included; 1: it runs serially */
  uint32_t worker_count;
  /* Runs body(user, begin, end, worker) over [0, count) in chunks of `grain` indices, on the
   * engine's workers and the calling thread (worker < worker_count), and returns when every
   * chunk is done. Allocation- and lock-free: callable from step(). When another body is using
   * the workers it runs serially on the caller (worker 0). Not re-entrant from inside body. */
  void (*parallel_for)(void* jobs, uint32_t count, uint32_t grain,
                       void (*body)(void* user, uint32_t begin, uint32_t end, uint32_t worker),
                       void* user);
  void* jobs;
  /* Memory the engine owns for the instance's life (freed after destroy), 64-byte aligned and
   * zeroed; only during create(). NULL when `bytes` is past what the engine grants. */
  void* (*scratch)(void* arena, size_t bytes);
  void* arena;
  /* appended (read only when struct_size reaches it): how many threads a parallel_for called
   * now, from this thread, can spread over: 1 while this thread runs one part of a split
   * parallel_for of the same engine (a body stepped in a group, one body per job) or steps a
   * body on a thread of its own (which shares the workers with the tick's bodies), else
   * worker_count. It depends on where the call is made, never on timing, so a model may pick
   * its code path by it each step and stay deterministic; the call may still run serially when
   * another body holds the workers. */
  uint32_t (*workers_here)(void* jobs);
} tacta_host_services;

/* Threads a parallel_for called now from this thread can spread over (see workers_here); an
 * engine that predates the entry answers worker_count. */
static inline uint32_t tacta_host_workers_here(const tacta_host_services* host) {
  if (host == NULL) return 1;
  if (host->struct_size < offsetof(tacta_host_services, workers_here) + sizeof host->workers_here ||
      host->workers_here == NULL)
    return host->worker_count;
  return host->workers_here(host->jobs);
}

/* What create() receives. Everything is valid only during create() unless stated otherwise. */
typedef struct tacta_model_setup {
  uint32_t struct_size;
  const tacta_mesh_view* mesh; /* valid for the instance's lifetime */
  const tacta_material* material;
  const double* masses; /* 1 per node, kg: lumped by the engine; valid for the lifetime */
  const uint8_t* fixed; /* 1 per node, 1 = held at its current position; valid for the lifetime */
  const tacta_param_value* params; /* validated against the descriptor's schema, schema order */
  uint32_t param_count;
  double dt; /* the step the engine will use, s (the haptic tick unless the body runs slower) */
  /* appended: engine services, valid for the instance's lifetime; NULL from an engine (or a
   * test) that offers none, or when struct_size does not reach this field */
  const tacta_host_services* host;
} tacta_model_setup;

/* The state a step advances, in place. The engine has already added gravity (m g), contact and
 * user forces into external_forces, which are constant over the step. */
typedef struct tacta_body_state {
  uint32_t node_count;
  double* positions;             /* 3 per node, m */
  double* velocities;            /* 3 per node, m/s */
  const double* external_forces; /* 3 per node, N */
  double time;                   /* s, at the start of the step */
} tacta_body_state;

/* Step result bits: 0 is success. The engine freezes the body on any fault bit. */
#define TACTA_STEP_OK 0u
#define TACTA_STEP_NOT_FINITE (1u << 0)           /* fault: NaN or infinity in the new state */
#define TACTA_STEP_DIVERGED (1u << 1)             /* fault: energy or displacement blew up */
#define TACTA_STEP_SOLVER_NOT_CONVERGED (1u << 2) /* warning: iterative solver hit its limit */
#define TACTA_STEP_INVERTED_ELEMENT (1u << 3)     /* warning: an element turned inside out */
#define TACTA_STEP_FAULT_MASK (TACTA_STEP_NOT_FINITE | TACTA_STEP_DIVERGED)

/* A named figure a model keeps about its own work since create() (solver fallbacks, Newton
 * iterations), for report.json. name: static storage, snake_case. */
typedef struct tacta_model_counter {
  const char* name;
  double value;
} tacta_model_counter;

/* What a model guarantees about its internal forces (tacta_model_api.claims); `tacta check-plugin`
 * tests each property a model claims and skips the others. */
#define TACTA_MODEL_CLAIM_ROTATION_INVARIANT (1u << 0) /* no force under a rigid rotation */
#define TACTA_MODEL_CLAIM_MOMENTUM (1u << 1) /* internal forces sum to zero at any shape */
/* step() reads nothing an earlier step wrote: positions, velocities and the parameters are the
 * whole state, so a checkpoint needs no save_state/load_state from this model. */
#define TACTA_MODEL_CLAIM_NO_HISTORY (1u << 2)
/* The model may be rebuilt mid-run on an edited mesh (cutting): create() on the new mesh, then
 * begin() with the carried-over positions and velocities, continues correctly (the instance keeps
 * no state that a rebuild on the new mesh would make wrong). The engine refuses cuts on bodies
 * whose model does not claim it. */
#define TACTA_MODEL_CLAIM_TOPOLOGY_EDITS (1u << 3)

typedef struct tacta_model_api {
  /* required: build an instance for one body; may allocate. Writes a reason on failure. */
  tacta_status (*create)(const tacta_model_setup* setup, void** instance, char* message,
                         size_t message_capacity);
  /* required */
  void (*destroy)(void* instance);
  /* required: advance state by dt seconds. 1 kHz path: no allocation, no lock, no throw. */
  uint32_t (*step)(void* instance, tacta_body_state* state, double dt);

  /* optional: the state was set from outside (first step, a model swap, a reset, a freeze);
   * re-initialise any history (e.g. central differences' previous position = x - dt v). */
  void (*begin)(void* instance, const tacta_body_state* state, double dt);
  /* optional: elastic (strain) energy at these positions, J. */
  double (*elastic_energy)(void* instance, const double* positions);
  /* optional: internal forces at these positions (3 per node, N), elastic only; used by tests
   * (zero at rest, rigid motions, patch tests) and by the haptic local contact model. */
  void (*internal_forces)(void* instance, const double* positions, double* forces);
  /* optional: change one parameter (schema index) while running; not from the 1 kHz path. */
  tacta_status (*set_param)(void* instance, uint32_t index, const tacta_param_value* value,
                            char* message, size_t message_capacity);
  /* optional: von Mises stress per node (Pa), for colour maps and VTK output. */
  void (*node_stress)(void* instance, const double* positions, double* von_mises);
  /* optional, appended (the engine reads it only when api_size reaches it): the model's counters;
   * writes at most capacity of them into out and returns how many it has. Not from the 1 kHz
   * path. */
  uint32_t (*counters)(void* instance, tacta_model_counter* out, uint32_t capacity);
  /* optional: one sentence on what the instance chose for this body that its parameters did not
   * say (an integrator picked for stability at dt, sub-steps), written into text (NUL-ended,
   * truncated to capacity); the engine puts it into report.json. Not from the 1 kHz path. */
  void (*describe)(void* instance, char* text, size_t capacity);
  /* optional, appended (0 when api_size does not reach it): TACTA_MODEL_CLAIM_* bits. A plain
   * flag word, not an entry: an older host simply never reads it, so the ABI minor stays. */
  uint32_t claims;
  /* optional, appended (NULL when api_size does not reach it): the parameters set_param changes
   * between steps without rebuilding the instance, as "name|name"; the engine changes any other
   * parameter by a swap to a fresh instance. Only REAL, INT and BOOL parameters can be live. */
  const char* live_params;
  /* optional, appended (NULL when api_size does not reach it): the instance's own evolving state,
   * for checkpoints: what step() reads that an earlier step wrote (element rotations, warm starts,
   * integrator history, counters), not what create() derives from the setup. save_state writes it
   * into bytes when capacity is enough and returns its size in bytes either way (call with
   * capacity 0 to ask). load_state sets it, on an instance created from the same setup, from what
   * save_state wrote; it checks size and content and returns an error with a reason otherwise.
   * The engine calls no begin() after a load: the next step() continues bit for bit as the saved
   * instance's would. A model with neither entry must claim TACTA_MODEL_CLAIM_NO_HISTORY to be
   * checkpointed. Not from the 1 kHz path. */
  size_t (*save_state)(void* instance, void* bytes, size_t capacity);
  tacta_status (*load_state)(void* instance, const void* bytes, size_t size, char* message,
                             size_t message_capacity);
} tacta_model_api;

/* The claims of a model table whose plugin saw api_size bytes of it (0 for an older plugin). */
static inline uint32_t tacta_model_claims(const tacta_model_api* api, uint32_t api_size) {
  return api_size >= offsetof(tacta_model_api, claims) + sizeof(uint32_t) ? api->claims : 0u;
}

/* Whether a model table has both checkpoint entries (0: either is NULL, or the plugin is older). */
static inline int tacta_model_has_state_entries(const tacta_model_api* api, uint32_t api_size) {
  return api_size >= offsetof(tacta_model_api, load_state) + sizeof(void*) &&
         api->save_state != NULL && api->load_state != NULL;
}

/* The live parameter list of a model table ("a|b"), NULL when the plugin has none or is older. */
static inline const char* tacta_model_live_params(const tacta_model_api* api, uint32_t api_size) {
  return api_size >= offsetof(tacta_model_api, live_params) + sizeof(const char*) ? api->live_params
                                                                                  : NULL;
}

#define TACTA_MODEL_API_FIELD(member, required) \
  { #member, offsetof(tacta_model_api, member), required }

static const tacta_api_field tacta_model_api_fields[] = {
    TACTA_MODEL_API_FIELD(create, 1),         TACTA_MODEL_API_FIELD(destroy, 1),
    TACTA_MODEL_API_FIELD(step, 1),           TACTA_MODEL_API_FIELD(begin, 0),
    TACTA_MODEL_API_FIELD(elastic_energy, 0), TACTA_MODEL_API_FIELD(internal_forces, 0),
    TACTA_MODEL_API_FIELD(set_param, 0),      TACTA_MODEL_API_FIELD(node_stress, 0),
    TACTA_MODEL_API_FIELD(counters, 0),       TACTA_MODEL_API_FIELD(describe, 0),
    TACTA_MODEL_API_FIELD(save_state, 0),     TACTA_MODEL_API_FIELD(load_state, 0),
};

#ifdef __cplusplus
}
#endif

#endif /* TACTA_MODEL_API_H */
