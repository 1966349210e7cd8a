// The model panel: for a chosen body, a combo of every loaded model plugin and widgets built from
// the selected model's parameter schema (REAL/INT sliders over their range, BOOL checkbox,
// CHOICE combo). Choosing a model swaps it in with its defaults; releasing a widget swaps in the
// same model with the new values (Simulation::request_model_swap, state carried over).
#pragma once

#include <string>
#include <vector>

#include "param_values.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta::view {

class ModelPanel {
 public:
  ModelPanel(const PluginRegistry& plugins, Simulation& simulation, const SceneDesc& scene);

  void draw();  // Dear ImGui widgets, inside the caller's window

  // The same actions without the GUI (the --script driver). False, with error(), on refusal.
  bool swap_model(const std::string& body, const std::string& model);
  bool set_param(const std::string& body, const std::string& name, double number);

  const std::string& error() const { return error_; }
  int swaps() const { return swaps_; }  // requests the simulation accepted
  // "body -> model" per accepted request, oldest first.
  const std::vector<std::string>& history() const { return history_; }

 private:
  struct BodyState {
    std::string model;
    std::vector<ParamValue> values;
  };
  bool choose_model(size_t body, const std::string& model);  // defaults
  bool apply(size_t body);
  bool param_widget(ParamValue& value);  // true when an edit is complete
  size_t body_index(const std::string& name);

  const PluginRegistry& plugins_;
  Simulation& simulation_;
  std::vector<std::string> model_names_;
  std::vector<std::string> body_names_;
  std::vector<BodyHandle> handles_;  // per scene body, as body_names_
  std::vector<BodyState> bodies_;
  size_t selected_ = 0;
  std::string error_;
  int swaps_ = 0;
  std::vector<std::string> history_;
};

}  // namespace tacta::view
