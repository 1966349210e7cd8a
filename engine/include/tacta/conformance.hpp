// The model-plugin conformance suite behind `tacta check-plugin`: what every elastic model must
// do whatever its method (zero force at rest and under rigid motion, momentum where it claims it,
// a quiet 1 kHz step, NaN reported, a sane schema, any thread may step it). Each check builds
// its own instance on a small built-in cube and returns one line with its figure.
#pragma once

#include <string>
#include <vector>

#include "tacta/plugin.h"

namespace tacta::conformance {

// Heap allocations are counted by whoever owns malloc (the executable interposes it); when
// start is null the allocation check is skipped and `unavailable` says why.
struct AllocationProbe {
  void (*start)() = nullptr;  // begin counting from zero
  long (*stop)() = nullptr;   // stop counting; returns allocations since start
  std::string unavailable;
};

enum class Verdict { Pass, Fail, Skip };

struct CheckResult {
  std::string name;    // e.g. "net internal force"
  std::string figure;  // what was measured and the limit, e.g. "|sum f| 3.2e-15 N, limit 1e-9 N"
  Verdict verdict = Verdict::Pass;
};

// Runs every check on a model descriptor (kind TACTA_KIND_MODEL), its parameters at their
// defaults. Never throws for a misbehaving plugin: a create() refusal is a failed check.
std::vector<CheckResult> check_model(const tacta_descriptor& model, const AllocationProbe& probe);

const char* verdict_name(Verdict verdict);

}  // namespace tacta::conformance
