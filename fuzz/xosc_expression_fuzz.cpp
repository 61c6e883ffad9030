// libFuzzer target: any bytes as the body of a `${...}` expression. Must end in a value or an
// ExpressionError; a numeric result is never NaN or infinite.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "corsa/xosc/expression.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using corsa::xosc::ExprValue;
  const auto lookup = [](std::string_view name) -> std::optional<ExprValue> {
    if (name == "a") return ExprValue::of(2.5);
    if (name == "b") return ExprValue::of(-7.0);
    if (name == "t") return ExprValue::of_bool(true);
    return std::nullopt;
  };
  try {
    const ExprValue value = corsa::xosc::evaluate_expression(
        std::string_view(reinterpret_cast<const char*>(data), size), lookup);
    if (!value.is_bool && !std::isfinite(value.number)) {
      std::abort();  // the evaluator promises finite numbers
    }
  } catch (const corsa::xosc::ExpressionError&) {
  }
  return 0;
}
