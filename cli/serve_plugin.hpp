#pragma once
// cpp-httplib (with OpenSSL and Brotli) is loaded only by `coverbench serve` (coverbench/plugin.hpp):
// the server (serve_command.cpp) is built into the plug-in libcoverbench_serve.so, which the
// command opens when it serves. Unlike the GDAL and OMPL plug-ins it carries its own copy of the
// layers it serves from (they are linked into it); the host passes the one thing that must be the
// host's: how to throw an InputError its caller catches.

#include <string>

#include "commands.hpp"

namespace coverbench::cli::serve_detail {

struct ServeHost {
  /// Throws InputError(source, field, problem) of the host.
  void (*input_error)(const std::string& source, const std::string& field, const std::string& problem);
};

struct ServeApi {
  int abi;  ///< kServePluginAbi of the plug-in's build
  /// Serves until stopped; the process's exit code (serveCommand).
  int (*serve)(const ServeOptions& options);
};

/// Changes whenever ServeHost, ServeApi or ServeOptions change.
inline constexpr int kServePluginAbi = 1;

/// The entry: const void* coverbench_serve_plugin(const void* host) takes a ServeHost and returns
/// a ServeApi.
inline constexpr const char* kServePluginEntry = "coverbench_serve_plugin";

}  // namespace coverbench::cli::serve_detail
