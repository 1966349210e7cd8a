#include "view_status.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace tacta::view {

void write_view_status(const std::string& path, const ViewStatus& s) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write the status file " + path);
  const nlohmann::ordered_json json = {{"frames", s.frames},
                                       {"sim_time_s", s.sim_time_s},
                                       {"wall_time_s", s.wall_time_s},
                                       {"marks", s.marks},
                                       {"swaps_requested", s.swaps_requested},
                                       {"swap_history", s.swap_history},
                                       {"body_models", s.body_models},
                                       {"body_frozen", s.body_frozen},
                                       {"body_revisions", s.body_revisions},
                                       {"cut_key_frames", s.cut_key_frames},
                                       {"max_force_N", s.max_force_N},
                                       {"mouse", s.mouse},
                                       {"mouse_target", s.mouse_target},
                                       {"stylus", s.stylus},
                                       {"script_failures", s.script_failures},
                                       {"model_error", s.model_error},
                                       {"run_error", s.run_error}};
  // Doubles round-trip, NaN and infinities are null, bytes that are not UTF-8 become U+FFFD.
  out << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
  if (!out) throw std::runtime_error("cannot write the status file " + path);
}

}  // namespace tacta::view
