#include "coverbench/shards.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "coverbench/wall.hpp"

namespace coverbench {
namespace {

/// A decimal number without sign, spaces or leading zeros ("0" itself allowed); nullopt otherwise.
std::optional<unsigned long long> decimal(const std::string& text) {
  if (text.empty() || text.size() > 12 || (text.size() > 1 && text[0] == '0')) return std::nullopt;
  unsigned long long v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

}  // namespace

Shard parseShard(const std::string& text, const std::string& source) {
  const std::size_t slash = text.find('/');
  const auto index = slash == std::string::npos ? std::nullopt : decimal(text.substr(0, slash));
  const auto count = slash == std::string::npos ? std::nullopt : decimal(text.substr(slash + 1));
  if (!index || !count)
    throw InputError(source, "shard", "must be I/N with whole numbers 0 <= I < N (e.g. 0/8), got '" + shownBytes(text) + "'");
  if (*count < 1 || *count > kMaxShards)
    throw InputError(source, "shard", "N must be in [1, " + std::to_string(kMaxShards) + "], got '" + shownBytes(text) + "'");
  if (*index >= *count)
    throw InputError(source, "shard", "I must be below N (shards are numbered 0 to N-1), got '" + shownBytes(text) + "'");
  return Shard{static_cast<unsigned>(*index), static_cast<unsigned>(*count)};
}

std::string toString(const Shard& shard) { return std::to_string(shard.index) + "/" + std::to_string(shard.count); }

unsigned shardOf(const RunSpec& run, unsigned count) {
  // The base key is a SHA-256 in hex: its first 16 digits are 64 uniformly distributed bits.
  const std::string& key = run.base_key;
  std::uint64_t bits = 0;
  const auto [end, ec] = std::from_chars(key.data(), key.data() + std::min<std::size_t>(16, key.size()), bits, 16);
  if (ec != std::errc() || key.size() < 16) throw std::logic_error("run base key is not a SHA-256: '" + key + "'");
  (void)end;
  return static_cast<unsigned>(bits % count);
}

std::string shardDatabasePath(const ExperimentConfig& config, const Shard& shard) {
  return (std::filesystem::path(config.output) / "shards" /
          ("shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".sqlite"))
      .string();
}

}  // namespace coverbench
