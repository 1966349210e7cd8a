/* A model plugin that breaks two rules on purpose, for the check-plugin test: every node feels a
 * constant 1 N along +x even at rest (so "force at rest" fails), and step() allocates (so "no
 * allocation in step" fails). Plain C, through the public headers only, as an outside author
 * would write it. */
#include <stdlib.h>
#include <string.h>

#include "tacta/model_api.h"

typedef struct broken_model {
  uint32_t node_count;
  const double* masses;
} broken_model;

static tacta_status broken_create(const tacta_model_setup* setup, void** instance, char* message,
                                  size_t message_capacity) {
  broken_model* model = (broken_model*)calloc(1, sizeof(broken_model));
  (void)message;
  (void)message_capacity;
  if (model == NULL) return TACTA_ERR_OUT_OF_MEMORY;
  model->node_count = setup->mesh->node_count;
  model->masses = setup->masses;
  *instance = model;
  return TACTA_OK;
}

static void broken_destroy(void* instance) { free(instance); }

static void broken_forces(void* instance, const double* positions, double* forces) {
  const broken_model* model = (const broken_model*)instance;
  (void)positions;
  memset(forces, 0, sizeof(double) * 3 * model->node_count);
  for (uint32_t n = 0; n < model->node_count; ++n) forces[3 * n] = 1.0; /* N, at any shape */
}

static uint32_t broken_step(void* instance, tacta_body_state* state, double dt) {
  const broken_model* model = (const broken_model*)instance;
  double* forces = (double*)malloc(sizeof(double) * 3 * model->node_count); /* the 1 kHz sin */
  if (forces == NULL) return TACTA_STEP_DIVERGED;
  broken_forces(instance, state->positions, forces);
  for (uint32_t i = 0; i < 3 * model->node_count; ++i) {
    state->velocities[i] += dt * (forces[i] + state->external_forces[i]) / model->masses[i / 3];
    state->positions[i] += dt * state->velocities[i];
  }
  free(forces);
  for (uint32_t i = 0; i < 3 * model->node_count; ++i)
    if (state->positions[i] != state->positions[i]) return TACTA_STEP_NOT_FINITE;
  return TACTA_STEP_OK;
}

static const tacta_param_spec broken_params[] = {
    {"unused_gain", TACTA_PARAM_REAL, "", 1.0, 0.0, 10.0, NULL, NULL, 0, "does nothing"},
};

static tacta_model_api broken_api(void) {
  tacta_model_api api;
  memset(&api, 0, sizeof api);
  api.create = broken_create;
  api.destroy = broken_destroy;
  api.step = broken_step;
  api.internal_forces = broken_forces;
  api.claims = TACTA_MODEL_CLAIM_MOMENTUM; /* a false claim: the forces do not cancel */
  return api;
}

TACTA_EXPORT tacta_status tacta_plugin_entry(uint64_t host_abi, const tacta_host* host,
                                             char* message, size_t message_capacity) {
  static tacta_model_api api;
  static tacta_descriptor descriptor;
  if (!tacta_abi_check(host_abi, TACTA_ABI_ID, message, message_capacity)) return TACTA_ERR_ABI;
  api = broken_api();
  descriptor.struct_size = sizeof descriptor;
  descriptor.abi = TACTA_ABI_ID;
  descriptor.kind = TACTA_KIND_MODEL;
  descriptor.name = "broken_model";
  descriptor.version = 100;
  descriptor.description = "pushes at rest and allocates in step (check-plugin test)";
  descriptor.params = broken_params;
  descriptor.param_count = 1;
  descriptor.api = &api;
  descriptor.api_size = sizeof api;
  return host->register_descriptor(host->context, &descriptor);
}
