#pragma once
/// Shared by the libFuzzer targets (tests/fuzz/README.md): inputs that only a file can carry are
/// written to one scratch file per process; a broken promise aborts, which libFuzzer reports.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

namespace coverbench::fuzz {

/// Writes the input to this process's scratch file (under TMPDIR) and returns its path.
inline std::string scratchFile(const std::uint8_t* data, std::size_t size, const char* suffix) {
  const char* dir = std::getenv("TMPDIR");
  const std::string path = std::string(dir && *dir ? dir : "/tmp") + "/coverbench-fuzz-" + std::to_string(::getpid()) + suffix;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// A broken promise: print it and abort, so libFuzzer keeps the input as a crash.
[[noreturn]] inline void broken(const std::string& what) {
  std::fprintf(stderr, "coverbench fuzz: %s\n", what.c_str());
  std::abort();
}

}  // namespace coverbench::fuzz
