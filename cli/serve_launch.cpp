// `coverbench serve` from the command: the server is the plug-in libcoverbench_serve.so
// (serve_plugin.hpp), opened here, so no other command loads cpp-httplib and OpenSSL.
#include "commands.hpp"
#include "coverbench/plugin.hpp"
#include "serve_plugin.hpp"

namespace coverbench::cli {
namespace {

void hostInputError(const std::string& source, const std::string& field, const std::string& problem) {
  throw InputError(source, field, problem);
}

}  // namespace

int serveCommand(const ServeOptions& options) {
  static const serve_detail::ServeHost host{&hostInputError};
  static const PluginSpec spec{"cpp-httplib", "the explorer cannot be served", "libcoverbench_serve.so", "COVERBENCH_SERVE_PLUGIN",
                               COVERBENCH_SERVE_PLUGIN_PATH, serve_detail::kServePluginEntry, serve_detail::kServePluginAbi};
  const auto* api = static_cast<const serve_detail::ServeApi*>(openPlugin(spec, &host));
  return api->serve(options);
}

}  // namespace coverbench::cli
