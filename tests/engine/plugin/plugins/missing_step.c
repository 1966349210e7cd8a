/* Test plugin, in plain C: a model descriptor whose required `step` entry is NULL. */
#include "tacta/model_api.h"

static tacta_status create(const tacta_model_setup* setup, void** instance, char* message,
                           size_t capacity) {
  (void)setup;
  (void)message;
  (void)capacity;
  *instance = 0;
  return TACTA_OK;
}
static void destroy(void* instance) { (void)instance; }

/* step left out on purpose; designated, so entries appended to the API need no edit here */
static const tacta_model_api api = {.create = create, .destroy = destroy};

TACTA_EXPORT tacta_status tacta_plugin_entry(uint64_t host_abi, const tacta_host* host,
                                             char* message, size_t capacity) {
  tacta_descriptor descriptor_template = {sizeof(tacta_descriptor),
                                          0,
                                          TACTA_KIND_MODEL,
                                          "test_missing_step",
                                          1,
                                          "no step function (test only)",
                                          0,
                                          0,
                                          &api,
                                          sizeof(tacta_model_api)};
  static tacta_descriptor descriptor;
  if (!tacta_abi_check(host_abi, TACTA_ABI_ID, message, capacity)) return TACTA_ERR_ABI;
  descriptor = descriptor_template;
  descriptor.abi = TACTA_ABI_ID;
  return host->register_descriptor(host->context, &descriptor);
}
