#pragma once
/// What every library reports bad input with, and how messages write numbers: the base of the
/// layers (docs/architecture.md), below the geometry.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace coverbench {

/// Bad input from a user: carries the file (or flag), the field and the problem, and formats them
/// as one line: `FILE: FIELD: PROBLEM`.
class InputError : public std::runtime_error {
 public:
  InputError(std::string source, std::string field, std::string problem);
  const std::string& source() const { return source_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string source_, field_, problem_;
};

/// A number as messages show it: six significant digits, or as many more as read back as it
/// ("0.1", "1e-09", "3600.0000001").
std::string shortNumber(double v);
/// A name from input as a message quotes it: bytes outside printable ASCII (control bytes, bytes
/// that may not be UTF-8) as \xHH, so the message is one line of valid text whatever was given;
/// past its first kShownBytes bytes, "... (N bytes)" (a megabyte of junk is not echoed back).
inline constexpr std::size_t kShownBytes = 80;
std::string shownBytes(const std::string& name);

}  // namespace coverbench
