// The one-line input error and the numbers messages show (input_error.hpp).
#include "coverbench/input_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace coverbench {

InputError::InputError(std::string source, std::string field, std::string problem)
    : std::runtime_error(source + ": " + field + ": " + problem),
      source_(std::move(source)),
      field_(std::move(field)),
      problem_(std::move(problem)) {}

std::string shortNumber(double v) {
  // Six significant digits, or as many more as it takes to read back as v: 3600.0000001 is not
  // printed as the bound 3600 it exceeds, and 0.1 stays 0.1.
  char buf[64];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v || !std::isfinite(v)) break;
  }
  return buf;
}

std::string shownBytes(const std::string& name) {
  static const char* hex = "0123456789abcdef";
  const std::size_t shown = std::min(name.size(), kShownBytes);
  std::string out;
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c >= 0x7f) out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
    else out += name[i];
  }
  if (shown < name.size()) out += "... (" + std::to_string(name.size()) + " bytes)";
  return out;
}

}  // namespace coverbench
