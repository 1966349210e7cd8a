#include "tacta/sim/cut.hpp"

namespace tacta {

const char* cut_mode_name(CutMode mode) noexcept {
  switch (mode) {
    case CutMode::kRemove: return "remove";
    case CutMode::kSeparate: return "separate";
  }
  return "unknown";
}

bool parse_cut_mode(const std::string& name, CutMode& mode) noexcept {
  for (CutMode m : {CutMode::kRemove, CutMode::kSeparate}) {
    if (name == cut_mode_name(m)) {
      mode = m;
      return true;
    }
  }
  return false;
}

}  // namespace tacta
