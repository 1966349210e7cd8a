// Runs the Z-width scene in process (lockstep, deterministic) for one model, coupling and
// stiffness, and judges the contact with the criterion of zwidth_criterion.hpp; finds the largest
// stable coupling stiffness by bisection.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "zwidth_criterion.hpp"

namespace tacta {
class PluginRegistry;
}

namespace tacta::bench {

struct ZwidthCase {
  std::string model;                   // a model as the scene's `model:` key takes it (YAML)
  double coupling_damping = 0.0;       // N s/m
  bool passivity = false;              // the passivity controller acts
  std::vector<std::string> overrides;  // further key=value overrides (e.g. the hand)
};

struct ZwidthSearch {
  double k_min = 100.0;      // N/m, lowest stiffness tried
  double k_max = 100000.0;   // N/m, highest stiffness tried
  double resolution = 1.05;  // stop when k_unstable / k_stable is below this ratio
};

struct ZwidthResult {
  double largest_stable = 0.0;     // N/m; 0 when even k_min is unstable
  double smallest_unstable = 0.0;  // N/m; 0 when even k_max is stable
  StabilityVerdict at_largest_stable;
  std::string unstable_reason;  // the verdict at smallest_unstable
  int runs = 0;
};

class ZwidthRunner {
 public:
  // scene: the Z-width scene file; work_dir: where each run writes its trace (overwritten).
  ZwidthRunner(std::string scene, std::string work_dir, const std::string& plugin_dir);
  ~ZwidthRunner();
  ZwidthRunner(const ZwidthRunner&) = delete;
  ZwidthRunner& operator=(const ZwidthRunner&) = delete;

  StabilityVerdict run(const ZwidthCase& c, double stiffness);
  // Bisection in log(stiffness), assuming one stable range [k_min, k*] (checked at both ends).
  ZwidthResult largest_stable(const ZwidthCase& c, const ZwidthSearch& search);
  StabilityCriterion criterion;

 private:
  std::string scene_, work_dir_;
  std::unique_ptr<PluginRegistry> plugins_;
};

}  // namespace tacta::bench
