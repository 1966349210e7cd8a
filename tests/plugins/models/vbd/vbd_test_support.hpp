// Shared helpers for the vbd tests: a model built straight from the core library, and the
// engine's own JobPool behind the host services, so the parallel path runs as in the engine.
// The body state arrays are the corotational tests' BodyState.
#pragma once

#include <atomic>
#include <memory>

#include "corotational_test_support.hpp"
#include "services/job_pool.hpp"
#include "vbd_model.hpp"

namespace tacta::models::vbd::testing {

using corotational::testing::BodyState;

inline std::unique_ptr<VbdModel> make_vbd(const TestMesh& mesh, const tacta_material& material,
                                          const Options& options = {}) {
  return std::make_unique<VbdModel>(mesh.view(), material, mesh.masses, mesh.fixed, options);
}

// tacta_host_services over a JobPool of `threads`, as the engine fills them, counting the
// parallel_for calls that had more than one chunk (the ones that could use a worker).
struct PoolHost {
  explicit PoolHost(uint32_t threads) : pool(threads) {
    services.struct_size = sizeof services;
    services.worker_count = pool.threads();
    services.parallel_for = &PoolHost::counted;
    services.jobs = this;
  }
  static void counted(void* jobs, uint32_t count, uint32_t grain,
                      void (*body)(void*, uint32_t, uint32_t, uint32_t), void* user) {
    auto& self = *static_cast<PoolHost*>(jobs);
    if (count > grain) self.split_calls.fetch_add(1, std::memory_order_relaxed);
    self.pool.parallel_for(count, grain, body, user);
  }
  JobPool pool;
  std::atomic<long> split_calls{0};
  tacta_host_services services{};
};

}  // namespace tacta::models::vbd::testing
