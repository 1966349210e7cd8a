// ParamSet: plugin parameter values that own their storage and expose C views of it (header-only,
// so plugins and tests that do not link the engine use the same type).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tacta/plugin.h"

namespace tacta {

// Plugin parameter values resolved against the plugin's schema (schema order, defaults filled),
// owning the storage that the C views in `values` point into.
class ParamSet {
 public:
  ParamSet() = default;
  ParamSet(const ParamSet& other) { *this = other; }
  ParamSet& operator=(const ParamSet& other) {
    if (this == &other) return *this;
    names_ = other.names_;
    values_ = other.values_;
    kinds_ = other.kinds_;
    texts_ = other.texts_;
    vectors_ = other.vectors_;
    relink();
    return *this;
  }
  // Moves relink too: a short std::string's characters move with it.
  ParamSet(ParamSet&& other) noexcept { *this = std::move(other); }
  ParamSet& operator=(ParamSet&& other) noexcept {
    names_ = std::move(other.names_);
    values_ = std::move(other.values_);
    kinds_ = std::move(other.kinds_);
    texts_ = std::move(other.texts_);
    vectors_ = std::move(other.vectors_);
    relink();
    return *this;
  }

  // Appends one value (in schema order); text and vector storage are copied in.
  void add_number(const std::string& name, double number) {
    append(name, Kind::Number, number, {}, {});
  }
  void add_text(const std::string& name, const std::string& text, double choice_index = 0) {
    append(name, Kind::Text, choice_index, text, {});
  }
  void add_vector(const std::string& name, std::vector<double> values) {
    append(name, Kind::Vector, 0.0, {}, std::move(values));
  }

  const tacta_param_value* data() const { return values_.data(); }
  uint32_t size() const { return static_cast<uint32_t>(values_.size()); }
  const std::vector<std::string>& names() const { return names_; }
  const tacta_param_value* find(const std::string& name) const {
    for (size_t i = 0; i < names_.size(); ++i)
      if (names_[i] == name) return &values_[i];
    return nullptr;
  }
  // Sets an existing number value (REAL/INT/BOOL); false when there is no value of that name.
  bool set_number(const std::string& name, double number) {
    for (size_t i = 0; i < names_.size(); ++i)
      if (names_[i] == name && kinds_[i] == Kind::Number) {
        values_[i].number = number;
        return true;
      }
    return false;
  }

 private:
  enum class Kind { Number, Text, Vector };
  void append(const std::string& name, Kind kind, double number, std::string text,
              std::vector<double> values) {
    names_.push_back(name);
    kinds_.push_back(kind);
    values_.push_back(tacta_param_value{number, nullptr, nullptr, 0});
    texts_.push_back(std::move(text));
    vectors_.push_back(std::move(values));
    relink();
  }
  // Re-points the C views after a copy, a move or a growth.
  void relink() {
    for (size_t i = 0; i < values_.size(); ++i) {
      values_[i].text = kinds_[i] == Kind::Text ? texts_[i].c_str() : nullptr;
      values_[i].values = kinds_[i] == Kind::Vector ? vectors_[i].data() : nullptr;
      values_[i].count = kinds_[i] == Kind::Vector ? static_cast<uint32_t>(vectors_[i].size()) : 0;
    }
  }
  std::vector<std::string> names_;
  std::vector<tacta_param_value> values_;
  std::vector<Kind> kinds_;
  std::vector<std::string> texts_;            // 1 per value; used by TEXT and CHOICE
  std::vector<std::vector<double>> vectors_;  // 1 per value; used by VECTOR
};

}  // namespace tacta
