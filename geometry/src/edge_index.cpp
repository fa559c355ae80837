#include "coverbench/edge_index.hpp"

#include <cmath>
#include <utility>

namespace coverbench {
namespace {

/// Liang-Barsky: does the segment [a, b] meet the closed box?
bool segmentMeetsBox(Point a, Point b, const Box& r) {
  double t0 = 0.0, t1 = 1.0;
  const double d[2] = {b.x - a.x, b.y - a.y};
  const double lo[2] = {r.min_x - a.x, r.min_y - a.y}, hi[2] = {r.max_x - a.x, r.max_y - a.y};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (lo[k] > 0.0 || hi[k] < 0.0) return false;
      continue;
    }
    double ta = lo[k] / d[k], tb = hi[k] / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::fmax(t0, ta);
    t1 = std::fmin(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

EdgeIndex::EdgeIndex(const std::vector<Ring>& rings, double cell) : cell_(cell) {
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point a = ring[i], b = ring[(i + 1) % ring.size()];
      edges_.push_back({a, b});
      for (long x = index(std::fmin(a.x, b.x)); x <= index(std::fmax(a.x, b.x)); ++x)
        for (long y = index(std::fmin(a.y, b.y)); y <= index(std::fmax(a.y, b.y)); ++y)
          buckets_[key(x, y)].push_back(static_cast<std::uint32_t>(edges_.size() - 1));
    }
}

long EdgeIndex::index(double v) const { return static_cast<long>(std::floor(v / cell_)); }

bool EdgeIndex::anyWithin(Point p, double radius) const {
  const double r2 = radius * radius;
  for (long x = index(p.x - radius); x <= index(p.x + radius); ++x)
    for (long y = index(p.y - radius); y <= index(p.y + radius); ++y) {
      const auto it = buckets_.find(key(x, y));
      if (it == buckets_.end()) continue;
      for (std::uint32_t e : it->second)
        if (squaredDistancePointSegment(p, edges_[e].first, edges_[e].second) <= r2) return true;
    }
  return false;
}

bool EdgeIndex::meetsBox(const Box& box) const {
  for (long x = index(box.min_x); x <= index(box.max_x); ++x)
    for (long y = index(box.min_y); y <= index(box.max_y); ++y) {
      const auto it = buckets_.find(key(x, y));
      if (it == buckets_.end()) continue;
      for (std::uint32_t e : it->second)
        if (segmentMeetsBox(edges_[e].first, edges_[e].second, box)) return true;
    }
  return false;
}

}  // namespace coverbench
