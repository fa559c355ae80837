// Planner code identities from the generated build identity.
#include "coverbench/build_identity.hpp"

#include "coverbench/hash.hpp"

#include <stdexcept>

namespace coverbench {

std::string BuildIdentity::plannerCode(const std::vector<std::string>& folders) const {
  std::string text = "coverbench-code/1\nshared=" + shared_code_sha256 + "\ncompiler=" + compiler +
                     "\nbuild_type=" + build_type + "\nflags=" + flags;
  for (const std::string& f : folders) {
    const auto it = folder_code_sha256.find(f);
    // A misspelt folder would hash as empty, and a changed planner's stored runs would be reused.
    if (it == folder_code_sha256.end())
      throw std::logic_error("code folder '" + f + "' is not a folder of algorithms/ (a planner's code_folders is misspelt)");
    text += "\nfolder." + f + "=" + it->second;
  }
  return sha256Hex(text);
}

std::string BuildIdentity::describe() const {
  return git_revision.substr(0, 12) + (dirty_diff_sha256.empty() ? "" : "-dirty:" + dirty_diff_sha256.substr(0, 12));
}

}  // namespace coverbench
