// The car's headland layout (coverbench/car_sweep.hpp, docs/vehicles.md): how many rings and where
// rows end, passes along the obstacles' straight edges, and the block order a stack of rows is
// taken in.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "car_sweep_parts.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {

namespace vehicle_detail {

bool leaveRoomToTurn(Workspace& ws, Point& a, Point& b, double rho, double max_cut_a, double max_cut_b,
                     double min_length) {
  const Point u = (b - a) * (1.0 / distance(a, b));
  for (int end = 0; end < 2; ++end) {
    Point& tip = end == 0 ? b : a;
    const Point ahead = end == 0 ? u : u * -1.0;
    const double max_cut = end == 0 ? max_cut_b : max_cut_a;
    double cut = 0.0;
    while (cut < max_cut && !ws.router().isFree(tip, tip + ahead * rho)) {
      cut += 0.25 * rho;
      tip = tip - ahead * (0.25 * rho);
    }
  }
  return dot(b - a, u) >= min_length;
}

}  // namespace vehicle_detail

using vehicle_detail::leaveRoomToTurn;

std::vector<std::size_t> carBlockOrder(std::size_t m, std::size_t k, std::size_t p, bool whole) {
  std::vector<std::size_t> order;
  const std::size_t least = 2 * k + 1;
  if (k == 0 || m < least || p >= k) return order;
  // Blocks of about equal size, all but the last odd; when m leaves 2k over, a last block of 2k.
  // Not whole: blocks of 2k + 1, the last of 2k + 2 when lines are left (as cheap), the rest left
  // out.
  const std::size_t blocks = m / least;
  const std::size_t last = m % least == 2 * k ? 2 * k : 0;
  if (!whole && last == 0) m = std::min(m, blocks * least + 1);
  std::size_t base = 0;
  auto pair = [&](std::size_t first, std::size_t second) {
    order.push_back(base + first);
    order.push_back(base + second);
  };
  for (std::size_t i = 0; i < blocks; ++i) {
    std::size_t size = (m - last - base) / (blocks - i);  // not whole: 2k + 1, then 2k + 1 or 2k + 2
    if ((i + 1 < blocks || last > 0) && size % 2 == 0) --size;
    if (size % 2 == 1) {
      // Lines j and j + h - 1 for j = p down to 0, the top line, then j + h - 1 and j for j = h -
      // 2 down to p + 1: links span h - 1 or h lines, and the block ends on line p + h, h - 1
      // below the next block's line p.
      const std::size_t h = (size + 1) / 2;
      for (std::size_t j = p + 1; j-- > 0;) pair(j, j + h - 1);
      order.push_back(base + size - 1);
      for (std::size_t j = h - 2; j > p; --j) pair(j, j + h - 1);
    } else {
      // The last block, of even size 2g: lines j and j + g for j = p down to 0, then j + g and j
      // for j = g - 1 down to p + 1 (links span g - 1 or g lines).
      const std::size_t g = size / 2;
      for (std::size_t j = p + 1; j-- > 0;) pair(j, j + g);
      for (std::size_t j = g - 1; j > p; --j) pair(j + g, j);
    }
    base += size;
  }
  // The last 2k lines, entered at their line k - 1 (h - 1 - p + k - 1 >= k lines above the last
  // block's end): lines j and j + k for j = k - 1 down to 0 (links span k or k + 1 lines).
  if (last > 0)
    for (std::size_t j = k; j-- > 0;) pair(j, j + k);
  return order;
}

ParamSpec carPlanParam() {
  return {"car_plan", ParamType::Choice, std::string("headland"), 0, 0, {"headland", "headland_no_fill", "smoothed"}, "",
          "for a car: headland rings and rows in an order its turns can link, then passes through what they left "
          "unpainted (headland), the same without those passes (headland_no_fill), or the path planned for a tool "
          "that turns on the spot, smoothed (smoothed: the baseline); nothing changes for other vehicles"};
}

std::vector<CarRow> carHolePasses(Workspace& ws, std::vector<Ring>& loops, double spacing) {
  std::vector<CarRow> passes;
  std::vector<Ring> kept;
  const bool forward_only = !ws.vehicle().reverse;
  const double rho = ws.vehicle().turn_radius * (1.0 + kCarRadiusSlack);
  for (Ring& ring : loops) {
    std::vector<CarRow> mine;
    bool straight = false;  // an edge long enough for a pass (the ring is replaced by passes)
    if (signedArea(ring) < 0.0)  // a hole's ring (clockwise)
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Point a = ring[i], b = ring[(i + 1) % ring.size()];
        const double length = distance(a, b);
        if (length < 2.0 * spacing) continue;
        straight = true;
        const Point u = (b - a) * (1.0 / length);
        auto extended = [&](Point from, Point to, Point dir) {
          for (double e : {0.5, 0.35, 0.25, 0.15, 0.08, 0.04})
            if (ws.router().isFree(from, to + dir * e)) return to + dir * e;
          return to;
        };
        Point b2 = extended(a, b, u);
        Point a2 = extended(b2, a, u * -1.0);
        // A forward-only car turns out of a pass beyond its end: not along an edge that runs on
        // into a gap too narrow to turn in (a window tucked into a corner of the wall).
        if (forward_only && !leaveRoomToTurn(ws, a2, b2, rho, distance(a2, a) + rho, distance(b2, b) + rho, 2.0 * spacing))
          continue;
        mine.push_back({a2, b2, 0, false});
      }
    if (!straight) kept.push_back(std::move(ring));
    else passes.insert(passes.end(), mine.begin(), mine.end());
  }
  loops = std::move(kept);
  return passes;
}

Problem asHolonomic(const Problem& problem) {
  Problem holonomic = problem;
  holonomic.vehicle = VehicleModel{};
  holonomic.straight_segments_only = true;
  return holonomic;
}

CarHeadlandLayout carHeadlandLayout(double spacing, double turn_radius) {
  // Rows end (loops - 1 + 0.5) spacings inside F's edge: at least the turn radius.
  CarHeadlandLayout layout;
  const double needed = (turn_radius - 0.5 * spacing) / spacing;
  layout.loops = 1 + static_cast<std::size_t>(std::max(0.0, std::ceil(needed - 1e-9)));
  layout.end_inset = 0.5;
  return layout;
}

HeadlandOptions carHeadlandOptions(const Problem& problem, double spacing, std::size_t loops, double end_inset,
                                   double arc_tolerance, bool along_x) {
  const CarHeadlandLayout car = carHeadlandLayout(spacing, problem.vehicle.turn_radius);
  HeadlandOptions layout;
  layout.spacing = spacing;
  layout.radius = problem.tool.tool_width / 2.0;
  layout.loops = std::max(car.loops, loops);
  layout.end_inset = std::max(car.end_inset, end_inset);
  layout.arc_tolerance = arc_tolerance;
  layout.along_x = along_x;
  return layout;
}

}  // namespace coverbench
