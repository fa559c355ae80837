// Seeded wall generators. Portability of the bytes: our own PRNG (xoshiro256**, seeded by
// SplitMix64) and our own mapping to doubles (no std:: distributions, whose output differs
// between standard libraries); every coordinate is rounded to a millimetre, which also absorbs
// any last-bit difference of sin/cos between C libraries.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

#include "coverbench/datasets.hpp"
#include "coverbench/rng.hpp"

namespace coverbench {
namespace {

/// Millimetres: every generated coordinate goes through this.
double mm(double v) { return std::round(v * 1000.0) / 1000.0; }

Obstacle rectObstacle(double x, double y, double w, double h, std::string label) {
  Obstacle o;
  o.type = ObstacleType::Rect;
  x = mm(x), y = mm(y), w = mm(w), h = mm(h);
  o.polygon = {{x, y}, {mm(x + w), y}, {mm(x + w), mm(y + h)}, {x, mm(y + h)}};
  o.label = std::move(label);
  return o;
}

Obstacle circleObstacle(double x, double y, double r, std::string label) {
  Obstacle o;
  o.type = ObstacleType::Circle;
  o.center = {mm(x), mm(y)};
  o.radius = mm(r);
  o.label = std::move(label);
  return o;
}

Ring rectRing(double w, double h) { return {{0, 0}, {mm(w), 0}, {mm(w), mm(h)}, {0, mm(h)}}; }

Box obstacleBox(const Obstacle& o) {
  if (o.type != ObstacleType::Circle) return boundingBox(o.polygon);
  Box b;
  b.add({o.center.x - o.radius, o.center.y - o.radius});
  b.add({o.center.x + o.radius, o.center.y + o.radius});
  return b;
}

/// A wall under construction: obstacles are added only where they keep `margin` from the
/// boundary (unless allowed to touch it) and `gap` from every other obstacle.
struct Draft {
  Wall wall;

  bool insideWithMargin(const Obstacle& o, double margin) const {
    const Ring& b = wall.boundary;
    if (o.type == ObstacleType::Circle)
      return pointInRing(o.center, b) && distanceSegmentRingEdges(o.center, o.center, b) >= o.radius + margin;
    for (std::size_t i = 0; i < o.polygon.size(); ++i) {
      const Point p = o.polygon[i], q = o.polygon[(i + 1) % o.polygon.size()];
      if (!pointInRing(p, b) || distanceSegmentRingEdges(p, q, b) < margin) return false;
    }
    return true;
  }
  bool clearOfOthers(const Obstacle& o, double gap) const {
    const Box box = obstacleBox(o);
    for (const Obstacle& other : wall.obstacles)
      if (boxDistance(box, obstacleBox(other)) < gap) return false;
    return true;
  }
  /// Adds `o` when it fits; returns whether it did.
  bool add(Obstacle o, double gap, double margin) {
    if (!insideWithMargin(o, margin) || !clearOfOthers(o, gap)) return false;
    wall.obstacles.push_back(std::move(o));
    return true;
  }
  /// Adds without the boundary test (doors at the floor, obstacles crossing the edge).
  bool addTouching(Obstacle o, double gap) {
    if (!clearOfOthers(o, gap)) return false;
    wall.obstacles.push_back(std::move(o));
    return true;
  }
};

constexpr int kTries = 40;

Wall residential(Rng& rng) {
  Draft d;
  const double W = mm(rng.uniform(2.5, 6.0)), H = mm(rng.uniform(2.4, 3.0));
  d.wall.boundary = rectRing(W, H);
  double door_x = -1.0, door_w = 0.0;
  if (rng.chance(0.5)) {
    door_w = rng.uniform(0.8, 1.0);
    const double h = std::fmin(rng.uniform(2.0, 2.1), H - 0.25);
    door_x = rng.uniform(0.1, W - door_w - 0.1);
    d.addTouching(rectObstacle(door_x, 0.0, door_w, h, "door"), 0.0);
  }
  std::vector<Box> windows;
  const int n_windows = rng.integer(0, 2);
  for (int k = 0; k < n_windows; ++k)
    for (int t = 0; t < kTries; ++t) {
      const double w = rng.uniform(0.6, std::fmin(1.6, W / 2.0)), sill = rng.uniform(0.8, 1.0);
      const double h = std::fmin(rng.uniform(1.0, 1.5), H - sill - 0.15);
      if (d.add(rectObstacle(rng.uniform(0.1, W - w - 0.1), sill, w, h, "window"), 0.3, 0.1)) {
        windows.push_back(obstacleBox(d.wall.obstacles.back()));
        break;
      }
    }
  if (rng.chance(0.4))
    for (int t = 0; t < kTries; ++t) {
      const double w = rng.uniform(0.6, std::fmin(1.4, W - 0.4)), h = rng.uniform(0.45, 0.6);
      double x = rng.uniform(0.1, W - w - 0.1);
      if (!windows.empty() && t < kTries / 2) x = (windows[0].min_x + windows[0].max_x - w) / 2.0;  // under the window
      if (d.add(rectObstacle(x, rng.uniform(0.1, 0.15), w, h, "radiator"), 0.05, 0.05)) break;
    }
  const int n_sockets = rng.integer(0, 3);
  for (int k = 0; k < n_sockets; ++k)
    for (int t = 0; t < kTries; ++t) {
      const double y = rng.uniform(0.25, 0.35), x = rng.uniform(0.1, W - 0.2);  // in the order the bytes were pinned
      if (d.add(rectObstacle(x, y, 0.08, 0.08, "socket"), 0.05, 0.05)) break;
    }
  const int n_switches = rng.integer(0, 2);
  for (int k = 0; k < n_switches; ++k)
    for (int t = 0; t < kTries; ++t) {
      // Next to the door when there is one, at 1.05-1.15 m.
      double x = rng.uniform(0.1, W - 0.2);
      if (door_x >= 0.0 && t < kTries / 2)
        x = rng.chance(0.5) ? door_x - rng.uniform(0.15, 0.3) : door_x + door_w + rng.uniform(0.07, 0.2);
      if (d.add(rectObstacle(x, rng.uniform(1.05, 1.15), 0.08, 0.08, "switch"), 0.05, 0.05)) break;
    }
  return d.wall;
}

Wall facade(Rng& rng) {
  Draft d;
  const int floors = rng.integer(2, 5), columns = rng.integer(3, 10);
  const double floor_h = rng.uniform(2.8, 3.2), bay = rng.uniform(2.0, 3.2);
  const double side = rng.uniform(0.3, 1.0);
  const double W = mm(columns * bay + 2.0 * side), H = mm(floors * floor_h + rng.uniform(0.4, 1.0));
  d.wall.boundary = rectRing(W, H);
  const double win_w = rng.uniform(0.9, std::fmin(1.5, bay - 0.6)), win_h = rng.uniform(1.2, 1.6);
  const int entrance = rng.integer(0, columns - 1);
  for (int f = 0; f < floors; ++f) {
    const double level = f * floor_h;
    for (int c = 0; c < columns; ++c) {
      const double centre = side + (c + 0.5) * bay;
      if (f == 0 && c == entrance) {
        const double w = rng.uniform(1.0, std::fmin(1.4, bay - 0.4));
        d.addTouching(rectObstacle(centre - w / 2.0, 0.0, w, rng.uniform(2.2, 2.4), "door"), 0.1);
      } else if (f > 0 && rng.chance(0.2)) {
        // A balcony: its door, and the slab with railing in front of it (they overlap).
        d.add(rectObstacle(centre - win_w / 2.0, level + 0.05, win_w, 2.1, "balcony door"), 0.1, 0.1);
        const double bw = std::fmin(win_w + 0.8, bay - 0.2);
        d.addTouching(rectObstacle(centre - bw / 2.0, level - 0.25, bw, 1.25, "balcony"), 0.0);
      } else {
        d.add(rectObstacle(centre - win_w / 2.0, level + 0.9, win_w, win_h, "window"), 0.1, 0.1);
      }
    }
  }
  return d.wall;
}

Wall gable(Rng& rng) {
  Draft d;
  const double W = mm(rng.uniform(4.0, 10.0)), eaves = mm(rng.uniform(2.5, 6.0));
  const double ridge = mm(eaves + rng.uniform(1.5, 4.0)), rx = mm(W * rng.uniform(0.35, 0.65));
  d.wall.boundary = {{0, 0}, {W, 0}, {W, eaves}, {rx, ridge}, {0, eaves}};
  const int rounds = rng.integer(1, 2);
  for (int k = 0; k < rounds; ++k)
    for (int t = 0; t < kTries; ++t) {
      const double r = rng.uniform(0.2, 0.5);
      const double y = rng.uniform(eaves - 0.5, ridge - 0.6);
      if (d.add(circleObstacle(rx + rng.uniform(-1.5, 1.5), y, r, "round window"), 0.2, 0.15)) break;
    }
  const int windows = rng.integer(0, 3);
  for (int k = 0; k < windows; ++k)
    for (int t = 0; t < kTries; ++t) {
      const double w = rng.uniform(0.6, 1.4), sill = rng.uniform(0.8, 1.0);
      const double h = std::fmin(rng.uniform(1.0, 1.5), eaves - sill - 0.2);
      if (h < 0.5) break;
      if (d.add(rectObstacle(rng.uniform(0.15, W - w - 0.15), sill, w, h, "window"), 0.3, 0.15)) break;
    }
  if (rng.chance(0.4))
    for (int t = 0; t < kTries; ++t) {
      const double w = rng.uniform(0.8, 1.0);
      if (d.addTouching(rectObstacle(rng.uniform(0.15, W - w - 0.15), 0.0, w, std::fmin(2.1, eaves - 0.3), "door"), 0.15))
        break;
    }
  return d.wall;
}

Wall stairwell(Rng& rng) {
  Draft d;
  const int steps = rng.integer(6, 14);
  const double rise = mm(rng.uniform(0.15, 0.19)), run = mm(rng.uniform(0.25, 0.30));
  const double before = mm(rng.uniform(0.5, 1.5)), after = mm(rng.uniform(0.5, 1.5));
  const double clear = mm(rng.uniform(2.2, 3.0));
  Ring b{{0, 0}, {before, 0}};
  for (int i = 1; i <= steps; ++i) {
    b.push_back({mm(before + (i - 1) * run), mm(i * rise)});
    b.push_back({mm(before + i * run), mm(i * rise)});
  }
  const double top_x = mm(before + steps * run), top_y = mm(steps * rise);
  const double W = mm(top_x + after);
  b.push_back({W, top_y});
  b.push_back({W, mm(top_y + clear)});
  b.push_back({top_x, mm(top_y + clear)});
  b.push_back({before, clear});
  b.push_back({0, clear});
  d.wall.boundary = b;
  // Handrail brackets along the pitch, 0.9 m above the nosings, about every metre.
  const double pitch = std::atan2(rise, run);
  const double length = steps * std::hypot(rise, run);
  for (double t = rng.uniform(0.3, 0.6); t < length - 0.2; t += rng.uniform(0.9, 1.2)) {
    const double x = before + t * std::cos(pitch), y = t * std::sin(pitch) + 0.9;
    d.add(circleObstacle(x, y, rng.uniform(0.025, 0.04), "handrail bracket"), 0.1, 0.05);
  }
  if (rng.chance(0.5))
    for (int t = 0; t < kTries; ++t) {
      const double w = rng.uniform(0.5, 1.0);
      const double h = rng.uniform(0.6, 1.0), y = top_y + rng.uniform(1.0, 1.3), x = top_x + rng.uniform(-0.5, after - w);
      if (d.add(rectObstacle(x, y, w, h, "window"), 0.2, 0.1))
        break;
    }
  const int switches = rng.integer(0, 2);
  for (int k = 0; k < switches; ++k)
    for (int t = 0; t < kTries; ++t) {
      const bool upper = rng.chance(0.5);
      const double x = upper ? rng.uniform(top_x, W - 0.15) : rng.uniform(0.05, before - 0.1);
      const double y = (upper ? top_y : 0.0) + rng.uniform(1.05, 1.15);
      if (d.add(rectObstacle(x, y, 0.08, 0.08, "switch"), 0.05, 0.05)) break;
    }
  return d.wall;
}

Wall industrial(Rng& rng) {
  Draft d;
  const double W = mm(rng.uniform(5.0, 20.0)), H = mm(rng.uniform(3.0, 8.0));
  d.wall.boundary = rectRing(W, H);
  // Pipe penetrations: single ones and horizontal rows.
  const int groups = rng.integer(1, 5);
  for (int g = 0; g < groups; ++g) {
    const int in_row = rng.chance(0.5) ? rng.integer(2, 6) : 1;
    const double r = rng.uniform(0.03, 0.2), pitch = 2.0 * r + rng.uniform(0.15, 0.4);
    const double x0 = rng.uniform(0.3, W - 0.3), y = rng.uniform(0.3, H - 0.3);
    for (int k = 0; k < in_row; ++k) d.add(circleObstacle(x0 + k * pitch, y, r, "pipe"), 0.05, 0.1);
  }
  const int panels = rng.integer(1, 4);
  for (int k = 0; k < panels; ++k)
    for (int t = 0; t < kTries; ++t) {
      const double w = rng.uniform(0.4, 1.2), h = rng.uniform(0.4, 1.6);
      const double y = rng.uniform(0.1, H - h - 0.1), x = rng.uniform(0.1, W - w - 0.1);
      if (d.add(rectObstacle(x, y, w, h, "panel"), 0.1, 0.1))
        break;
    }
  // Rotated equipment: rectangles and hexagons at any angle.
  const int rotated = rng.integer(1, 4);
  for (int k = 0; k < rotated; ++k)
    for (int t = 0; t < kTries; ++t) {
      const Point c{rng.uniform(0.5, W - 0.5), rng.uniform(0.5, H - 0.5)};
      const double angle = rng.uniform(0.0, M_PI);
      Ring shape;
      if (rng.chance(0.5)) {
        const double a = rng.uniform(0.15, 0.5), b2 = rng.uniform(0.1, 0.4);
        shape = {{-a, -b2}, {a, -b2}, {a, b2}, {-a, b2}};
      } else {
        const double radius = rng.uniform(0.2, 0.6);
        for (int i = 0; i < 6; ++i) shape.push_back({radius * std::cos(i * M_PI / 3.0), radius * std::sin(i * M_PI / 3.0)});
      }
      Obstacle o;
      o.type = ObstacleType::Polygon;
      o.label = "equipment";
      for (const Point& p : shape) {
        const Point q = rotate(p, angle) + c;
        o.polygon.push_back({mm(q.x), mm(q.y)});
      }
      if (d.add(std::move(o), 0.1, 0.1)) break;
    }
  return d.wall;
}

Wall randomWall(Rng& rng) {
  Draft d;
  const double W = mm(rng.uniform(1.0, 15.0)), H = mm(rng.uniform(1.0, 10.0));
  d.wall.boundary = rectRing(W, H);
  const int n = rng.integer(0, 30);
  for (int k = 0; k < n; ++k) {
    const double w = rng.uniform(0.05, std::fmin(2.0, W / 2.0)), h = rng.uniform(0.05, std::fmin(2.0, H / 2.0));
    double x = rng.uniform(-w / 2.0, W - w / 2.0), y = rng.uniform(-h / 2.0, H - h / 2.0);
    if (rng.chance(0.1)) x = rng.chance(0.5) ? 0.0 : W - w;  // touching a side
    if (rng.chance(0.1)) y = rng.chance(0.5) ? 0.0 : H - h;
    d.wall.obstacles.push_back(rectObstacle(x, y, w, h, ""));  // may overlap others and the edge
  }
  return d.wall;
}

Wall openWall(Rng& rng) {
  // Nothing in the way: what a planner's rows, turns and boundary passes cost by themselves.
  Draft d;
  const double W = mm(rng.uniform(5.0, 12.0));
  const double H = mm(rng.uniform(5.0, 12.0));
  d.wall.boundary = rectRing(W, H);
  return d.wall;
}

Wall narrow(Rng& rng) {
  // Gaps near s + 2c = 0.14 m (the default tool, s = 0.1 m, c = 0.02 m): 0.7 to 1.4 times that,
  // between obstacles and the boundary and between neighbouring obstacles.
  Draft d;
  const double W = mm(rng.uniform(3.0, 8.0)), H = mm(rng.uniform(2.0, 3.0));
  d.wall.boundary = rectRing(W, H);
  auto gap = [&] { return 0.14 * rng.uniform(0.7, 1.4); };
  for (double x = rng.uniform(0.3, 0.8); x < W - 0.5;) {
    const double w = rng.uniform(0.2, 0.6);
    if (x + w > W - 0.3) break;
    switch (rng.integer(0, 2)) {
      case 0:  // from the floor up to a narrow gap below the top
        d.addTouching(rectObstacle(x, 0.0, w, H - gap(), "narrow gap above"), 0.0);
        break;
      case 1: {  // from the top down to a narrow gap above the floor
        const double g = gap();
        d.addTouching(rectObstacle(x, g, w, H - g, "narrow gap below"), 0.0);
        break;
      }
      default: {  // two blocks with a narrow slot between them
        const double y = rng.uniform(0.3, H / 2.0), g = gap();
        d.addTouching(rectObstacle(x, 0.0, w, y, "narrow slot"), 0.0);
        d.addTouching(rectObstacle(x, y + g, w, H - y - g + rng.uniform(-0.3, 0.0), "narrow slot"), 0.0);
      }
    }
    x += w + (rng.chance(0.5) ? gap() : rng.uniform(0.3, 1.0));
  }
  return d.wall;
}

Wall stress(Rng& rng) {
  Draft d;
  const double W = mm(rng.uniform(40.0, 60.0)), H = mm(rng.uniform(15.0, 25.0));
  d.wall.boundary = rectRing(W, H);
  const int n = rng.integer(150, 400);
  for (int t = 0; t < 10 * n && static_cast<int>(d.wall.obstacles.size()) < n; ++t) {
    const double w = rng.uniform(0.3, 1.5), h = rng.uniform(0.3, 1.5);
    const double y = rng.uniform(0.1, H - h - 0.1), x = rng.uniform(0.1, W - w - 0.1);
    d.add(rectObstacle(x, y, w, h, "window"), 0.15, 0.1);
  }
  return d.wall;
}

Wall field(Rng& rng) {
  // Outdoor polygons in the spirit of the published 100 m polygon sets and agricultural fields:
  // a star-shaped boundary 50-500 m across (5-10 corners at sorted angles), 1-15 holes that are
  // buildings (rotated rectangles) or trees (circles), kept 2 % of the size from the edge and
  // from each other. Planned at tool widths of 1-6 m (experiments/field.yaml).
  Draft d;
  const double size = rng.uniform(50.0, 500.0), R = size / 2.0;
  const int corners = rng.integer(5, 10);
  std::vector<double> angles;
  for (int k = 0; k < corners; ++k) angles.push_back((k + rng.uniform(0.1, 0.9)) * 2.0 * M_PI / corners);
  for (double a : angles) {
    const double r = R * rng.uniform(0.7, 1.0);
    d.wall.boundary.push_back({mm(R + r * std::cos(a)), mm(R + r * std::sin(a))});
  }
  const double margin = 0.02 * size;
  const int holes = rng.integer(1, 15);
  for (int k = 0; k < holes; ++k)
    for (int t = 0; t < kTries; ++t) {
      const Point c{rng.uniform(0.2 * size, 0.8 * size), rng.uniform(0.2 * size, 0.8 * size)};
      if (rng.chance(0.3)) {
        if (d.add(circleObstacle(c.x, c.y, rng.uniform(0.005, 0.02) * size, "tree"), margin, margin)) break;
        continue;
      }
      const double a = rng.uniform(0.02, 0.08) * size, b = rng.uniform(0.02, 0.06) * size, angle = rng.uniform(0.0, M_PI);
      Obstacle o;
      o.type = ObstacleType::Polygon;
      o.label = "building";
      for (const Point& p : {Point{-a, -b}, Point{a, -b}, Point{a, b}, Point{-a, b}}) {
        const Point q = rotate(p, angle) + c;
        o.polygon.push_back({mm(q.x), mm(q.y)});
      }
      if (d.add(std::move(o), margin, margin)) break;
    }
  return d.wall;
}

// --- the seeds' cases, as a fixed suite -------------------------------------------------------

Wall withRects(const std::string& name, double W, double H, std::vector<Obstacle> obstacles) {
  Wall w;
  w.name = name;
  w.boundary = rectRing(W, H);
  w.obstacles = std::move(obstacles);
  return w;
}

std::vector<Wall> seedCases() {
  std::vector<Wall> walls;
  walls.push_back(withRects("seed-1x1-empty", 1, 1, {}));
  walls.push_back(withRects("seed-5x5-1obs", 5, 5, {rectObstacle(2.0, 2.0, 1.0, 1.0, "window")}));
  walls.push_back(withRects("seed-5x5-3obs", 5, 5,
                            {rectObstacle(0.8, 2.5, 1.2, 1.5, "window"), rectObstacle(3.2, 0.0, 0.9, 2.1, "door"),
                             rectObstacle(2.4, 3.4, 0.15, 0.1, "socket")}));
  walls.push_back(withRects("seed-10x8-3obs", 10, 8,
                            {rectObstacle(1.5, 3.0, 2.0, 2.5, "window"), rectObstacle(5.0, 0.0, 1.2, 2.2, "door"),
                             rectObstacle(7.0, 4.0, 2.0, 2.0, "window")}));
  walls.push_back(withRects("seed-10x10-5obs", 10, 10,
                            {rectObstacle(1.0, 1.0, 1.5, 1.5, "window"), rectObstacle(4.0, 0.0, 1.0, 2.2, "door"),
                             rectObstacle(7.0, 2.0, 2.0, 1.5, "window"), rectObstacle(2.0, 6.0, 2.5, 2.0, "window"),
                             rectObstacle(6.5, 6.5, 1.5, 1.5, "window")}));
  walls.push_back(withRects("seed-20x10-empty", 20, 10, {}));
  Wall l;
  l.name = "seed-l-shape";
  l.boundary = {{0, 0}, {5, 0}, {5, 1.5}, {2, 1.5}, {2, 4}, {0, 4}};
  l.obstacles = {circleObstacle(3.5, 0.75, 0.2, "pipe")};
  walls.push_back(l);
  walls.push_back(withRects("seed-garden-trees", 8, 6,
                            {circleObstacle(1.5, 1.5, 0.5, "tree"), circleObstacle(2.3, 2.0, 0.4, "tree"),
                             circleObstacle(5.0, 3.0, 0.8, "tree"), circleObstacle(7.9, 5.9, 0.5, "tree"),
                             circleObstacle(4.0, 5.2, 0.05, "post")}));
  walls.push_back(withRects("seed-narrow-passages", 6, 1.2,
                            {rectObstacle(1.4, 0.0, 0.2, 1.04, "tall window"),
                             rectObstacle(3.0, 0.15, 0.3, 1.05, "cabinet"),
                             rectObstacle(4.5, 0.0, 0.2, 1.1, "too tall to pass")}));
  return walls;
}

using Generator = std::function<Wall(Rng&)>;

const std::map<std::string, Generator>& generators() {
  static const std::map<std::string, Generator> g = {
      {"residential", residential}, {"facade", facade}, {"gable", gable},   {"stairwell", stairwell},
      {"industrial", industrial},   {"random", randomWall}, {"narrow", narrow}, {"stress", stress},
      {"open", openWall},           {"field", field}};
  return g;
}

std::uint64_t familyTag(const std::string& family) {
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a
  for (unsigned char ch : family) h = (h ^ ch) * 1099511628211ULL;
  return h;
}

}  // namespace

const std::vector<FamilyInfo>& wallFamilies() {
  static const std::vector<FamilyInfo> families = {
      {"residential", "interior walls 2.5-6 m x 2.4-3 m: a door at the floor, windows at sill height, sockets, switches, a radiator"},
      {"facade", "facades of 2-5 storeys and 3-10 bays: a grid of windows, balconies, an entrance door"},
      {"gable", "gable walls (pentagons with a sloped top) with round windows, rectangular windows and a door"},
      {"stairwell", "stepped walls along a flight of 6-14 stairs with handrail brackets, a window and switches"},
      {"industrial", "5-20 m walls with pipe penetrations (circles, single and in rows), panels, rotated equipment"},
      {"random", "uniform random rectangles that may overlap each other and touch or cross the boundary"},
      {"narrow", "gaps of 0.7-1.4 times s + 2c (0.14 m for the default tool) between obstacles and the boundary"},
      {"stress", "40-60 m x 15-25 m walls with 150-400 rectangular openings"},
      {"open", "obstacle-free rectangles 5-12 m x 5-12 m: rows, turns and boundary passes alone"},
      {"field", "outdoor polygons 50-500 m across with 1-15 buildings and trees, for tools of 1-6 m"},
      {"seed-cases", "the seeds' cases: 1x1 empty, 5x5 with 1 and 3, 10x8 with 3, 10x10 with 5, 20x10 empty, L-shape, garden trees, narrow passages", true},
  };
  return families;
}

const FamilyInfo& findFamily(const std::string& family, const std::string& source, const std::string& field) {
  for (const FamilyInfo& f : wallFamilies())
    if (f.name == family) return f;
  std::string known;
  for (const FamilyInfo& f : wallFamilies()) known += (known.empty() ? "" : ", ") + f.name;
  throw InputError(source, field, "unknown family '" + shownBytes(family) + "' (known: " + known + ")");
}

std::size_t suiteSize(const std::string& suite) {
  if (suite == "seed-cases") return seedCases().size();
  throw std::invalid_argument("not a fixed suite: " + suite);
}

Wall generateWall(const std::string& family, std::uint64_t seed, std::size_t index) {
  const FamilyInfo& info = findFamily(family, "generator", "family");
  char name[128];
  if (info.fixed_suite) {
    std::vector<Wall> walls = seedCases();
    if (index >= walls.size()) throw std::out_of_range("suite " + family + " has " + std::to_string(walls.size()) + " walls");
    return walls[index];
  }
  std::snprintf(name, sizeof name, "%s-s%llu-%04zu", family.c_str(), static_cast<unsigned long long>(seed), index);
  const Generator& make = generators().at(family);
  // Each wall has its own stream: independent of how many walls are generated before it.
  std::uint64_t mix = familyTag(family) ^ (seed * 0x9e3779b97f4a7c15ULL);
  mix = Rng::splitmix(mix) ^ static_cast<std::uint64_t>(index);
  for (std::uint64_t attempt = 0; attempt < 64; ++attempt) {
    std::uint64_t stream = mix + attempt * 0xd1b54a32d192ed03ULL;
    Rng rng(Rng::splitmix(stream));
    Wall wall = make(rng);
    wall.name = name;
    // Random walls may bury the wall under rectangles: drop the last ones until it is valid.
    for (;;) {
      try {
        validateWall(wall, name);
        return wall;
      } catch (const InputError&) {
        if (family != "random" || wall.obstacles.empty()) break;
        wall.obstacles.pop_back();
      }
    }
  }
  throw std::logic_error("generator " + family + " made no valid wall for seed " + std::to_string(seed) + ", index " +
                         std::to_string(index));
}

std::vector<Wall> generateWalls(const std::string& family, std::uint64_t seed, std::size_t count) {
  const FamilyInfo& info = findFamily(family, "generator", "family");
  if (info.fixed_suite) {
    std::vector<Wall> walls = seedCases();
    if (count > 0 && count < walls.size()) walls.resize(count);
    return walls;
  }
  std::vector<Wall> walls;
  walls.reserve(count);
  for (std::size_t i = 0; i < count; ++i) walls.push_back(generateWall(family, seed, i));
  return walls;
}

}  // namespace coverbench
