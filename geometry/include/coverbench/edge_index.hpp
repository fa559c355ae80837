#pragma once
/// Ring edges bucketed in a uniform grid, for proximity queries that must not scan every edge:
/// "is any edge within this distance of p" and "does any edge meet this rectangle".
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "coverbench/geometry.hpp"

namespace coverbench {

class EdgeIndex {
 public:
  /// `cell`: bucket size in metres (a few times the typical query size works well).
  EdgeIndex(const std::vector<Ring>& rings, double cell);
  /// Whether some edge passes within `radius` of p (closed).
  bool anyWithin(Point p, double radius) const;
  /// Whether some edge meets the closed rectangle.
  bool meetsBox(const Box& box) const;

 private:
  long index(double v) const;
  static long long key(long x, long y) { return (static_cast<long long>(x) << 32) ^ (y & 0xffffffffLL); }
  double cell_;
  std::vector<std::pair<Point, Point>> edges_;
  std::unordered_map<long long, std::vector<std::uint32_t>> buckets_;
};

}  // namespace coverbench
