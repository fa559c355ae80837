// The car's curves (coverbench/car.hpp, docs/vehicles.md): the six Dubins words in closed form,
// OMPL's Reeds-Shepp curve driven out as lines and arcs, and the car's rules on a path (headings
// that join, cusps, arcs no tighter than its turn radius).
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "coverbench/car.hpp"

namespace coverbench {
namespace {

/// The turn from heading `from` to heading `to` (wrapAngle).
double angleBetween(double from, double to) { return wrapAngle(to - from); }

/// The headings segment k of `path` starts and ends with: its chord's, turned back and on by half
/// an arc's angle.
std::pair<double, double> headings(const Path& path, std::size_t k) {
  const Point d = path.waypoints[k + 1] - path.waypoints[k];
  const double chord = std::atan2(d.y, d.x), bulge = path.bulgeOf(k);
  const double half = bulge == 0.0 ? 0.0 : 2.0 * std::atan(bulge);
  return {chord - half, chord + half};
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

}  // namespace coverbench
