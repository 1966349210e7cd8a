// One validation row as `scripts/validate` collects it (docs/VALIDATION.md, "Rows"): a test that
// checks a number against a reference prints it, then asserts the same `pass`.
//   VALIDATION name=ID reference="..." tolerance="..." measured="..." pass=yes|no kind=reference|regression
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace tacta::test {

enum class RowKind { reference, regression };  // regression: a band around the code's own output

inline std::string validation_quote(std::string_view text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? '\'' : c == '\n' ? ' ' : c;
  return out + "\"";
}

// `name`: letters, digits and _ . : / + - (unique over the tree); the others are free text.
inline bool validation_row(std::string_view name, std::string_view reference,
                           std::string_view tolerance, std::string_view measured, bool pass,
                           RowKind kind = RowKind::reference) {
  std::printf("VALIDATION name=%.*s reference=%s tolerance=%s measured=%s pass=%s kind=%s\n",
              static_cast<int>(name.size()), name.data(), validation_quote(reference).c_str(),
              validation_quote(tolerance).c_str(), validation_quote(measured).c_str(),
              pass ? "yes" : "no", kind == RowKind::reference ? "reference" : "regression");
  std::fflush(stdout);
  return pass;
}

// A number with `digits` significant digits, for the free-text fields.
inline std::string validation_number(double value, int digits = 4) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace tacta::test
