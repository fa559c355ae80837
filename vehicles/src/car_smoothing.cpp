// A planner's path made drivable by a car: fillets, Dubins / Reeds-Shepp turns, skips
// (docs/vehicles.md). Every piece is checked against the free region before it is used.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "coverbench/car.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

struct Segment {
  Point a, b;
  bool tool = false;
  double length = 0.0;
  Point dir;  ///< unit
  double heading = 0.0;
};

double angleBetween(double from, double to) { return wrapAngle(to - from); }

/// The headings segment k of `path` starts and ends with: its chord's, turned back and on by half
/// an arc's angle.
std::pair<double, double> headings(const Path& path, std::size_t k) {
  const Point d = path.waypoints[k + 1] - path.waypoints[k];
  const double chord = std::atan2(d.y, d.x), bulge = path.bulgeOf(k);
  const double half = bulge == 0.0 ? 0.0 : 2.0 * std::atan(bulge);
  return {chord - half, chord + half};
}

/// A curve that turns more than a quarter circle beyond what its two poses differ by is a loop (a
/// Dubins car circling round to line up with a pose just beside it): painted, it scribbles
/// circles over the wall; such a curve is not taken.
bool loops(const Path& curve, Pose from, Pose to) {
  double turning = 0.0;
  for (std::size_t k = 0; k < curve.segments(); ++k) turning += std::fabs(4.0 * std::atan(curve.bulgeOf(k)));
  return turning > std::fabs(angleBetween(from.heading, to.heading)) + M_PI / 2.0 + 1e-9;
}

/// Appends a primitive to the curve, from `pose` (advanced); arcs in pieces of at most a quarter
/// circle.
void appendPrimitive(Path& out, Pose& pose, CurvePrimitive c, double radius, bool tool) {
  // Pieces of rounding size are left out (the arrival check below bounds what that costs): a
  // tiny arc's radius would not survive ending the curve exactly on its target.
  if (c.kind == 'S' ? std::fabs(c.amount) * radius < 1e-9 : std::fabs(c.amount) < 1e-6) return;
  if (c.kind == 'S') {
    pose.at = pose.at + Point{std::cos(pose.heading), std::sin(pose.heading)} * (c.amount * radius);
    out.moveTo(pose.at, tool);
    return;
  }
  const double turn = c.kind == 'L' ? 1.0 : -1.0;  // the heading turns by turn * amount
  const Point centre = pose.at + Point{-std::sin(pose.heading), std::cos(pose.heading)} * (turn * radius);
  const int pieces = static_cast<int>(std::ceil(std::fabs(c.amount) / (M_PI / 2.0)));
  for (int k = 1; k <= pieces; ++k) {
    const double heading = pose.heading + turn * c.amount / pieces;
    const Point next = centre + Point{std::sin(heading), -std::cos(heading)} * (turn * radius);
    // The position turns about the centre by the heading's change: that is the arc's signed angle.
    out.arcTo(next, std::tan(turn * c.amount / pieces / 4.0), tool);
    pose.heading = heading;
    pose.at = next;
  }
}

/// a into [0, 2 pi), exactly as fmod would put it. The angles here are within two turns of that
/// range, where one subtraction or addition of 2 pi is exact (Sterbenz: both lie within a factor
/// of two of each other), so fmod (tens of instructions, half a million calls a plan) is needed
/// only beyond them; -2 pi goes to fmod, which keeps its sign of zero.
double mod2pi(double a) {
  constexpr double kTwoPi = 2.0 * M_PI;
  if (a >= 0.0 && a < kTwoPi) return a;
  if (a >= kTwoPi && a < 2.0 * kTwoPi) return a - kTwoPi;
  if (a < 0.0 && a > -kTwoPi) return a + kTwoPi;
  if (a < -kTwoPi && a > -2.0 * kTwoPi) return (a + kTwoPi) + kTwoPi;
  const double r = std::fmod(a, kTwoPi);
  return r < 0.0 ? r + kTwoPi : r;
}

/// A Dubins word: three primitives (turn, straight or turn, turn).
using DubinsWord = std::array<CurvePrimitive, 3>;

/// A curve's length in turn radii.
template <class Word>
double wordLength(const Word& word) {
  double sum = 0.0;
  for (const CurvePrimitive& c : word) sum += std::fabs(c.amount);
  return sum;
}

/// The Dubins words that exist between two poses (at most six), without allocating: the sweep
/// measures tens of thousands of these.
struct DubinsWords {
  std::array<DubinsWord, 6> words;
  std::size_t count = 0;
  void add(DubinsWord w) { words[count++] = w; }
  const DubinsWord* begin() const { return words.data(); }
  const DubinsWord* end() const { return words.data() + count; }
};

/// The six Dubins words between the normalised poses (Shkel & Lumelsky 2001): distance d in radii,
/// headings alpha and beta relative to the line between them. Each gives (t, p, q) or nothing;
/// `emit` gets those that exist, in that order, but for a word whose middle part alone is no
/// shorter than `bound()`: it is not finished (its atan2s not taken), as no word is shorter than
/// its middle part.
template <class Bound, class Emit>
void dubinsWordsWithin(double d, double alpha, double beta, Bound bound, Emit emit) {
  const double sa = std::sin(alpha), sb = std::sin(beta), ca = std::cos(alpha), cb = std::cos(beta);
  const double cab = std::cos(alpha - beta);
  // LSL and LRL measure the same angle, with opposite signs of its sine (atan2 is odd in it, and
  // at a sine of exactly zero both are +0); RSR and RLR measure one angle. One atan2 each serves both.
  const double lsl = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb);
  const double lrl = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0;
  const double left = lsl >= 0.0 || std::fabs(lrl) <= 1.0 ? std::atan2(cb - ca, d + sa - sb) : 0.0;
  if (lsl >= 0.0 && std::sqrt(lsl) < bound())
    emit(DubinsWord{{{'L', mod2pi(left - alpha)}, {'S', std::sqrt(lsl)}, {'L', mod2pi(beta - left)}}});
  const double rsr = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa);
  const double rlr = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0;
  bool have_right = false;
  double right = 0.0;
  auto rightAngle = [&] {
    if (!have_right) right = std::atan2(ca - cb, d - sa + sb), have_right = true;
    return right;
  };
  if (rsr >= 0.0 && std::sqrt(rsr) < bound())
    emit(DubinsWord{{{'R', mod2pi(alpha - rightAngle())}, {'S', std::sqrt(rsr)}, {'R', mod2pi(rightAngle() - beta)}}});
  double p2 = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb);  // LSR
  if (p2 >= 0.0 && std::sqrt(p2) < bound()) {
    const double p = std::sqrt(p2);
    const double tmp = std::atan2(-ca - cb, d + sa + sb) - std::atan2(-2.0, p);
    emit(DubinsWord{{{'L', mod2pi(tmp - alpha)}, {'S', p}, {'R', mod2pi(tmp - beta)}}});
  }
  p2 = -2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb);  // RSL
  if (p2 >= 0.0 && std::sqrt(p2) < bound()) {
    const double p = std::sqrt(p2);
    const double tmp = std::atan2(ca + cb, d - sa - sb) - std::atan2(2.0, p);
    emit(DubinsWord{{{'R', mod2pi(alpha - tmp)}, {'S', p}, {'L', mod2pi(beta - tmp)}}});
  }
  if (std::fabs(rlr) <= 1.0) {  // RLR
    const double p = mod2pi(2.0 * M_PI - std::acos(rlr));
    if (p < bound()) {
      const double t = mod2pi(alpha - rightAngle() + p / 2.0);
      emit(DubinsWord{{{'R', t}, {'L', p}, {'R', mod2pi(alpha - beta - t + p)}}});
    }
  }
  if (std::fabs(lrl) <= 1.0) {  // LRL
    const double p = mod2pi(2.0 * M_PI - std::acos(lrl));
    if (p < bound()) {
      const double t = mod2pi(-alpha - (ca == cb ? left : -left) + p / 2.0);
      emit(DubinsWord{{{'L', t}, {'R', p}, {'L', mod2pi(beta - alpha - t + p)}}});
    }
  }
}

/// Every Dubins word between the normalised poses (dubinsWordsWithin).
DubinsWords dubinsWords(double d, double alpha, double beta) {
  DubinsWords out;
  dubinsWordsWithin(d, alpha, beta, [] { return INFINITY; }, [&](const DubinsWord& w) { out.add(w); });
  return out;
}

/// The shortest of those words' lengths (in radii; infinite when there is none), the same number
/// to the last bit, without finishing the words that cannot be shorter (turn-aware orders and the
/// car's searches measure these by the ten thousand).
double dubinsShortest(double d, double alpha, double beta) {
  double best = INFINITY;
  dubinsWordsWithin(d, alpha, beta, [&] { return best; }, [&](const DubinsWord& w) { best = std::min(best, wordLength(w)); });
  return best;
}

/// Segments a curve has at most, but for rounding: up to five primitives (Reeds-Shepp), arcs in
/// pieces of a quarter circle (space reserved for them up front: curves are built by the ten
/// thousand).
constexpr std::size_t kCurveSegments = 16;

/// The curve of `primitives` from `from` into `out` (emptied first, its room kept: curves are
/// built by the ten thousand), and whether it arrives at `to`.
template <class Word>
void drive(Pose from, Pose to, const Word& primitives, double radius, bool tool, Path& out, bool& arrives) {
  out.waypoints.clear();
  out.tool_on.clear();
  out.bulge.clear();
  out.reserve(kCurveSegments);
  out.moveTo(from.at, tool);
  Pose pose = from;
  for (const CurvePrimitive& c : primitives) appendPrimitive(out, pose, c, radius, tool);
  // Within 1e-9 m (and a fifth of the heading tolerance: the pieces left out turn at most 1e-6 rad).
  arrives = distance(pose.at, to.at) <= 1e-9 * (1.0 + radius) &&
            std::fabs(angleBetween(pose.heading, to.heading)) <= kCarHeadingTolerance / 5.0;
}

}  // namespace

namespace {

/// The first of `words` (tried in order) that arrives at `to`, as a path in `clean` (emptied
/// first, its room kept); false, and `clean` empty, if none does.
template <class Words>
bool firstArriving(Pose from, Pose to, const Words& words, double radius, bool reverse, bool tool, Path& clean) {
  for (const auto& primitives : words) {
    bool arrives = false;
    thread_local Path out;
    drive(from, to, primitives, radius, tool, out, arrives);
    if (!arrives) continue;
    // End exactly at `to` (the last chord moves by rounding), without segments of rounding
    // length, whose direction means nothing.
    clean.waypoints.clear();
    clean.tool_on.clear();
    clean.bulge.clear();
    clean.reserve(out.segments());
    clean.moveTo(from.at, tool);
    for (std::size_t i = 0; i < out.segments(); ++i) {
      const bool last = i + 1 == out.segments();
      const Point p = last ? to.at : out.waypoints[i + 1];
      if (distance(clean.waypoints.back(), p) <= 1e-9 * (1.0 + radius)) {
        if (last && clean.waypoints.size() > 1) clean.waypoints.back() = to.at;
        continue;
      }
      clean.arcTo(p, out.bulgeOf(i), tool);
    }
    // Ending exactly on `to` moved the last piece's end by up to 1e-9 m: a piece only a little
    // longer than that turns by a heading a car cannot take. Such a word is not taken.
    // Each segment's headings measured once: from `from`'s heading through every join to `to`'s.
    bool joins = true;
    double arrive = from.heading;
    for (std::size_t k = 0; k < clean.segments() && joins; ++k) {
      const auto [start, end] = headings(clean, k);
      joins = headingsJoin(arrive, start, reverse);
      arrive = end;
    }
    if (clean.segments() == 0 || (joins && headingsJoin(arrive, to.heading, reverse))) return true;
  }
  clean.waypoints.clear();
  clean.tool_on.clear();
  clean.bulge.clear();
  return false;
}

}  // namespace

Path carCurve(Pose from, Pose to, double radius, bool reverse, bool tool) {
  Path out;
  carCurveInto(from, to, radius, reverse, tool, out);
  return out;
}

bool carCurveInto(Pose from, Pose to, double radius, bool reverse, bool tool, Path& out) {
  if (reverse) return firstArriving(from, to, std::array{reedsSheppPrimitives(from, to, radius)}, radius, true, tool, out);
  const Point delta = to.at - from.at;
  const double d = norm(delta) / radius, phi = std::atan2(delta.y, delta.x);
  DubinsWords words = dubinsWords(d, mod2pi(from.heading - phi), mod2pi(to.heading - phi));
  // Shortest first, ties in the order found (a stable insertion sort: at most six words, no
  // buffer to allocate).
  for (std::size_t i = 1; i < words.count; ++i)
    for (std::size_t j = i; j > 0 && wordLength(words.words[j]) < wordLength(words.words[j - 1]); --j)
      std::swap(words.words[j], words.words[j - 1]);
  return firstArriving(from, to, words, radius, false, tool, out);
}

double carCurveLength(Pose from, Pose to, double radius, bool reverse) {
  if (reverse) return reedsSheppLength(from, to, radius);
  const Point delta = to.at - from.at;
  const double d = norm(delta) / radius, phi = std::atan2(delta.y, delta.x);
  // (The shortest length in radii times the radius is the shortest of the lengths times it:
  // multiplying by a positive number keeps their order.)
  return dubinsShortest(d, mod2pi(from.heading - phi), mod2pi(to.heading - phi)) * radius;
}

bool headingsJoin(double end, double start, bool reverse) {
  const double jump = std::fabs(angleBetween(end, start));
  return jump <= kCarHeadingTolerance / 2.0 || (reverse && jump >= M_PI - kCarHeadingTolerance / 2.0);
}

std::size_t cusps(const Path& path) {
  std::size_t n = 0;
  for (std::size_t k = 1; k < path.segments(); ++k)
    n += std::fabs(angleBetween(headings(path, k - 1).second, headings(path, k).first)) > M_PI / 2.0;
  return n;
}

double startHeading(const Path& path) { return headings(path, 0).first; }

Pose endPose(const Path& path) {
  const std::size_t k = path.segments() - 1;
  return {path.waypoints.back(), headings(path, k).second};
}

void checkDrivable(const Path& path, const VehicleModel& car, const char* who) {
  double end_heading = 0.0;
  for (std::size_t k = 0; k < path.segments(); ++k) {
    const double bulge = path.bulgeOf(k);
    if (bulge != 0.0 && arcGeometry(path.waypoints[k], path.waypoints[k + 1], bulge).radius < car.turn_radius)
      throw std::logic_error(std::string(who) + " made an arc tighter than the turn radius at segment " + std::to_string(k));
    const auto [start, end] = headings(path, k);
    if (k > 0 && !headingsJoin(end_heading, start, car.reverse))
      throw std::logic_error(std::string(who) + " left a heading jump of " +
                             std::to_string(std::fabs(angleBetween(end_heading, start))) + " rad at segment " +
                             std::to_string(k));
    end_heading = end;
  }
}

CarSmoothing smoothForCar(const Workspace& ws, const Path& in) {
  const VehicleModel& car = ws.vehicle();
  const double rho = car.turn_radius * (1.0 + kCarRadiusSlack);
  CarSmoothing out;
  if (in.waypoints.empty()) return out;
  out.path.moveTo(in.waypoints.front(), false);
  // The path by arc length: segment k from w[k] to w[k + 1] starts at along[k].
  std::vector<Segment> segs;
  std::vector<double> along;
  double total = 0.0;
  for (std::size_t i = 0; i < in.segments(); ++i) {
    Segment sg{in.waypoints[i], in.waypoints[i + 1], in.tool_on[i]};
    sg.length = distance(sg.a, sg.b);
    if (sg.length == 0.0) continue;
    sg.dir = (sg.b - sg.a) * (1.0 / sg.length);
    sg.heading = std::atan2(sg.dir.y, sg.dir.x);
    segs.push_back(sg);
    along.push_back(total);
    total += sg.length;
  }
  // A forward-only car cannot drive a spur (out and straight back the same way, as the spiral's
  // corners have): its painting is left out and the path closes over it.
  if (!car.reverse) {
    std::vector<Segment> kept;
    for (const Segment& sg : segs) {
      if (!kept.empty() && sg.a == kept.back().b && sg.b == kept.back().a) {
        if (kept.back().tool) out.cut_m += kept.back().length;
        if (sg.tool) out.cut_m += sg.length;
        out.skipped += 2;
        kept.pop_back();
        continue;
      }
      kept.push_back(sg);
    }
    segs = std::move(kept);
    along.clear();
    total = 0.0;
    for (const Segment& sg : segs) {
      along.push_back(total);
      total += sg.length;
    }
  }
  const std::size_t m = segs.size();
  if (m == 0) return out;
  // The segment holding arc length x (the later one at a vertex), and the pose there.
  auto segmentAt = [&](double x) {
    const auto it = std::upper_bound(along.begin(), along.end(), x);
    return static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - along.begin()) - 1));
  };
  // The pose at arc length x: heading as the car arrives there (at a vertex: the segment before
  // it) or as it leaves (the segment after it).
  auto poseAt = [&](double x, bool arriving) {
    std::size_t k = segmentAt(x);
    if (arriving && k > 0 && x <= along[k]) --k;
    const double into = std::clamp(x - along[k], 0.0, segs[k].length);
    return Pose{into >= segs[k].length ? segs[k].b : segs[k].a + segs[k].dir * into, segs[k].heading};
  };
  // Painted all along [x0, x1]; and the painted length within it (what a turn leaves undriven).
  auto paintedThrough = [&](double x0, double x1) {
    for (std::size_t k = segmentAt(x0); k < m && along[k] < x1; ++k)
      if (!segs[k].tool) return false;
    return true;
  };
  auto paintedLength = [&](double x0, double x1) {
    double sum = 0.0;
    for (std::size_t k = segmentAt(x0); k < m && along[k] < x1; ++k)
      if (segs[k].tool) sum += std::max(0.0, std::min(x1, along[k] + segs[k].length) - std::max(x0, along[k]));
    return sum;
  };
  // The painted pieces of [x0, x1] (what a skip or a stop leaves undriven), for a planner to cover
  // otherwise.
  auto recordUndriven = [&](double x0, double x1) {
    for (std::size_t k = segmentAt(x0); k < m && along[k] < x1; ++k) {
      const double lo = std::max(x0, along[k]), hi = std::min(x1, along[k] + segs[k].length);
      if (segs[k].tool && hi - lo > 1e-9)
        out.undriven.emplace_back(segs[k].a + segs[k].dir * (lo - along[k]), segs[k].a + segs[k].dir * (hi - along[k]));
    }
  };
  auto append = [&](const Path& piece) {
    for (std::size_t k = 0; k < piece.segments(); ++k) out.path.arcTo(piece.waypoints[k + 1], piece.bulgeOf(k), piece.tool_on[k]);
  };

  // Drives the path straight from x to the point at y (no corner between them), tool as the segment.
  auto driveTo = [&](double y) {
    const std::size_t k = segmentAt(y);
    const Point target = poseAt(y, true).at;
    // Where the car already is, but for rounding: a segment of 1e-14 m has no heading to keep.
    if (distance(out.path.waypoints.back(), target) <= 1e-9) return;
    out.path.moveTo(target, segs[k > 0 && y <= along[k] ? k - 1 : k].tool);
  };
  // The pose a curve starts from after driveTo(y): where the car already is when that is within
  // rounding of y (driveTo then stays; a curve from the rounded point would start off its end,
  // and its first piece, when tiny, in a direction that means nothing).
  auto startPose = [&](double y) {
    Pose p = poseAt(y, true);
    if (distance(out.path.waypoints.back(), p.at) <= 1e-9) p.at = out.path.waypoints.back();
    return p;
  };
  // Where the car was after each step (the output's waypoints then, its arc length), to go back to.
  struct Checkpoint {
    std::size_t waypoints;
    double x;
  };
  std::vector<Checkpoint> checkpoints;
  // The car is at arc length x, on the path, heading along it.
  double x = 0.0;
  // Drives `curve` (from where the output ends), which leaves the path's painting `cut` m undriven
  // and `skipped` segments out, to arc length `to`.
  auto take = [&](const Path& curve, double to, double cut, std::size_t skipped) {
    append(curve);
    ++out.turns;
    out.cusps += cusps(curve);
    out.cut_m += cut;
    out.skipped += skipped;
    x = to;
  };
  // Where a turn may start and end, in turn radii back before and on after a corner: fewest first.
  static const std::vector<std::pair<double, double>> kTurnShifts = [] {
    const double steps[] = {0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0};
    std::vector<std::pair<double, double>> shifts;
    for (double back : steps)
      for (double on : steps) shifts.emplace_back(back, on);
    std::stable_sort(shifts.begin(), shifts.end(), [](const auto& u, const auto& v) {
      return u.first + u.second < v.first + v.second || (u.first + u.second == v.first + v.second && u.first < v.first);
    });
    return shifts;
  }();
  // Where a skip may enter a later segment, in turn radii from its start, nearest first: on the
  // corner's own next segment and the next few (further on, only the start is tried).
  static constexpr double kSkipInto[] = {0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0};
  static constexpr std::size_t kSkipIntoSegments = 8;
  // The sharpest turn a car that reverses rounds; sharper corners it drives into and backs out of.
  static constexpr double kCornerManoeuvre = M_PI / 3.0;
  // A skip that leaves more painting than this (m) is searched for a shorter way first: at most
  // kSkipSearches routes of kSkipSearchExpansions poses each, and kSmoothingSearchBudget poses over
  // the whole path (about 2 us each).
  static constexpr double kSearchSkip = 1.0;
  static constexpr std::size_t kSkipSearches = 2, kSkipSearchExpansions = 600, kSmoothingSearchBudget = 6000;
  std::size_t searched = 0;
  std::size_t corner = 1;  // the next vertex that may be a corner
  while (true) {
    if (checkpoints.empty() || checkpoints.back().x < x) checkpoints.push_back({out.path.waypoints.size(), x});
    // A vertex whose segments' headings differ by less than the car's rules notice is no corner:
    // a fillet of it (a few picometres) would be a chord whose heading is rounding noise.
    while (corner < m && (along[corner] <= x ||
                          std::fabs(angleBetween(segs[corner - 1].heading, segs[corner].heading)) <= kCarHeadingTolerance / 4.0))
      ++corner;
    if (corner >= m) {
      // No corner left: drive to the end, from where the car is (a turn may end there already: a
      // segment of no length has no heading to keep).
      for (std::size_t k = segmentAt(x); k < m; ++k)
        if (distance(out.path.waypoints.back(), segs[k].b) > 1e-9) out.path.moveTo(segs[k].b, segs[k].tool);
      break;
    }
    const double at = along[corner];  // the corner's arc length
    const Segment &s = segs[corner - 1], &t = segs[corner];
    const double theta = angleBetween(s.heading, t.heading);
    // A car that reverses drives into the corner (painting it), backs straight out to `from` over
    // what it just painted, and takes `curve` from there (steps 0 and 2b).
    auto backOutAndTake = [&](Point from, const Path& curve, double to, double cut, std::size_t skipped) {
      driveTo(at);
      out.path.moveTo(from, false);
      take(curve, to, cut, skipped);
    };
    // 0. A car that reverses paints a sharp corner whole: it drives into it, backs out along the
    //    segment it came by, and comes back into the corner along the next one (reversing), then
    //    drives on from it. A fillet or a curve would leave the corner's tip unpainted: on F's
    //    edge (rho + r)^2 (1 - pi / 4) at a right angle, far more than the tool's own corner
    //    loss; on the rings inside, the slivers between their fillets, which no other pass
    //    paints (on a 6 m x 4 m rectangle 0.9917 of R covered with fillets, 0.9995 without).
    if (car.reverse && std::fabs(theta) >= kCornerManoeuvre && std::fabs(theta) < M_PI - 1e-9 && s.tool && t.tool) {
      // Backing out by the fillet's tangent length, the fillet, and straight back into the
      // corner along the next segment: every piece on the path's segments or the fillet.
      const double d = rho * std::tan(std::fabs(theta) / 2.0);
      if (d <= at - along[corner - 1] && d <= t.length) {
        const Point p = s.b - s.dir * d, q = t.a + t.dir * d;
        const double bulge = std::tan(theta / 4.0);
        if (arcFree(ws, p, q, bulge)) {
          driveTo(at);
          out.path.moveTo(p, false);
          out.path.arcTo(q, bulge, false);
          out.path.moveTo(t.a, false);
          ++out.turns;
          out.cusps += 2;
          x = at;
          continue;
        }
      }
      bool done = false;
      const Pose corner_pose{t.a, t.heading};
      for (double back : {0.5, 1.0, 1.5, 2.0, 3.0}) {
        const double from = at - back * rho;
        if (from < along[corner - 1]) break;
        const Pose p = poseAt(from, true);
        const Path curve = carCurve(p, corner_pose, rho, true, false);
        if (curve.waypoints.empty() || !pathFree(ws, curve)) continue;
        backOutAndTake(p.at, curve, at, 0.0, 0);
        done = true;
        break;
      }
      if (done) continue;
    }
    // 1. A fillet of the turn radius, tangent to both segments, where both are long enough.
    const double d = std::fabs(theta) < M_PI - 1e-9 ? rho * std::tan(std::fabs(theta) / 2.0) : INFINITY;
    if (d <= at - x && d <= at - along[corner - 1] && d <= t.length) {
      const Point p = s.b - s.dir * d, q = t.a + t.dir * d;
      const double bulge = std::tan(theta / 4.0);
      if (arcFree(ws, p, q, bulge)) {
        driveTo(at - d);
        out.path.arcTo(q, bulge, s.tool && t.tool);
        ++out.fillets;
        out.cut_m += paintedLength(at - d, at + d);
        x = at + d;
        continue;
      }
    }
    // 2. A Dubins / Reeds-Shepp curve from a point moved back before the corner to a point moved
    //    on after it (in turn radii; fewest first), past any corners in between.
    bool done = false;
    for (const auto& [back, on] : kTurnShifts) {
      const double from = at - back * rho, to = at + on * rho;
      if (from < x || to > total) continue;
      const Pose p = startPose(from), q = poseAt(to, false);
      const Path curve = carCurve(p, q, rho, car.reverse, paintedThrough(from, to));
      if (curve.waypoints.empty() || loops(curve, p, q) || !pathFree(ws, curve)) continue;
      driveTo(from);
      const std::size_t s0 = segmentAt(from), s1 = segmentAt(to);
      take(curve, to, paintedLength(from, to), s1 - s0 > 1 ? s1 - s0 - 1 : 0);
      done = true;
      break;
    }
    if (done) continue;
    // 2b. A car that reverses drives into the corner (painting it), backs straight out along the
    //     segment it came by, and turns from there: the shortest curve from the corner itself
    //     often swings out of F where a short reversal first leaves it room.
    if (car.reverse)
      for (const auto& [back, on] : kTurnShifts) {
        const double from = at - back * rho, to = at + on * rho;
        if (back == 0.0 || from < along[corner - 1] || to > total) continue;
        const Pose p = poseAt(from, true), q = poseAt(to, false);
        const Path curve = carCurve(p, q, rho, true, paintedThrough(at, to));
        if (curve.waypoints.empty() || loops(curve, p, q) || !pathFree(ws, curve)) continue;
        const std::size_t s0 = segmentAt(at), s1 = segmentAt(to);
        backOutAndTake(p.at, curve, to, paintedLength(at, to), s1 - s0 > 1 ? s1 - s0 - 1 : 0);
        done = true;
        break;
      }
    if (done) continue;
    // 3. Skip, tool off: from the corner, or a point further back (a forward-only car facing a
    //    wall needs room to turn), to the nearest point along the path a free curve reaches on a
    //    later segment: its start, or up to kSkipInto turn radii into it (a long segment whose
    //    start lies in a corner the car cannot turn into is entered a little further on, not
    //    skipped whole). Ties go to the point moved back least.
    struct Skip {
      double from, to;
      std::size_t j;
      Path curve;
      bool searched = false;
    };
    std::optional<Skip> skip;
    for (double back : {0.0, 1.0, 2.0, 4.0, 8.0}) {
      const double from = at - back * rho;
      if (from < x) continue;
      const Pose p = startPose(from);
      bool found = false;
      for (std::size_t j = corner; j < m && !found && !(skip && along[j] >= skip->to); ++j)
        for (double into : kSkipInto) {
          const double to = along[j] + into * rho;
          if (j == corner && into == 0.0) continue;
          if ((into > 0.0 && (into * rho >= segs[j].length - 1e-9 || j >= corner + kSkipIntoSegments)) || (skip && to >= skip->to)) break;
          Path curve = carCurve(p, {segs[j].a + segs[j].dir * (into * rho), segs[j].heading}, rho, car.reverse, false);
          if (curve.waypoints.empty() || !pathFree(ws, curve)) continue;
          skip = Skip{from, to, j, std::move(curve)};
          found = true;
          break;
        }
    }
    // 3b. No curve reaches the path again within kSearchSkip of painting (a corner of a stair,
    //     from which every curve to what follows crosses the steps): a route searched over the car's
    //     own motions (searchCarRoute) to the next long segments, a turn radius into each.
    const double search_from = std::max(x, at - rho);
    // Where the car is, as it heads (not as the path arrives there: x may be a vertex the car
    // reached along the next segment), or the point ahead it drives to first.
    const Pose search_start = search_from <= x && out.path.segments() > 0 ? endPose(out.path) : startPose(search_from);
    if ((!skip || paintedLength(skip->from, skip->to) > kSearchSkip) && searched < kSmoothingSearchBudget) {
      std::size_t tries = 0;
      for (std::size_t j = corner; j < m && tries < kSkipSearches && searched < kSmoothingSearchBudget; ++j) {
        const double to = along[j] + rho;
        if (skip && to >= skip->to) break;
        if (segs[j].length < 2.0 * rho) continue;
        ++tries;
        const Pose target{segs[j].a + segs[j].dir * rho, segs[j].heading};
        Path route = searchCarRoute(ws, search_start, target, rho, car.reverse,
                                    std::min(kSkipSearchExpansions, kSmoothingSearchBudget - searched), &searched);
        if (route.segments() == 0) continue;
        skip = Skip{search_from, to, j, std::move(route), true};
        break;
      }
    }
    if (skip) {
      driveTo(skip->from);
      take(skip->curve, skip->to, paintedLength(skip->from, skip->to), skip->j - corner);  // segment j is entered, not skipped
      recordUndriven(skip->from, skip->to);
      out.searched += skip->searched;
      continue;
    }
    // 4. Stuck (a forward-only car that drove into a passage too narrow to turn in): go back to
    //    where it was some steps ago, drop what it drove since, and skip from there to a segment
    //    beyond this corner.
    for (std::size_t steps = 1; steps <= checkpoints.size() && !done; steps *= 2) {
      const Checkpoint& c = checkpoints[checkpoints.size() - steps];
      const Pose p = poseAt(c.x, false);
      for (std::size_t j = corner + 1; j < m && !done; ++j) {
        const Path curve = carCurve(p, {segs[j].a, segs[j].heading}, rho, car.reverse, false);
        if (curve.waypoints.empty() || !pathFree(ws, curve)) continue;
        out.path.waypoints.resize(c.waypoints);
        out.path.tool_on.resize(c.waypoints - 1);
        if (!out.path.bulge.empty()) out.path.bulge.resize(c.waypoints - 1);
        take(curve, along[j], paintedLength(c.x, along[j]), j - segmentAt(c.x));  // what it painted since is dropped too
        recordUndriven(c.x, along[j]);
        checkpoints.resize(checkpoints.size() - steps);
        done = true;
      }
    }
    if (done) continue;
    driveTo(at);
    out.stopped = true;
    out.cut_m += paintedLength(at, total);
    recordUndriven(at, total);
    out.skipped += m - corner;
    break;
  }
  // The car's rules, checked on what was built (the judges check again): a slip here is a bug,
  // and the plan fails with it rather than hand over a path the car cannot drive.
  checkDrivable(out.path, car, "car smoothing");
  char buf[200];
  if (out.stopped || out.skipped) {
    std::snprintf(buf, sizeof buf, "the car skips %zu segments%s", out.skipped,
                  out.stopped ? " and stops where no curve it can drive reaches further" : "");
    out.reason = buf;
  }
  return out;
}

}  // namespace coverbench
