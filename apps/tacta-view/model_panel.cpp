#include "model_panel.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <imgui.h>

namespace tacta::view {

ModelPanel::ModelPanel(const PluginRegistry& plugins, Simulation& simulation,
                       const SceneDesc& scene)
    : plugins_(plugins), simulation_(simulation) {
  for (const LoadedDescriptor& d : plugins.list())
    if (d.descriptor->kind == TACTA_KIND_MODEL) model_names_.emplace_back(d.descriptor->name);
  for (const BodyDesc& b : scene.bodies) {
    body_names_.push_back(b.name);
    handles_.push_back(simulation.body(b.name));
    BodyState state;
    state.model = b.model;
    if (auto schema = plugins.schema(TACTA_KIND_MODEL, b.model))
      state.values = param_values(*schema, &b.model_params);
    bodies_.push_back(std::move(state));
  }
}

size_t ModelPanel::body_index(const std::string& name) {
  for (size_t i = 0; i < body_names_.size(); ++i)
    if (body_names_[i] == name) return i;
  error_ = "no body named '" + name + "'";
  return body_names_.size();
}

bool ModelPanel::swap_model(const std::string& body, const std::string& model) {
  const size_t i = body_index(body);
  return i < bodies_.size() && choose_model(i, model);
}

bool ModelPanel::set_param(const std::string& body, const std::string& name, double number) {
  const size_t i = body_index(body);
  if (i >= bodies_.size()) return false;
  for (ParamValue& v : bodies_[i].values)
    if (name == v.spec->name) {
      v.number = number;
      return apply(i);
    }
  error_ = "model " + bodies_[i].model + " has no parameter '" + name + "'";
  return false;
}

bool ModelPanel::choose_model(size_t body, const std::string& model) {
  const auto schema = plugins_.schema(TACTA_KIND_MODEL, model);
  if (!schema) {
    error_ = plugins_.unknown_name_message(TACTA_KIND_MODEL, model);
    return false;
  }
  BodyState previous = bodies_[body];
  bodies_[body].model = model;
  bodies_[body].values = param_values(*schema);
  if (apply(body)) return true;
  bodies_[body] = std::move(previous);  // the refused model leaves the panel as it was
  return false;
}

bool ModelPanel::apply(size_t body) {
  try {
    simulation_.request_model_swap(handles_[body], bodies_[body].model,
                                   to_param_set(bodies_[body].values));
  } catch (const std::exception& e) {
    error_ = e.what();
    return false;
  }
  error_.clear();
  ++swaps_;
  history_.push_back(body_names_[body] + " -> " + bodies_[body].model);
  return true;
}

bool ModelPanel::param_widget(ParamValue& value) {
  const tacta_param_spec& spec = *value.spec;
  bool done = false;
  switch (spec.type) {
    case TACTA_PARAM_REAL: {
      const double lo = spec.min_value, hi = spec.max_value;
      if (lo >= 0 && hi > 1e3 * std::max(lo, 1e-300)) {
        ImGui::SliderScalar(spec.name, ImGuiDataType_Double, &value.number, &lo, &hi, "%.4g",
                            ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
      } else if (hi - lo <= 1e4) {
        ImGui::SliderScalar(spec.name, ImGuiDataType_Double, &value.number, &lo, &hi, "%.4g",
                            ImGuiSliderFlags_AlwaysClamp);
      } else {
        ImGui::InputDouble(spec.name, &value.number, 0, 0, "%.6g");
        value.number = std::clamp(value.number, lo, hi);
      }
      done = ImGui::IsItemDeactivatedAfterEdit();
      break;
    }
    case TACTA_PARAM_INT: {
      int n = static_cast<int>(value.number);
      const int lo = static_cast<int>(spec.min_value), hi = static_cast<int>(spec.max_value);
      ImGui::SliderInt(
          spec.name, &n, lo, hi, "%d",
          ImGuiSliderFlags_AlwaysClamp | (hi - lo > 1000 ? ImGuiSliderFlags_Logarithmic : 0));
      value.number = n;
      done = ImGui::IsItemDeactivatedAfterEdit();
      break;
    }
    case TACTA_PARAM_BOOL: {
      bool on = value.number != 0;
      done = ImGui::Checkbox(spec.name, &on);
      value.number = on ? 1 : 0;
      break;
    }
    case TACTA_PARAM_CHOICE: {
      const std::vector<std::string> names = choice_names(spec);
      const auto current = static_cast<size_t>(value.number);
      if (ImGui::BeginCombo(spec.name, current < names.size() ? names[current].c_str() : "?")) {
        for (size_t k = 0; k < names.size(); ++k)
          if (ImGui::Selectable(names[k].c_str(), k == current)) {
            value.number = static_cast<double>(k);
            done = k != current;
          }
        ImGui::EndCombo();
      }
      break;
    }
    case TACTA_PARAM_TEXT: ImGui::TextDisabled("%s: %s", spec.name, value.text.c_str()); break;
    default: ImGui::TextDisabled("%s: %zu values", spec.name, value.values.size()); break;
  }
  if (ImGui::IsItemHovered() && spec.help != nullptr)
    ImGui::SetTooltip("%s%s%s%s", spec.help, spec.unit && *spec.unit ? " (" : "",
                      spec.unit ? spec.unit : "", spec.unit && *spec.unit ? ")" : "");
  return done;
}

void ModelPanel::draw() {
  if (bodies_.empty()) {
    ImGui::TextDisabled("no bodies");
    return;
  }
  if (ImGui::BeginCombo("body", body_names_[selected_].c_str())) {
    for (size_t i = 0; i < body_names_.size(); ++i)
      if (ImGui::Selectable(body_names_[i].c_str(), i == selected_)) selected_ = i;
    ImGui::EndCombo();
  }
  BodyState& body = bodies_[selected_];
  if (ImGui::BeginCombo("model", body.model.c_str())) {
    for (const std::string& name : model_names_)
      if (ImGui::Selectable(name.c_str(), name == body.model) && name != body.model)
        choose_model(selected_, name);
    ImGui::EndCombo();
  }
  ImGui::PushID(static_cast<int>(selected_));
  for (ParamValue& value : body.values)
    if (param_widget(value)) apply(selected_);
  ImGui::PopID();
  if (!error_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_.c_str());
  ImGui::Text("swaps requested: %d", swaps_);
}

}  // namespace tacta::view
