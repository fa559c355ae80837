// A coverage planner outside CoverBench's tree, in C++ with nothing of CoverBench: it speaks the
// planner protocol (docs/external_planners.md) on stdin and stdout, using only nlohmann-json.
// Columns run along y, a tool width apart. On each column it computes exactly where the tool's
// centre may be (the disk inside the wall, the clearance kept from every obstacle), paints those
// intervals, and joins them with straight moves it checks the same way. A piece no straight move
// reaches is left out, and the plan says so (status partial).
//   cmake -S . -B build && cmake --build build    (or built with CoverBench, see CMakeLists.txt)
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace {

using nlohmann::json;
struct P {
  double x, y;
};
using Ring = std::vector<P>;
constexpr double kMargin = 1e-6;

double pointSegment(P p, P a, P b) {
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  const double t = l2 == 0 ? 0 : std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0, 1.0);
  return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}
double orient(P p, P q, P r) { return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x); }
double segmentSegment(P a, P b, P c, P d) {
  if (orient(a, b, c) * orient(a, b, d) < 0 && orient(c, d, a) * orient(c, d, b) < 0) return 0;
  return std::min({pointSegment(a, c, d), pointSegment(b, c, d), pointSegment(c, a, b), pointSegment(d, a, b)});
}
bool inside(P p, const Ring& r) {
  bool in = false;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    if ((r[i].y > p.y) != (r[j].y > p.y) && p.x < r[i].x + (p.y - r[i].y) * (r[j].x - r[i].x) / (r[j].y - r[i].y)) in = !in;
  return in;
}

struct Wall {
  Ring boundary;
  std::vector<Ring> polygons;
  std::vector<std::pair<P, double>> circles;
  double r = 0, keep = 0;  // what the centre keeps from the wall edge and from obstacles

  template <class F>
  void edges(const Ring& ring, F f) const {
    for (std::size_t i = 0; i < ring.size(); ++i) f(ring[i], ring[(i + 1) % ring.size()]);
  }
  bool freeMove(P a, P b) const {
    for (P p : {a, b}) {
      if (!inside(p, boundary)) return false;
      for (const Ring& o : polygons)
        if (inside(p, o)) return false;
    }
    bool ok = true;
    edges(boundary, [&](P c, P d) { ok = ok && segmentSegment(a, b, c, d) >= r; });
    for (const Ring& o : polygons) edges(o, [&](P c, P d) { ok = ok && segmentSegment(a, b, c, d) >= keep; });
    for (const auto& [c, rad] : circles) ok = ok && pointSegment(c, a, b) >= rad + keep;
    return ok;
  }
  /// Where the centre may be on the column x: its free intervals of y.
  std::vector<std::pair<double, double>> column(double x) const {
    auto crossings = [x, this](const Ring& ring) {
      std::vector<double> ys;
      edges(ring, [&](P a, P b) {
        if ((a.x > x) != (b.x > x)) ys.push_back(a.y + (x - a.x) * (b.y - a.y) / (b.x - a.x));
      });
      std::sort(ys.begin(), ys.end());
      return ys;
    };
    std::vector<std::pair<double, double>> pieces, blocked;
    const std::vector<double> in = crossings(boundary);
    for (std::size_t i = 0; i + 1 < in.size(); i += 2) pieces.push_back({in[i], in[i + 1]});
    // The band of the column nearer than d to a segment (convex: the hull of its parts).
    auto band = [x, &blocked](P a, P b, double d) {
      double lo = INFINITY, hi = -INFINITY;
      for (P c : {a, b})
        if (std::fabs(x - c.x) < d) {
          const double h = std::sqrt(d * d - (x - c.x) * (x - c.x));
          lo = std::min(lo, c.y - h), hi = std::max(hi, c.y + h);
        }
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      if (len > 0) {
        const double ux = (b.x - a.x) / len, uy = (b.y - a.y) / len, nx = -uy, ny = ux;
        double yl = -INFINITY, yh = INFINITY;
        for (auto [coef, cst, low, high] : {std::tuple{ny, nx * (x - a.x) - ny * a.y, -d, d},
                                            std::tuple{uy, ux * (x - a.x) - uy * a.y, 0.0, len}}) {
          if (std::fabs(coef) < 1e-15) {
            if (cst < low || cst > high) yl = INFINITY, yh = -INFINITY;
            continue;
          }
          const double y1 = (low - cst) / coef, y2 = (high - cst) / coef;
          yl = std::max(yl, std::min(y1, y2)), yh = std::min(yh, std::max(y1, y2));
        }
        if (yl <= yh) lo = std::min(lo, yl), hi = std::max(hi, yh);
      }
      if (lo <= hi) blocked.push_back({lo, hi});
    };
    edges(boundary, [&](P a, P b) { band(a, b, r); });
    for (const Ring& o : polygons) {
      edges(o, [&](P a, P b) { band(a, b, keep); });
      const std::vector<double> ys = crossings(o);
      for (std::size_t i = 0; i + 1 < ys.size(); i += 2) blocked.push_back({ys[i], ys[i + 1]});
    }
    for (const auto& [c, rad] : circles)
      if (std::fabs(x - c.x) < rad + keep) {
        const double h = std::sqrt((rad + keep) * (rad + keep) - (x - c.x) * (x - c.x));
        blocked.push_back({c.y - h, c.y + h});
      }
    for (const auto& [bl, bh] : blocked) {
      std::vector<std::pair<double, double>> next;
      for (const auto& [pl, ph] : pieces)
        for (auto q : {std::pair{pl, std::min(ph, bl)}, std::pair{std::max(pl, bh), ph}})
          if (q.second - q.first > 1e-9) next.push_back(q);
      pieces = std::move(next);
    }
    std::vector<std::pair<double, double>> out;
    for (const auto& [a, b] : pieces)
      if (b - a > 2e-7) out.push_back({a + 1e-7, b - 1e-7});
    return out;
  }
};

Ring ring(const json& points) {
  Ring r;
  for (const json& p : points) r.push_back({p[0].get<double>(), p[1].get<double>()});
  return r;
}

json plan(const json& problem) {
  Wall w;
  w.boundary = ring(problem["wall"]["boundary"]);
  for (const json& o : problem["wall"]["obstacles"]) {
    if (o["type"] == "circle") w.circles.push_back({{o["x"].get<double>(), o["y"].get<double>()}, o["radius"].get<double>()});
    else w.polygons.push_back(ring(o["points"]));
  }
  const double s = problem["tool"]["width"].get<double>(), c = problem["tool"]["clearance"].get<double>();
  w.r = s / 2 + kMargin;
  w.keep = s / 2 + c + kMargin;
  double x0 = INFINITY, x1 = -INFINITY;
  for (P p : w.boundary) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
  x0 += w.r + kMargin, x1 -= w.r + kMargin;
  if (x1 < x0) return {{"status", "no_reachable_area"}, {"reason", "the wall is narrower than the tool"}};
  const auto columns = static_cast<int>(std::ceil((x1 - x0) / s - 1e-9));
  struct Piece {
    int column;
    double x, y0, y1;
    bool done = false;
  };
  std::vector<Piece> pieces;
  for (int k = 0; k <= columns; ++k) {
    const double x = columns ? x0 + (x1 - x0) * k / columns : x0;
    for (const auto& [a, b] : w.column(x)) pieces.push_back({k, x, a, b});
  }
  if (pieces.empty()) return {{"status", "no_reachable_area"}, {"reason", "the tool fits on no column"}};
  json waypoints = json::array(), tool_on = json::array();
  bool up = true;
  P here{};
  int column = 0;
  std::size_t left = pieces.size(), unreached = 0;
  auto paint = [&](Piece& p, bool first) {
    const P start{p.x, up ? p.y0 : p.y1}, end{p.x, up ? p.y1 : p.y0};
    if (!first) tool_on.push_back(std::fabs(here.x - start.x) <= s * 1.01 && std::fabs(here.y - start.y) <= s);
    waypoints.push_back({start.x, start.y});
    tool_on.push_back(true);
    waypoints.push_back({end.x, end.y});
    here = end, column = p.column, up = !up, p.done = true, --left;
  };
  paint(pieces.front(), true);
  while (left > 0) {
    double best = INFINITY;
    Piece* next = nullptr;
    bool flip = false;
    for (Piece& p : pieces) {
      if (p.done || (next && std::abs(p.column - column) > 1 && best <= 2 * s)) continue;
      for (bool f : {false, true}) {
        const bool u = up != f;
        const P start{p.x, u ? p.y0 : p.y1};
        const double d = std::hypot(start.x - here.x, start.y - here.y) + 10.0 * std::abs(p.column - column);
        if (d < best && w.freeMove(here, start)) best = d, next = &p, flip = f;
      }
    }
    if (!next) {
      // Back along the path already driven (its moves are free) to a waypoint that sees a piece
      // left, then on from there.
      std::vector<P> back;
      for (std::size_t k = waypoints.size() - 1; k-- > 0 && !next;) {
        const P at{waypoints[k][0].get<double>(), waypoints[k][1].get<double>()};
        back.push_back(at);
        for (Piece& p : pieces)
          for (bool f : {false, true})
            if (!p.done && !next && w.freeMove(at, {p.x, (up != f) ? p.y0 : p.y1})) next = &p, flip = f;
      }
      if (!next) {
        unreached = left;
        break;
      }
      for (P at : back) {
        tool_on.push_back(false);
        waypoints.push_back({at.x, at.y});
      }
      here = back.back();
    }
    if (flip) up = !up;
    paint(*next, false);
  }
  json out = {{"status", unreached ? "partial" : "ok"}, {"waypoints", waypoints}, {"tool_on", tool_on},
              {"stats", {{"columns", columns + 1}, {"pieces", pieces.size()}, {"unreached_pieces", unreached}}}};
  if (unreached) out["reason"] = std::to_string(unreached) + " column pieces no straight move reaches were left out";
  return out;
}

}  // namespace

int main() {
  std::string line;
  while (std::getline(std::cin, line)) {
    const json request = json::parse(line);
    json answer;
    try {
      answer = plan(request["problem"]);
    } catch (const std::exception& e) {
      answer = {{"status", "error"}, {"reason", e.what()}};
    }
    answer["protocol"] = 1;
    answer["id"] = request["id"];
    std::cout << answer.dump() << '\n' << std::flush;
  }
}
