// ParamSet: plugin parameter values that own their storage and expose C views of it.
#include "tacta/scene.hpp"

namespace tacta {

ParamSet& ParamSet::operator=(const ParamSet& other) {
  if (this == &other) return *this;
  names_ = other.names_;
  values_ = other.values_;
  kinds_ = other.kinds_;
  texts_ = other.texts_;
  vectors_ = other.vectors_;
  relink();
  return *this;
}

void ParamSet::add_number(const std::string& name, double number) {
  names_.push_back(name);
  kinds_.push_back(Kind::Number);
  values_.push_back(tacta_param_value{number, nullptr, nullptr, 0});
  texts_.emplace_back();
  vectors_.emplace_back();
  relink();
}

void ParamSet::add_text(const std::string& name, const std::string& text, double choice_index) {
  names_.push_back(name);
  kinds_.push_back(Kind::Text);
  values_.push_back(tacta_param_value{choice_index, nullptr, nullptr, 0});
  texts_.push_back(text);
  vectors_.emplace_back();
  relink();
}

void ParamSet::add_vector(const std::string& name, std::vector<double> values) {
  names_.push_back(name);
  kinds_.push_back(Kind::Vector);
  values_.push_back(tacta_param_value{0.0, nullptr, nullptr, 0});
  texts_.emplace_back();
  vectors_.push_back(std::move(values));
  relink();
}

const tacta_param_value* ParamSet::find(const std::string& name) const {
  for (size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return &values_[i];
  return nullptr;
}

bool ParamSet::set_number(const std::string& name, double number) {
  for (size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name && kinds_[i] == Kind::Number) {
      values_[i].number = number;
      return true;
    }
  return false;
}

void ParamSet::relink() {
  for (size_t i = 0; i < values_.size(); ++i) {
    values_[i].text = kinds_[i] == Kind::Text ? texts_[i].c_str() : nullptr;
    values_[i].values = kinds_[i] == Kind::Vector ? vectors_[i].data() : nullptr;
    values_[i].count = kinds_[i] == Kind::Vector ? static_cast<uint32_t>(vectors_[i].size()) : 0;
  }
}

}  // namespace tacta
