#pragma once
// The raster the car's sweep measures what a path paints on (PaintGrid), and the chords it draws
// a path's arcs with. Private to vehicles/src.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "coverbench/car_sweep.hpp"

namespace coverbench::vehicle_detail {

/// Calls chord(p, q) for each piece of segment i of the path: the segment when it is straight,
/// else chords within `tolerance` of its arc.
template <class Chord>
void forEachChordOf(const Path& path, std::size_t i, double tolerance, Chord&& chord) {
  const Point a = path.waypoints[i], b = path.waypoints[i + 1];
  Point from = a;
  if (effectiveBulge(a, b, path.bulgeOf(i)) != 0.0) {
    const ArcGeometry arc = arcGeometry(a, b, path.bulgeOf(i));
    const double step = 2.0 * std::acos(std::max(-1.0, 1.0 - tolerance / arc.radius));
    const int k = std::max(1, static_cast<int>(std::ceil(std::fabs(arc.sweep) / step)));
    const double start = std::atan2(a.y - arc.centre.y, a.x - arc.centre.x);
    for (int j = 1; j < k; ++j) {
      const double t = start + arc.sweep * j / k;
      const Point to = arc.centre + Point{std::cos(t), std::sin(t)} * arc.radius;
      chord(from, to);
      from = to;
    }
  }
  chord(from, b);
}

/// Calls chord(p, q) for each piece of what the path paints from segment `first` on: its straight
/// segments, and chords within `tolerance` of its arcs.
template <class Chord>
void forEachChord(const Path& path, double tolerance, std::size_t first, bool painted_only, Chord&& chord) {
  for (std::size_t i = first; i < path.segments(); ++i)
    if (!painted_only || path.tool_on[i]) forEachChordOf(path, i, tolerance, chord);
}

/// forEachChord over the painted segments only.
template <class Chord>
void forEachPaintedChord(const Path& path, double tolerance, std::size_t first, Chord&& chord) {
  forEachChord(path, tolerance, first, true, chord);
}

/// A raster of F and of its painted reach (what lies within a tool radius of F), and what a path
/// paints of it: what the fill rounds look for passes in. Cells of `h` metres; a cell is in F, or
/// painted, when its centre is, and in the reach when its centre lies within a tool radius of the
/// centre of a cell of F. Same path, same cells.
class PaintGrid {
 public:
  PaintGrid(const Workspace& ws, double h);
  /// Marks what `path` paints (its arcs drawn with chords within a tenth of a cell), and only that.
  void paint(const Path& path);
  /// Marks what `path` paints from segment `first` on, besides what is marked (a path painted
  /// before, which this one goes on from: what a path paints is the union of its segments').
  void paintMore(const Path& path, std::size_t first);
  /// Marks what segment i of `path` paints, besides what is marked.
  void paintSegment(const Path& path, std::size_t i);
  /// The cells of the reach left unpainted, and all cells of the reach, in the capsule of the
  /// tool's radius round p-q.
  std::pair<std::size_t, std::size_t> openIn(Point p, Point q) const;
  /// Whether at least `share` of the reach's cells that segment i of `path` would paint are
  /// unpainted (counted chord by chord, as paintMore draws it), and there are some.
  bool openAlong(const Path& path, std::size_t i, double share) const;
  /// The reach's area, counted in cells (m²).
  double reach() const;
  /// The painted area, counted in cells of the reach (m²).
  double painted() const;
  /// Passes through each piece of the reach left unpainted (4-connected cells) of at least
  /// `min_area`: lines along the piece's long axis (the principal axis of its cells; across it when
  /// that gives no pass), a spacing apart and centred on it, as many as its width across them
  /// needs (a piece one line wide whose middle line gives none: that line moved across); each
  /// stretch of a line whose points lie in F and within half a tool radius of the piece is a pass,
  /// kept when it runs at least `min_pass` and the workspace finds it free (its ends moved in by up
  /// to 3 cells otherwise), and for a forward-only car when it leaves room to turn out of both
  /// ends (leaveRoomToTurn).
  std::vector<CarRow> passes(Workspace& ws, double spacing, double min_area, double rho, bool forward_only, double min_pass);

 private:
  static constexpr std::uint8_t kReach = 1, kFree = 2, kPainted = 4;
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i); }
  Point centre(std::size_t c) const {
    return origin_ + Point{(static_cast<double>(c % static_cast<std::size_t>(nx_)) + 0.5) * h_,
                           (static_cast<double>(c / static_cast<std::size_t>(nx_)) + 0.5) * h_};
  }
  bool open(std::size_t c) const { return (cells_[c] & kReach) && !(cells_[c] & kPainted); }
  bool cellOf(Point p, int& i, int& j) const {
    i = static_cast<int>(std::floor((p.x - origin_.x) / h_));
    j = static_cast<int>(std::floor((p.y - origin_.y) / h_));
    return i >= 0 && i < nx_ && j >= 0 && j < ny_;
  }
  bool inFree(Point p) const {
    int i = 0, j = 0;
    return cellOf(p, i, j) && (cells_[index(i, j)] & kFree);
  }
  /// Whether a cell of piece `id` lies within `near` cells of p's.
  bool nearPiece(Point p, const std::vector<int>& piece, int id, int near) const;
  /// Sets `bit` on the cells of row j whose centres lie in [x0, x1].
  void mark(int j, double x0, double x1, std::uint8_t bit);
  /// Paints the capsule of the tool's radius round the segment p-q.
  void capsule(Point p, Point q);
  /// The capsule of the tool's radius round the segment p-q, a row of cells at a time:
  /// `row(j, lo, hi)` with the span of the two end disks and the rectangle between them (their
  /// union is convex).
  template <class Row>
  void capsuleRows(Point p, Point q, Row&& row) const;

  double h_, r_;
  Point origin_;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint8_t> cells_;
};

}  // namespace coverbench::vehicle_detail
