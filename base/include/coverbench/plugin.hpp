#pragma once
/// Plug-ins: heavy libraries are loaded only by the commands that use them (docs/architecture.md,
/// "Heavy libraries load on first use"). The code that includes such a library is built as a
/// plug-in of ours, libcoverbench_<name>.so, beside the command (GDAL for imports, OMPL for the
/// sampling transits and the car's Reeds-Shepp curves, cpp-httplib and OpenSSL for `coverbench
/// serve`), which the first use opens here, once per process. A plug-in exports one C function, its
/// entry, that takes what the host offers it and returns its table of functions, whose first member
/// is the interface number it was built with (a plug-in of another build is refused, not called).

namespace coverbench {

/// Where a plug-in is and what it is for.
struct PluginSpec {
  const char* library;   ///< the heavy library it holds, as refusals name it: "GDAL"
  const char* purpose;   ///< what cannot be done without it: "this format cannot be imported"
  const char* file;      ///< its file name: "libcoverbench_gdal.so"
  const char* variable;  ///< the environment variable that names the file instead: "COVERBENCH_GDAL_PLUGIN"
  const char* built_at;  ///< where the build made it (the last place looked in)
  const char* entry;     ///< its exported entry: const void* entry(const void* host)
  int abi;               ///< the interface number the table must carry
};

/// The table the plug-in's entry returns for `host` (a pointer to the plug-in's table type, whose
/// first member is an int equal to spec.abi). Looks for the file where `spec.variable` says, else
/// beside the program or library this code is linked into (the command, the Python module), else
/// at spec.built_at. Throws InputError(library, "(plug-in)", "cannot be opened, so <purpose>: <each
/// place and why>") when no place holds a plug-in that answers with spec.abi. A library opened
/// before is not opened again (the system keeps one copy per process); callers keep the table.
const void* openPlugin(const PluginSpec& spec, const void* host);

}  // namespace coverbench
