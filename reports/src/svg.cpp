#include "coverbench/svg.hpp"

#include "coverbench/deposition.hpp"
#include "coverbench/escape.hpp"
#include "coverbench/input_error.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/free_region.hpp"
#include "coverbench/motion.hpp"

#include <nlohmann/json.hpp>
#include <openssl/evp.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace coverbench {
namespace {

constexpr double kMaxWidthPx = 1000.0;
constexpr double kMaxHeightPx = 700.0;
constexpr double kPadPx = 24.0;
constexpr double kLegendPx = 82.0;
/// The filled regions (F, the unpainted and the overlapped parts) are drawn simplified within this
/// many pixels: far below what a screen shows, and it drops the thousands of sub-pixel chords of
/// their arcs that made most of a gallery picture's bytes.
constexpr double kRegionDrawTolerancePx = 0.1;
/// The arcs of the regions (F, R, the swept band) are made as chords within this many pixels.
constexpr double kRegionArcTolerancePx = 0.05;

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

/// SVG path data written compactly and without loss against absolute coordinates at 0.01 px: the
/// first point and every 64th absolute, every other one as the step from the point before in
/// hundredths of a pixel, `h`/`v` where a step is level or plumb (the overlap layer's strips are
/// all such steps).
class PathData {
 public:
  void moveTo(double px, double py) { step(px, py, 'M'); start_x_ = x_; start_y_ = y_; }
  void lineTo(double px, double py) { step(px, py, 'L'); }
  void close() {
    d_ += 'z';
    x_ = start_x_;  // after a close the current point is the subpath's start
    y_ = start_y_;
  }
  const std::string& str() const { return d_; }

 private:
  /// n hundredths as the shortest decimal: 147 -> "1.47", -20 -> "-.2", 300 -> "3".
  static std::string hundredths(long long n) {
    const long long a = std::llabs(n), whole = a / 100, frac = a % 100;
    char buf[32];
    int len = std::snprintf(buf, sizeof buf, "%s%lld", n < 0 ? "-" : "", whole);
    if (frac != 0) {
      if (whole == 0) --len;  // "-.2", not "-0.2"
      len += std::snprintf(buf + len, sizeof buf - static_cast<std::size_t>(len), frac % 10 == 0 ? ".%lld" : ".%02lld",
                           frac % 10 == 0 ? frac / 10 : frac);
    }
    return std::string(buf, static_cast<std::size_t>(len));
  }
  /// Appends a command and its numbers; a number follows the one before directly when its minus
  /// sign separates them.
  void emit(char cmd, long long a) {
    d_ += cmd;
    d_ += hundredths(a);
  }
  void emit(char cmd, long long a, long long b) {
    emit(cmd, a);
    const std::string sb = hundredths(b);
    if (sb[0] != '-') d_ += ',';
    d_ += sb;
  }
  void step(double px, double py, char cmd) {
    const long long x = std::llround(px * 100.0), y = std::llround(py * 100.0);
    // Absolute now and then, so that a renderer's float sums of the steps never drift far.
    if (d_.empty() || ++steps_ % kAbsoluteEvery == 0)
      emit(cmd, x, y);
    else if (cmd == 'M')
      emit('m', x - x_, y - y_);
    else if (y == y_)
      emit('h', x - x_);
    else if (x == x_)
      emit('v', y - y_);
    else
      emit('l', x - x_, y - y_);
    x_ = x;
    y_ = y;
  }
  static constexpr long long kAbsoluteEvery = 64;
  std::string d_;
  long long x_ = 0, y_ = 0, start_x_ = 0, start_y_ = 0, steps_ = 0;
};

/// Maps wall metres to picture pixels (y up in the wall, down in SVG).
struct View {
  Box box;
  double k = 1.0;
  double top = 0.0;
  double px(double x) const { return kPadPx + (x - box.min_x) * k; }
  double py(double y) const { return top + (box.max_y - y) * k; }
  std::string pt(Point p) const { return fmt(px(p.x)) + "," + fmt(py(p.y)); }
  void moveTo(PathData& d, Point p) const { d.moveTo(px(p.x), py(p.y)); }
  void lineTo(PathData& d, Point p) const { d.lineTo(px(p.x), py(p.y)); }
  void ring(PathData& d, const Ring& r) const {
    for (std::size_t i = 0; i < r.size(); ++i) (i == 0 ? moveTo(d, r[i]) : lineTo(d, r[i]));
    if (!r.empty()) d.close();
  }
  std::string ringPath(const Ring& r) const {
    PathData d;
    ring(d, r);
    return d.str();
  }
  std::string regionPath(const std::vector<PolygonWithHoles>& polys) const {
    PathData d;
    for (const PolygonWithHoles& poly : polys) {
      ring(d, poly.outer);
      for (const Ring& hole : poly.holes) ring(d, hole);
    }
    return d.str();
  }
};

/// The run of tool-on moves from waypoint i to waypoint j of `path` drawn as a rectangle's swath
/// centre: its first point moved back by e along its first move, its last moved on by e along its
/// last (zero-length moves skipped); the moves between as they are.
std::string rectangleRun(const View& v, const Path& path, std::size_t i, std::size_t j, double e) {
  const std::vector<Point>& w = path.waypoints;
  std::size_t first = i, last = j;
  while (first < j && w[first] == w[first + 1]) ++first;
  while (last > i && w[last - 1] == w[last]) --last;
  PathData d;
  if (first >= last) {  // no move: the rectangle where it stands is not drawn
    v.moveTo(d, w[i]);
    return d.str();
  }
  const Point t0 = (w[first + 1] - w[first]) * (1.0 / distance(w[first], w[first + 1]));
  const Point t1 = (w[last] - w[last - 1]) * (1.0 / distance(w[last - 1], w[last]));
  v.moveTo(d, w[first] - t0 * e);
  for (std::size_t k = first + 1; k < last; ++k) v.lineTo(d, w[k]);
  v.lineTo(d, w[last] + t1 * e);
  return d.str();
}

/// A "nice" scale-bar length: 1, 2 or 5 times a power of ten, about a fifth of the width.
double niceLength(double span) {
  const double target = span / 5.0;
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= target) return m * p;
  return p;
}

/// The picture's frame: the wall's box, grown to hold every waypoint (a path that leaves the wall
/// stays in the picture), scaled to the picture's size.
View pictureView(const Wall& wall, const Path* path) {
  View v;
  v.box = boundingBox(wall.boundary);
  if (path)
    for (const Point& p : path->waypoints) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      v.box.min_x = std::min(v.box.min_x, p.x);
      v.box.max_x = std::max(v.box.max_x, p.x);
      v.box.min_y = std::min(v.box.min_y, p.y);
      v.box.max_y = std::max(v.box.max_y, p.y);
    }
  v.k = std::min(kMaxWidthPx / v.box.width(), kMaxHeightPx / v.box.height());
  v.top = kPadPx + 20.0;
  return v;
}

/// Integers as text, each zigzag-mapped (0, -1, 1, -2, ... to 0, 1, 2, 3, ...) and written in
/// groups of 5 bits, lowest first, one character each from A-Z a-z 0-9 - _: a group's character
/// has 32 added when more groups follow. About half the size of decimal JSON.
std::string varints(const std::vector<long long>& values) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
  std::string out;
  for (const long long value : values) {
    unsigned long long z = value >= 0 ? static_cast<unsigned long long>(value) << 1
                                      : (static_cast<unsigned long long>(-(value + 1)) << 1) | 1u;
    do {
      const unsigned group = static_cast<unsigned>(z & 31u);
      z >>= 5;
      out += kDigits[z != 0 ? group | 32u : group];
    } while (z != 0);
  }
  return out;
}

double pictureWidth(const View& v) { return std::max(v.box.width() * v.k + 2 * kPadPx, 740.0); }  // room for the legend
double pictureHeight(const View& v) { return v.top + v.box.height() * v.k + kPadPx + kLegendPx; }

}  // namespace

PictureSize pictureSize(const Wall& wall, const Path* path) {
  const View v = pictureView(wall, path);
  return {pictureWidth(v), pictureHeight(v)};
}

namespace {

/// The picture's legend and scale bar, below the wall.
std::string legendSvg(const SvgContent& c, const View& v) {
  std::ostringstream s;
  const double ly = v.top + v.box.height() * v.k + kPadPx + 8;
  const double bar = niceLength(v.box.width());
  s << "<g transform=\"translate(" << fmt(kPadPx) << "," << fmt(ly) << ")\">\n"
    << "<line x1=\"0\" y1=\"0\" x2=\"" << fmt(bar * v.k) << "\" y2=\"0\" stroke=\"#000\" stroke-width=\"2\"/>"
    << "<text x=\"0\" y=\"16\">" << shortNumber(bar) << " m</text>\n"
    << "<g transform=\"translate(0,34)\">"
    << "<rect width=\"14\" height=\"10\" fill=\"#cfe8cf\" stroke=\"#7fb27f\"/><text x=\"20\" y=\"10\">free region F</text>"
    << "<rect x=\"120\" width=\"14\" height=\"10\" fill=\"#9a9a9a\"/><text x=\"140\" y=\"10\">obstacle</text>"
    << "<line x1=\"220\" y1=\"5\" x2=\"250\" y2=\"5\" stroke=\"#1f4f9f\" stroke-width=\"2\"/>"
    << "<text x=\"256\" y=\"10\">tool on (band = tool width)</text>"
    << (c.vehicle.liftsTool()
            ? "<line x1=\"440\" y1=\"5\" x2=\"470\" y2=\"5\" stroke=\"#8e44ad\" stroke-width=\"2\" "
              "stroke-dasharray=\"1.5,3\" stroke-linecap=\"round\"/><text x=\"476\" y=\"10\">lifted (tool off)</text>"
            : "<line x1=\"440\" y1=\"5\" x2=\"470\" y2=\"5\" stroke=\"#e07b00\" stroke-width=\"2\" "
              "stroke-dasharray=\"5,3\"/><text x=\"476\" y=\"10\">transit (tool off)</text>")
    << "<circle cx=\"600\" cy=\"5\" r=\"5\" fill=\"#19a33a\"/><text x=\"610\" y=\"10\">start</text>"
    << "<rect x=\"655\" width=\"10\" height=\"10\" fill=\"#d02f2f\"/><text x=\"670\" y=\"10\">end</text>"
    << "</g>\n";
  if (c.reachable || c.overlap || (c.violating && !c.violating->empty())) {
    s << "<g transform=\"translate(0,52)\">"
      << "<rect width=\"14\" height=\"10\" fill=\"#e8383d\" fill-opacity=\"0.75\"/>"
      << "<text x=\"20\" y=\"10\">reachable, not covered</text>"
      << "<rect x=\"180\" width=\"14\" height=\"10\" fill=\"#9b3fd1\" fill-opacity=\"0.45\"/>";
    const double x = 360;
    if (c.three_passes)  // the shades stack: 3 passes is the first and second drawn over each other
      s << "<text x=\"200\" y=\"10\">2 passes</text>"
        << "<rect x=\"262\" width=\"14\" height=\"10\" fill=\"#9b3fd1\" fill-opacity=\"0.45\"/>"
        << "<rect x=\"262\" width=\"14\" height=\"10\" fill=\"#6a1b9a\" fill-opacity=\"0.55\"/><text x=\"282\" y=\"10\">3</text>"
        << "<rect x=\"300\" width=\"14\" height=\"10\" fill=\"#9b3fd1\" fill-opacity=\"0.45\"/>"
        << "<rect x=\"300\" width=\"14\" height=\"10\" fill=\"#6a1b9a\" fill-opacity=\"0.55\"/>"
        << "<rect x=\"300\" width=\"14\" height=\"10\" fill=\"#2e0854\" fill-opacity=\"0.65\"/><text x=\"320\" y=\"10\">4+</text>";
    else
      s << "<text x=\"200\" y=\"10\">covered twice or more</text>";
    if (c.violating && !c.violating->empty())
      s << "<line x1=\"" << fmt(x) << "\" y1=\"5\" x2=\"" << fmt(x + 30) << "\" y2=\"5\" stroke=\"#ff0000\" stroke-width=\"4\"/>"
        << "<text x=\"" << fmt(x + 36) << "\" y=\"10\">fails the exact check (" << c.violating->size() << " segments"
        << (c.violating->size() >= kMaxListedViolations ? " or more" : "") << ")</text>";
    s << "</g>\n";
  }
  s << "</g>\n";
  return s.str();
}

}  // namespace

std::string renderSvg(const SvgContent& c) {
  const Wall& wall = *c.wall;
  const View v = pictureView(wall, c.path);
  const Box wall_box = boundingBox(wall.boundary);
  const double w_px = pictureWidth(v);
  const double h_px = pictureHeight(v);
  const double tool_px = c.tool.tool_width * v.k;

  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"" << fmt(w_px) << "\" height=\"" << fmt(h_px)
    << "\" viewBox=\"0 0 " << fmt(w_px) << " " << fmt(h_px) << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  s << "<text x=\"" << fmt(kPadPx) << "\" y=\"" << fmt(kPadPx + 6) << "\" font-size=\"14\" font-weight=\"bold\">"
    << escapeHtml(c.title) << "</text>\n";
  s << "<path d=\"" << v.ringPath(wall.boundary)
    << "\" fill=\"#f3efe6\" stroke=\"#333333\" stroke-width=\"1.5\"/>\n";
  const double draw_tolerance = kRegionDrawTolerancePx / v.k;  // metres
  if (c.free) {
    s << "<path d=\"" << v.regionPath(simplifyRegion(*c.free, draw_tolerance)) << "\" fill=\"#cfe8cf\" fill-rule=\"evenodd\" stroke=\"#7fb27f\" stroke-width=\"0.8\"/>\n";
  }
  auto region = [&](const Region* r, const char* fill, const char* opacity) {
    if (!r || r->empty()) return;
    s << "<path d=\"" << v.regionPath(simplifyRegion(*r, draw_tolerance)) << "\" fill=\"" << fill << "\" fill-opacity=\"" << opacity
      << "\" fill-rule=\"evenodd\" stroke=\"none\"/>\n";
  };
  // Obstacles may reach beyond the wall: draw them clipped to the wall's bounding box.
  s << "<clipPath id=\"wallbox\"><rect x=\"" << fmt(v.px(wall_box.min_x)) << "\" y=\"" << fmt(v.py(wall_box.max_y))
    << "\" width=\"" << fmt(wall_box.width() * v.k) << "\" height=\"" << fmt(wall_box.height() * v.k) << "\"/></clipPath>\n"
    << "<g clip-path=\"url(#wallbox)\">\n";
  for (const Obstacle& o : wall.obstacles) {
    if (o.type == ObstacleType::Circle) {
      s << "<circle cx=\"" << fmt(v.px(o.center.x)) << "\" cy=\"" << fmt(v.py(o.center.y)) << "\" r=\""
        << fmt(o.radius * v.k) << "\" fill=\"#9a9a9a\" fill-opacity=\"0.85\" stroke=\"#444444\"/>\n";
    } else {
      s << "<path d=\"" << v.ringPath(o.polygon)
        << "\" fill=\"#9a9a9a\" fill-opacity=\"0.85\" stroke=\"#444444\"/>\n";
    }
    if (!o.label.empty()) {
      const Point at = o.type == ObstacleType::Circle ? o.center : [&] {
        const Box b = boundingBox(o.polygon);
        return Point{(b.min_x + b.max_x) / 2, (b.min_y + b.max_y) / 2};
      }();
      s << "<text x=\"" << fmt(v.px(at.x)) << "\" y=\"" << fmt(v.py(at.y) + 4)
        << "\" text-anchor=\"middle\" fill=\"#ffffff\" font-size=\"11\">" << escapeHtml(o.label) << "</text>\n";
    }
  }
  s << "</g>\n";
  if (c.path && !c.path->waypoints.empty()) {
    const Path& path = *c.path;
    // Runs of consecutive segments with the same tool state become one path element each (each
    // run's translucent swath is its own, so where runs cross the swaths darken).
    std::string on_runs, off_runs, band_runs;
    for (std::size_t i = 0; i < path.tool_on.size();) {
      PathData d;
      v.moveTo(d, path.waypoints[i]);
      std::size_t j = i;
      for (; j < path.tool_on.size() && path.tool_on[j] == path.tool_on[i]; ++j) {
        if (path.bulgeOf(j) == 0.0) {
          v.lineTo(d, path.waypoints[j + 1]);
          continue;
        }
        // An arc (a car's, a boundary's) is drawn as chords within 1 mm of it.
        Path arc;
        arc.moveTo(path.waypoints[j], true);
        arc.arcTo(path.waypoints[j + 1], path.bulgeOf(j), true);
        const Path chords = chordalPath(arc, 1e-3);
        for (std::size_t k = 1; k < chords.waypoints.size(); ++k) v.lineTo(d, chords.waypoints[k]);
      }
      std::string& runs = path.tool_on[i] ? on_runs : off_runs;
      runs += "<path d=\"";
      runs += d.str();
      runs += "\"/>\n";
      // A rectangle's swath reaches d / 2 before a run's first waypoint and past its last (along
      // its first and last moves); it has straight moves only.
      if (path.tool_on[i] && c.tool.isRectangle()) band_runs += "<path d=\"" + rectangleRun(v, path, i, j, c.tool.halfDepth()) + "\"/>\n";
      i = j;
    }
    // The painted runs are written once and drawn twice (the tool's swath, then its centre line).
    s << "<defs><g id=\"paint\">\n" << on_runs << "</g>";
    if (c.tool.isRectangle()) s << "<g id=\"band\">\n" << band_runs << "</g>";
    s << "</defs>\n";
    const char* band = c.tool.isRectangle() ? "#band" : "#paint";
    // A line's and a rectangle's bands have square ends (their rectangles); their turns are drawn
    // as round joins.
    const char* cap = c.tool.turnsWithHeading() ? "butt" : "round";
    s << "<use xlink:href=\"" << band << "\" fill=\"none\" stroke=\"#2f6fd0\" stroke-opacity=\"0.18\" stroke-width=\"" << fmt(tool_px)
      << "\" stroke-linecap=\"" << cap << "\" stroke-linejoin=\"round\"/>\n";
    // R not swept: R in red under a mask that hides what the tool's band covers. The band is the
    // painted runs stroked at the tool's width with round caps and joins: S itself (the union of
    // the tool-on capsules), drawn by the viewer, so no polygon union of the path is computed.
    if (c.reachable && !c.reachable->empty()) {
      s << "<mask id=\"unswept\" maskUnits=\"userSpaceOnUse\" x=\"0\" y=\"0\" width=\"" << fmt(w_px) << "\" height=\""
        << fmt(h_px) << "\"><rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/><use xlink:href=\"" << band << "\" fill=\"none\" "
        << "stroke=\"#000000\" stroke-width=\"" << fmt(tool_px) << "\" stroke-linecap=\"" << cap << "\" stroke-linejoin=\"round\"/></mask>\n";
      s << "<path d=\"" << v.regionPath(simplifyRegion(*c.reachable, draw_tolerance))
        << "\" fill=\"#e8383d\" fill-opacity=\"0.75\" fill-rule=\"evenodd\" stroke=\"none\" mask=\"url(#unswept)\"/>\n";
    }
    region(c.overlap, "#9b3fd1", "0.45");
    region(c.three_passes, "#6a1b9a", "0.55");
    region(c.four_passes, "#2e0854", "0.65");
    s << "<use xlink:href=\"#paint\" fill=\"none\" stroke=\"#1f4f9f\" stroke-width=\"" << fmt(std::clamp(tool_px * 0.12, 0.5, 2.0))
      << "\" stroke-linejoin=\"round\"/>\n";
    if (c.vehicle.liftsTool())
      s << "<g class=\"lifted\" fill=\"none\" stroke=\"#8e44ad\" stroke-width=\"1.6\" stroke-dasharray=\"1.5,3\" "
           "stroke-linecap=\"round\">\n" << off_runs << "</g>\n";
    else
      s << "<g fill=\"none\" stroke=\"#e07b00\" stroke-width=\"1.6\" stroke-dasharray=\"5,3\">\n" << off_runs << "</g>\n";
    if (c.violating && !c.violating->empty()) {
      std::string d;
      for (std::size_t i : *c.violating)
        if (i + 1 < path.waypoints.size()) d += "M" + v.pt(path.waypoints[i]) + "L" + v.pt(path.waypoints[i + 1]);
        else if (i < path.waypoints.size()) d += "M" + v.pt(path.waypoints[i]) + "l0.01,0";
      s << "<path class=\"violation\" d=\"" << d
        << "\" fill=\"none\" stroke=\"#ff0000\" stroke-width=\"4\" stroke-linecap=\"round\" stroke-opacity=\"0.9\"/>\n";
    }
    const Point a = path.waypoints.front(), b = path.waypoints.back();
    s << "<circle cx=\"" << fmt(v.px(a.x)) << "\" cy=\"" << fmt(v.py(a.y))
      << "\" r=\"6\" fill=\"#19a33a\" stroke=\"#ffffff\" stroke-width=\"1.5\"/>\n";
    s << "<rect x=\"" << fmt(v.px(b.x) - 5) << "\" y=\"" << fmt(v.py(b.y) - 5)
      << "\" width=\"10\" height=\"10\" fill=\"#d02f2f\" stroke=\"#ffffff\" stroke-width=\"1.5\"/>\n";
  }
  s << legendSvg(c, v);
  s << "</svg>\n";
  return s.str();
}

/// The picture of a path; with its coverage layer when it can be scored.
std::string pathPicture(const Wall& wall, const ToolParams& tool, const VehicleModel& vehicle, const Path& path,
                        const std::string& title, bool coverage_layer, double overlap_strips,
                        std::size_t first_judged_segment, bool pass_counts) {
  // The regions' arcs as chords within a fraction of the picture's pixel (finer changes no pixel).
  const double arc_tolerance = std::max(kArcTolerance, kRegionArcTolerancePx / pictureView(wall, &path).k);
  const Region free = freeRegion(wall, tool, kFreeSpaceMargin, arc_tolerance);
  SvgContent content;
  content.wall = &wall;
  content.tool = tool;
  content.vehicle = vehicle;
  content.free = &free;
  content.path = &path;
  content.title = title;
  if (!coverage_layer) return renderSvg(content);
  const Region reachable = reachableRegion(wall, tool, arc_tolerance);
  Validity validity = checkValidity(wall, tool, path, vehicle);
  std::erase_if(validity.violating, [&](std::size_t i) { return i < first_judged_segment; });
  content.violating = &validity.violating;
  // Draw the overlap with strips no finer than the measure's and at most `overlap_strips` over the wall.
  const Box box = boundingBox(wall.boundary);
  const double strip = std::max(tool.radius() / 10.0, box.height() / overlap_strips);
  const Region overlap = passRegion(path, tool, strip, 2);
  content.reachable = &reachable;
  content.overlap = &overlap;
  Region three, four;
  if (pass_counts) {
    three = passRegion(path, tool, strip, 3);
    four = passRegion(path, tool, strip, 4);
    content.three_passes = &three;
    content.four_passes = &four;
  }
  return renderSvg(content);
}

namespace {

/// The coat's colour for a thickness `ratio` of the mean, in steps of a tenth: blues below 0.9
/// (darker thinner), one green within 10 %, oranges to dark red above 1.1 (2 and more darkest).
std::string coatColour(double ratio) {
  auto mix = [](const int a[3], const int b[3], double t) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(std::lround(a[0] + (b[0] - a[0]) * t)),
                  static_cast<int>(std::lround(a[1] + (b[1] - a[1]) * t)), static_cast<int>(std::lround(a[2] + (b[2] - a[2]) * t)));
    return std::string(buf);
  };
  static const int kBare[3] = {8, 48, 107}, kThin[3] = {158, 202, 225}, kThick[3] = {253, 174, 107}, kHeavy[3] = {127, 0, 0};
  if (ratio >= 0.9 && ratio <= 1.1) return "#41ab5d";
  if (ratio < 0.9) return mix(kBare, kThin, std::floor(std::max(ratio, 0.0) * 10.0) / 9.0);
  return mix(kThick, kHeavy, std::min(std::floor((ratio - 1.1) * 10.0), 9.0) / 9.0);
}

}  // namespace

std::string coatPicture(const Wall& wall, const ToolParams& tool, const Path& path, const MotionLimits& limits,
                        const VehicleModel& vehicle, const std::string& title, bool as_image) {
  if (!tool.profile.set()) throw InputError("coat picture", "tool.profile", "the coat's picture needs the tool's flux profile");
  return coatPicture(wall, tool, coat(wall, tool, path, tool.profile, limits, vehicle, coatBlockCells(wall, tool)), title, as_image);
}

std::size_t coatBlockCells(const Wall& wall, const ToolParams& tool) {
  const double k = pictureView(wall, nullptr).k, cell = depositionCell(tool, tool.profile);
  return cell > 0.0 ? std::max<std::size_t>(1, static_cast<std::size_t>(3.0 / (k * cell))) : 1;
}

namespace {

/// The colours of the coat's blocks, each its mean's ratio to `reference` (R's mean or the target;
/// "" where no sample is in R), row by row from the bottom; none for a reference of 0.
std::vector<std::string> blockColours(const CoatBlocks& b, double reference) {
  std::vector<std::string> colour(reference > 0.0 ? b.mean.size() : 0);
  for (std::size_t k = 0; k < colour.size(); ++k)
    if (!std::isnan(b.mean[k])) colour[k] = coatColour(b.mean[k] / reference);
  return colour;
}

/// The blocks as a PNG of one pixel a block (8-bit RGBA, transparent outside R, the top row
/// first; libpng's simplified writer), base-64 encoded for a data: address.
std::string coatPng(const CoatBlocks& b, const std::vector<std::string>& colour) {
  std::vector<unsigned char> rgba;
  rgba.reserve(4 * b.bx * b.by);
  for (std::size_t row = b.by; row-- > 0;)
    for (std::size_t i = 0; i < b.bx; ++i) {
      const std::string& c = colour[row * b.bx + i];
      const unsigned long rgb = c.empty() ? 0 : std::stoul(c.substr(1), nullptr, 16);
      for (const unsigned long v : {(rgb >> 16) & 0xff, (rgb >> 8) & 0xff, rgb & 0xff, c.empty() ? 0ul : 255ul})
        rgba.push_back(static_cast<unsigned char>(v));
    }
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(b.bx);
  image.height = static_cast<png_uint_32>(b.by);
  image.format = PNG_FORMAT_RGBA;
  png_alloc_size_t size = 0;
  std::vector<unsigned char> png;
  if (png_image_write_get_memory_size(image, size, 0, rgba.data(), 0, nullptr)) {
    png.resize(size);
    if (!png_image_write_to_memory(&image, png.data(), &size, 0, rgba.data(), 0, nullptr)) png.clear();
    png.resize(size);
  }
  if (png.empty()) throw std::runtime_error(std::string("coat picture: libpng could not write the image: ") + image.message);
  std::string text(4 * ((png.size() + 2) / 3) + 1, '\0');
  const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(text.data()), png.data(), static_cast<int>(png.size()));
  text.resize(static_cast<std::size_t>(n));
  return text;
}

}  // namespace

std::string coatPicture(const Wall& wall, const ToolParams& tool, const Coat& coat, const std::string& title,
                        bool as_image) {
  if (!tool.profile.set()) throw InputError("coat picture", "tool.profile", "the coat's picture needs the tool's flux profile");
  const double target_um = tool.profile.target;  // 0: none, the blocks' ratios are to R's mean
  const Deposition& d = coat.stats;
  const CoatBlocks& b = coat.blocks;
  const View v = pictureView(wall, nullptr);
  const double reference_um = target_um > 0.0 ? target_um : d.mean_um;
  const double w_px = pictureWidth(v), h_px = pictureHeight(v), reference = reference_um * 1e-6;
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << fmt(w_px) << "\" height=\"" << fmt(h_px) << "\" viewBox=\"0 0 "
    << fmt(w_px) << " " << fmt(h_px) << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n"
    << "<text x=\"" << fmt(kPadPx) << "\" y=\"" << fmt(kPadPx + 6) << "\" font-size=\"14\" font-weight=\"bold\">" << escapeHtml(title)
    << "</text>\n<path d=\"" << v.ringPath(wall.boundary) << "\" fill=\"#f3efe6\" stroke=\"none\"/>\n";
  // Blocks of cells about 3 px wide, each the mean of its samples in R, coloured by its ratio to
  // R's mean (or to the target, if the profile has one): runs of one colour along a row as one rectangle each, or (as_image) one PNG pixel
  // a block, drawn unsmoothed.
  const std::vector<std::string> colour = blockColours(b, d.mean_um > 0.0 ? reference : 0.0);
  const std::size_t rows = colour.empty() ? 0 : b.by;
  s << "<g class=\"coat\" stroke=\"none\">\n";
  if (as_image && rows > 0) {
    s << "<image x=\"" << fmt(v.px(b.x0)) << "\" y=\"" << fmt(v.py(b.y0 + static_cast<double>(b.by) * b.side)) << "\" width=\""
      << fmt(static_cast<double>(b.bx) * b.side * v.k) << "\" height=\"" << fmt(static_cast<double>(b.by) * b.side * v.k)
      << "\" preserveAspectRatio=\"none\" style=\"image-rendering:pixelated\" href=\"data:image/png;base64," << coatPng(b, colour)
      << "\"/>\n";
  }
  for (std::size_t j = 0; !as_image && j < rows; ++j) {
    std::string run_colour;
    std::size_t run_start = 0;
    auto flush = [&](std::size_t end) {
      if (run_colour.empty()) return;
      s << "<rect x=\"" << fmt(v.px(b.x0 + static_cast<double>(run_start) * b.side)) << "\" y=\""
        << fmt(v.py(b.y0 + static_cast<double>(j + 1) * b.side)) << "\" width=\"" << fmt(static_cast<double>(end - run_start) * b.side * v.k)
        << "\" height=\"" << fmt(b.side * v.k) << "\" fill=\"" << run_colour << "\"/>\n";
      run_colour.clear();
    };
    for (std::size_t i = 0; i < b.bx; ++i) {
      const std::string& c = colour[j * b.bx + i];
      if (c != run_colour) {
        flush(i);
        run_colour = c;
        run_start = i;
      }
    }
    flush(b.bx);
  }
  s << "</g>\n<path d=\"" << v.ringPath(wall.boundary) << "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1.5\"/>\n";
  for (const Obstacle& o : wall.obstacles) {
    if (o.type == ObstacleType::Circle)
      s << "<circle cx=\"" << fmt(v.px(o.center.x)) << "\" cy=\"" << fmt(v.py(o.center.y)) << "\" r=\"" << fmt(o.radius * v.k)
        << "\" fill=\"#9a9a9a\" stroke=\"#444444\"/>\n";
    else
      s << "<path d=\"" << v.ringPath(o.polygon) << "\" fill=\"#9a9a9a\" stroke=\"#444444\"/>\n";
  }
  // The colour scale in micrometres, 0 to twice the mean (or the target), and what the metrics say.
  const double ly = v.top + v.box.height() * v.k + kPadPx + 8, bar = 400.0;
  s << "<g class=\"coat-scale\" transform=\"translate(" << fmt(kPadPx) << "," << fmt(ly) << ")\">\n";
  for (int k = 0; k < 20; ++k)
    s << "<rect x=\"" << fmt(bar * k / 20.0) << "\" width=\"" << fmt(bar / 20.0 + 0.5) << "\" height=\"12\" fill=\""
      << coatColour((k + 0.5) / 10.0) << "\"/>";
  s << "\n";
  for (double r : {0.0, 0.9, 1.1, 2.0})
    s << "<line x1=\"" << fmt(bar * r / 2.0) << "\" y1=\"12\" x2=\"" << fmt(bar * r / 2.0) << "\" y2=\"17\" stroke=\"#000\"/>"
      << "<text x=\"" << fmt(bar * r / 2.0) << "\" y=\"29\" text-anchor=\"middle\">" << shortNumber(std::round(r * reference_um * 10.0) / 10.0)
      << (r == 2.0 ? "+" : "") << "</text>";
  s << "<text x=\"" << fmt(bar + 12) << "\" y=\"10\">coat thickness, \u00b5m (green: within 10 % of the "
    << (target_um > 0.0 ? "target, " + shortNumber(target_um) + " \u00b5m" : std::string("mean")) << ")</text>\n"
    // Two lines, so that the figures fit the picture's least width (740 px).
    << "<text x=\"0\" y=\"50\">" << escapeHtml(tool.profile.describe(tool.tool_width)) << ":</text>\n"
    << "<text x=\"0\" y=\"66\">mean " << shortNumber(std::round(d.mean_um * 100.0) / 100.0)
    << " \u00b5m, CV " << fmt(d.cv) << "; within 10 %: " << fmt(100.0 * d.even_share) << " %, thinner: " << fmt(100.0 * d.thin_share)
    << " %, thicker: " << fmt(100.0 * d.thick_share) << " % of R</text>\n</g>\n</svg>\n";
  return s.str();
}

std::string playbackScript(const std::string& id, const Wall& wall, const ToolParams& tool, const VehicleModel& vehicle,
                           const Path& path, const MotionLimits& limits) {
  const View v = pictureView(wall, &path);
  const Timeline timeline = coverbench::timeline(path, limits, vehicle);
  nlohmann::ordered_json d;
  d["id"] = id;
  d["size"] = {pictureWidth(v), pictureHeight(v)};
  d["tool_px"] = tool.tool_width * v.k;
  d["lifts"] = vehicle.liftsTool();
  d["model"] = limits.describe();
  // Integers, each the step from the one before: tenths of a pixel (a tenth of what a screen
  // shows), hundredths of a second.
  std::vector<long long> x, y, t;
  long long px = 0, py = 0, pt = 0;
  for (std::size_t i = 0; i < path.waypoints.size(); ++i) {
    const long long qx = std::llround(v.px(path.waypoints[i].x) * 10.0), qy = std::llround(v.py(path.waypoints[i].y) * 10.0);
    const long long qt = std::llround(timeline.arrive_s[i] * 100.0);
    x.push_back(qx - px);
    y.push_back(qy - py);
    t.push_back(qt - pt);
    px = qx, py = qy, pt = qt;
  }
  d["x"] = varints(x);
  d["y"] = varints(y);
  d["t"] = varints(t);
  d["end_cs"] = std::llround(timeline.end_s * 100.0);
  std::string on(path.segments(), '0');
  nlohmann::json waits = nlohmann::json::array(), arcs = nlohmann::json::array();
  for (std::size_t i = 0; i < path.segments(); ++i) {
    if (path.tool_on[i]) on[i] = '1';
    if (timeline.wait_s[i] > 0.0) waits.push_back({i, std::llround(timeline.wait_s[i] * 100.0)});
    // The picture's y points down: a counter-clockwise arc on the wall turns clockwise in it.
    if (path.bulgeOf(i) != 0.0) arcs.push_back({i, -std::llround(path.bulgeOf(i) * 1e6)});
  }
  d["on"] = on;
  d["waits"] = waits;
  d["arcs"] = arcs;
  // Segments that fail the validity check (a tool-on move across a window, a move off the wall):
  // the player marks them over its paint at every moment.
  nlohmann::json bad = nlohmann::json::array();
  for (const std::size_t i : checkValidity(wall, tool, path, vehicle).violating) bad.push_back(i);
  d["bad"] = bad;
  return "coverbenchPlayback(" + d.dump() + ");\n";
}

}  // namespace coverbench
