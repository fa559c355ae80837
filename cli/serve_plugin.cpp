// The entry of the plug-in libcoverbench_serve.so (serve_plugin.hpp): `coverbench serve` as the
// host opens it.
#include "serve.hpp"
#include "serve_plugin.hpp"

namespace coverbench::cli {
namespace {

const serve_detail::ServeHost* host = nullptr;

/// serveHere, with the plug-in's own InputError (its copy of the layers) thrown again as the host's.
int serve(const ServeOptions& options) {
  try {
    return serveHere(options);
  } catch (const InputError& e) {
    host->input_error(e.source(), e.field(), e.problem());
    throw;  // input_error throws; never reached
  }
}

}  // namespace
}  // namespace coverbench::cli

extern "C" __attribute__((visibility("default"))) const void* coverbench_serve_plugin(const void* h) {
  using namespace coverbench::cli;
  host = static_cast<const serve_detail::ServeHost*>(h);
  static const serve_detail::ServeApi api{serve_detail::kServePluginAbi, &serve};
  return &api;
}
