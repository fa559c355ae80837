#pragma once
/// Reading and writing whole files, with errors that name the file.
#include <string>

namespace coverbench {

/// Writes `text` to `path` atomically (a temporary file renamed into place), so a failure never
/// leaves a partial file. Throws InputError naming the path if it cannot be written.
void writeFileAtomically(const std::string& path, const std::string& text);

/// The bytes of a file. Throws InputError naming the path if it cannot be read.
std::string readFile(const std::string& path);

}  // namespace coverbench
