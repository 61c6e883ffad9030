#pragma once

// Run-time values of the scenario's global parameters or variables (OpenSCENARIO 1.3 §9.1, §9.3).
// Parameters are resolved into the model at load time; ParameterSetAction / VariableSetAction
// change the values seen by ParameterCondition / VariableCondition during the run.

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "corsa/xosc/parameters.h"

namespace corsa::engine::detail {

class ValueStore {
 public:
  void declare(std::string name, xosc::Value value) {
    values_.emplace_back(std::move(name), std::move(value));
  }
  const xosc::Value* find(std::string_view name) const {
    for (const auto& [key, value] : values_) {
      if (key == name) {
        return &value;
      }
    }
    return nullptr;
  }
  xosc::Value* find(std::string_view name) {
    return const_cast<xosc::Value*>(std::as_const(*this).find(name));
  }
  const std::vector<std::pair<std::string, xosc::Value>>& all() const { return values_; }

 private:
  std::vector<std::pair<std::string, xosc::Value>> values_;  // declaration order
};

}  // namespace corsa::engine::detail
