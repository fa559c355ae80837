#pragma once
/// Content hashes: SHA-256 (OpenSSL) as lowercase hex. Used for wall identities, dataset
/// manifests and run keys, so the same content gets the same name on every machine.
#include <string>
#include <string_view>

namespace coverbench {

std::string sha256Hex(std::string_view data);

}  // namespace coverbench
