// The one loader of plug-ins (plugin.hpp): dlopen on first use, the entry called once per caller.
#include "coverbench/plugin.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "coverbench/input_error.hpp"  // InputError

namespace coverbench {
namespace {

namespace fs = std::filesystem;

/// The places looked in, in order (plugin.hpp).
std::vector<std::string> places(const PluginSpec& spec) {
  if (const char* env = std::getenv(spec.variable); env && *env) return {env};
  std::vector<std::string> out;
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&openPlugin), &info) != 0 && info.dli_fname)
    out.push_back((fs::path(info.dli_fname).parent_path() / spec.file).string());
  if (out.empty() || out.front() != spec.built_at) out.push_back(spec.built_at);
  return out;
}

}  // namespace

const void* openPlugin(const PluginSpec& spec, const void* host) {
  using Entry = const void* (*)(const void*);
  std::string why;
  bool anywhere = false;  // some place holds a file
  for (const std::string& place : places(spec)) {
    std::error_code ec;
    if (!why.empty()) why += "; ";
    if (!fs::exists(place, ec)) {
      why += place + " does not exist";
      continue;
    }
    anywhere = true;
    if (!fs::is_regular_file(place, ec)) {  // a FIFO or device would block dlopen's read
      why += place + " is not a regular file";
      continue;
    }
    void* lib = ::dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
      const char* error = ::dlerror();
      why += error ? std::string(error) : place + ": cannot be loaded";
      continue;
    }
    const auto entry = reinterpret_cast<Entry>(::dlsym(lib, spec.entry));
    const void* table = entry ? entry(host) : nullptr;
    if (table && *static_cast<const int*>(table) == spec.abi) return table;
    why += place + (entry ? ": is of another build (its interface differs)" : ": has no " + std::string(spec.entry));
  }
  // None built where the build puts it (no variable named another file): the main job's build
  // (scripts/setup.sh main) leaves the plug-ins out.
  const char* named = std::getenv(spec.variable);
  if (!anywhere && !(named && *named)) why += " (`bash scripts/setup.sh` builds the plug-ins)";
  throw InputError(spec.library, "(plug-in)", std::string("cannot be opened, so ") + spec.purpose + ": " + why);
}

}  // namespace coverbench
