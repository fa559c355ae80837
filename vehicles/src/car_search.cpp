// A car's route round obstacles, searched over its own motions (hybrid A*; coverbench/car.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <queue>
#include <unordered_map>
#include <vector>

#include "coverbench/boundary_arcs.hpp"
#include "coverbench/car.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

/// Headings the search tells apart (15 degrees).
constexpr int kHeadingBins = 24;
/// The estimate's weight (weighted A*).
constexpr double kWeight = 2.0;

/// A pose with its heading's sine and cosine, computed once for every motion from it.
struct PoseTrig {
  Pose pose;
  double sin, cos;
  explicit PoseTrig(Pose p) : pose(p), sin(std::sin(p.heading)), cos(std::cos(p.heading)) {}
  PoseTrig(Pose p, double s, double c) : pose(p), sin(s), cos(c) {}
};

/// The bulge of an arc of signed curvature `kappa` and length `length`: the position turns about
/// the centre by the heading's change, the arc's signed angle.
double motionBulge(double kappa, double length) { return std::tan(kappa * length / 4.0); }

/// Where the arc of signed curvature `kappa` and length `length` from `from` ends (backwards when
/// `length` < 0).
Pose motionEnd(const PoseTrig& from, double kappa, double length) {
  const Pose& pose = from.pose;
  if (kappa == 0.0) return {pose.at + Point{from.cos, from.sin} * length, pose.heading};
  // The heading turns by kappa * length whichever way the car drives.
  const double heading = pose.heading + kappa * length;
  return {pose.at + Point{std::sin(heading) - from.sin, from.cos - std::cos(heading)} * (1.0 / kappa), wrapAngle(heading)};
}

/// motionEnd with the end heading's sine and cosine (those of the heading before it is wrapped
/// into [-pi, pi] when wrapping leaves it as it is: the same numbers PoseTrig would compute).
PoseTrig motionEndTrig(const PoseTrig& from, double kappa, double length) {
  const Pose& pose = from.pose;
  if (kappa == 0.0) return {{pose.at + Point{from.cos, from.sin} * length, pose.heading}, from.sin, from.cos};
  const double heading = pose.heading + kappa * length;
  const double s = std::sin(heading), c = std::cos(heading);
  const Pose end{pose.at + Point{s - from.sin, from.cos - c} * (1.0 / kappa), wrapAngle(heading)};
  return end.heading == heading ? PoseTrig{end, s, c} : PoseTrig{end};
}

/// That arc (bulge `bulge`, motionBulge) as a path (tool off) in `p` (emptied first, its room
/// kept), `end` its end (motionEnd).
void motionInto(Path& p, Pose pose, double kappa, double bulge, Pose end) {
  p.waypoints.clear();
  p.tool_on.clear();
  p.bulge.clear();
  p.reserve(1);
  p.moveTo(pose.at, false);
  if (kappa == 0.0) p.moveTo(end.at, false);
  else p.arcTo(end.at, bulge, false);
}

/// That arc as a path of its own.
Path motionPath(Pose pose, double kappa, double length, Pose end) {
  Path p;
  motionInto(p, pose, kappa, motionBulge(kappa, length), end);
  return p;
}

/// Weighted A* over the car's motions from `from` (`fineness`: searchCarUntil's): `estimate(pose)` guides it (0: by cost alone),
/// `finish(pose, out)` ends it at a pose taken (true, with the last piece to append in `out`,
/// possibly empty). The route as a path (tool off), or an empty path.
template <class Estimate, class Finish>
Path search(const Workspace& ws, Pose from, double radius, bool reverse, std::size_t max_expansions, Estimate estimate,
            Finish finish, std::size_t* used = nullptr, int fineness = 1) {
  // A full turn's motion turns the heading by 22.5 degrees (by 22.5 / fineness; cells and heading
  // bins as much finer).
  const double step = radius * M_PI / (8.0 * fineness);
  const double cell = radius / (2.0 * fineness);
  const int bins = kHeadingBins * fineness;
  const std::array<double, 5> curvatures{-1.0 / radius, -0.5 / radius, 0.0, 0.5 / radius, 1.0 / radius};
  // Each motion's bulge, forwards and backwards (the same for every pose).
  std::array<std::array<double, 5>, 2> bulges{};
  for (std::size_t i = 0; i < curvatures.size(); ++i)
    bulges[0][i] = motionBulge(curvatures[i], step), bulges[1][i] = motionBulge(curvatures[i], -step);
  struct Node {
    Pose pose;
    double cost;
    std::size_t parent;   // index into nodes; itself for the start
    double kappa, length;  // the motion from the parent's pose to this one (built again at the end)
  };
  std::vector<Node> nodes;
  nodes.push_back({from, 0.0, 0, 0.0, 0.0});
  Path piece;  // the motion being checked (its room reused)
  using Entry = std::pair<double, std::size_t>;  // cost plus estimate, node
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  open.push({estimate(from), 0});
  // The cheapest cost seen per cell and heading bin.
  auto key = [&](Pose p) { return poseKey(p, cell, bins); };
  std::unordered_map<std::int64_t, double> best;
  best[key(from)] = 0.0;
  std::size_t expansions = 0;
  Path last;  // the finish's last piece (its room reused)
  while (!open.empty() && expansions < max_expansions) {
    const std::size_t index = open.top().second;
    open.pop();
    const Pose pose = nodes[index].pose;
    const double cost = nodes[index].cost;
    if (cost > best[key(pose)] + 1e-12) continue;  // reached more cheaply since
    ++expansions;
    if (used) ++*used;
    if (finish(pose, last)) {
      std::vector<Path> pieces{std::move(last)};
      for (std::size_t i = index; i != 0; i = nodes[i].parent) {
        const Node& n = nodes[i];
        pieces.push_back(motionPath(nodes[n.parent].pose, n.kappa, n.length, n.pose));
      }
      Path out;
      out.moveTo(from.at, false);
      for (auto it = pieces.rbegin(); it != pieces.rend(); ++it)
        for (std::size_t k = 0; k < it->segments(); ++k) out.arcTo(it->waypoints[k + 1], it->bulgeOf(k), false);
      return out;
    }
    const PoseTrig trig(pose);
    for (const double direction : {1.0, -1.0}) {
      if (direction < 0.0 && !reverse) break;
      for (std::size_t i = 0; i < curvatures.size(); ++i) {
        const double kappa = curvatures[i];
        // Reversing costs more, so that a reversing car backs up only where it must.
        const double next_cost = cost + step * (direction < 0.0 ? 1.5 : 1.0);
        const Pose end = motionEnd(trig, kappa, direction * step);
        const auto k = key(end);
        const auto seen = best.find(k);
        if (seen != best.end() && seen->second <= next_cost) continue;  // before the costlier check
        motionInto(piece, pose, kappa, bulges[direction < 0.0][i], end);
        if (!pathFree(ws, piece)) continue;
        best[k] = next_cost;
        nodes.push_back({end, next_cost, index, kappa, direction * step});
        open.push({next_cost + estimate(end), nodes.size() - 1});
      }
    }
  }
  return Path{};
}

/// The full circle of radius `radius` the car drives turning left (or right) from `pose`, into
/// `p` (emptied first, its room kept). Four quarter turns, each as motionInto draws it.
void circleInto(Path& p, const PoseTrig& pose, double radius, bool left) {
  const double kappa = (left ? 1.0 : -1.0) / radius, length = radius * M_PI / 2.0;
  const double bulge = motionBulge(kappa, length);
  p.waypoints.clear();
  p.tool_on.clear();
  p.bulge.clear();
  p.reserve(4);
  p.moveTo(pose.pose.at, false);
  PoseTrig at = pose;
  for (int k = 0; k < 4; ++k) {
    at = motionEndTrig(at, kappa, length);
    p.arcTo(at.pose.at, bulge, false);
  }
}

}  // namespace

Path searchCarRoute(const Workspace& ws, Pose from, Pose to, double radius, bool reverse, std::size_t max_expansions,
                    std::size_t* used) {
  return search(
      ws, from, radius, reverse, max_expansions, [&](Pose p) { return kWeight * carCurveLength(p, to, radius, reverse); },
      [&](Pose p, Path& last) {
        // The shortest curve on to the goal, if it is free.
        return carCurveInto(p, to, radius, reverse, false, last) && pathFree(ws, last);
      },
      used);
}

std::int64_t poseKey(Pose p, double cell, int headings) {
  const auto x = static_cast<std::int64_t>(std::floor(p.at.x / cell)), y = static_cast<std::int64_t>(std::floor(p.at.y / cell));
  const int h = static_cast<int>(std::floor(wrapAngle(p.heading) / (2.0 * M_PI) * headings + headings)) % headings;
  return (x * 1000003 + y) * headings + h;
}

Path searchCarUntil(const Workspace& ws, Pose from, double radius, std::size_t max_expansions,
                    const std::function<bool(Pose, Path&)>& finish, std::size_t* used, int fineness) {
  return search(ws, from, radius, false, max_expansions, [](Pose) { return 0.0; }, finish, used, fineness);
}

bool carCanLoop(const Workspace& ws, Pose from, double radius, std::size_t max_expansions) {
  Path ring;  // the circle being checked (its room reused)
  const Path route = search(ws, from, radius, false, max_expansions, [](Pose) { return 0.0; }, [&](Pose p, Path& last) {
    last.waypoints.clear();
    last.tool_on.clear();
    last.bulge.clear();
    const PoseTrig trig(p);
    circleInto(ring, trig, radius, true);
    if (pathFree(ws, ring)) return true;
    circleInto(ring, trig, radius, false);
    return pathFree(ws, ring);
  });
  return !route.waypoints.empty();
}

}  // namespace coverbench
