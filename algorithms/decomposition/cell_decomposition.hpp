#pragma once
/// Exact vertical cell decompositions of a polygon with holes (seed 002, Choset 2000), shared by
/// the `trapezoidal` and `boustrophedon` planners.
///
/// The sweep runs along x. Between two consecutive distinct vertex x coordinates (a slab) no
/// vertex lies strictly inside, so the polygon's cross-section there is a fixed list of intervals,
/// each bounded below by one floor edge and above by one ceiling edge. Cells are runs of such slab
/// intervals in consecutive slabs:
/// - trapezoidal: an interval continues into the next slab while its floor and ceiling both
///   continue, which is a trapezoid between the vertical lines through the corners. A floor or
///   ceiling continues through a vertex where it turns by less than kCornerTurnDeg: such vertices
///   are the chords of an arc of F (round offsets of obstacle corners and circles), not corners of
///   the wall or obstacles as given, and a cell per chord would only add passes;
/// - boustrophedon: an interval continues while it touches exactly one interval on each side,
///   i.e. the cell is split only at critical points where the connectivity of the sweep line
///   changes.
/// Slabs have positive width, so vertices sharing an x coordinate (in one ring or across rings)
/// never give zero-width cells; intervals of zero height are never formed.

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "coverbench/geometry.hpp"

namespace coverbench::decomposition {

enum class Kind { Trapezoidal, Boustrophedon };

/// The smallest turn (degrees) at which a vertex of the region counts as a corner for the
/// trapezoidal decomposition. The free region's arcs are drawn with chords turning by at most
/// about 28 degrees (2 mm tolerance on the smallest radius, r + c = 0.07 m for the default tool);
/// the corners of walls and obstacles as given turn by 45 degrees or more in every generated family.
inline constexpr double kCornerTurnDeg = 30.0;

/// A polygon edge that is not vertical, as its left and right end points.
struct Edge {
  Point left, right;
  /// y on the edge's line at x (x clamped to the edge's extent).
  double yAt(double x) const;
};

/// One slab interval of a cell: x in [x0, x1], y between the floor and the ceiling edge.
struct Slice {
  double x0 = 0.0, x1 = 0.0;
  Edge floor, ceiling;
  double area() const;
};

/// The vertical segment a cell occupies at one x (the union of both slices at a slice boundary).
struct Span {
  double bottom = 0.0, top = 0.0;
};

/// A cell: x-monotone (every vertical line meets it in one segment), its slices in increasing x
/// and touching end to end.
struct Cell {
  std::vector<Slice> slices;
  double minX() const { return slices.front().x0; }
  double maxX() const { return slices.back().x1; }
  double area() const;
  Span spanAt(double x) const;
  /// The middle of its span halfway between its ends.
  Point centre() const;
  /// The floor (or ceiling) of the cell from x = a to x = b (either order) as a polyline on the
  /// polygon's boundary, vertical steps included; starts at spanAt(a) and ends at spanAt(b)'s
  /// bottom (or top).
  std::vector<Point> boundaryWalk(double a, double b, bool ceiling) const;
};

/// Two cells sharing a piece of a vertical line: x, and the shared y range. `x` is the left
/// cell's right end and the right cell's left end, or, after slivers were joined (decompose), a
/// boundary between two slices of either.
struct Contact {
  std::size_t left = 0, right = 0;  ///< cell indices, `left` on the smaller-x side
  double x = 0.0, y0 = 0.0, y1 = 0.0;
};

struct Decomposition {
  std::vector<Cell> cells;  ///< in sweep order (by their left end)
  std::vector<Contact> contacts;  ///< every pair of touching cells once per shared segment
  std::size_t slabs = 0;
};

/// Decomposes one polygon with holes (outer ring counter-clockwise, holes clockwise, as regions
/// come from region_ops). Contacts shorter than `min_contact` metres are not recorded.
///
/// Events closer than `merge_width` along the sweep count as one: a cell narrower than
/// `merge_width` (a sliver between two such events) joins a cell it continues, one that ends
/// where it begins or begins where it ends. Where a wall has several corners on one vertical line
/// (a hole's right side above the next hole's left side), the region drawn inside the wall has
/// them up to twice its depth apart, and each pair would make a sliver cell. A joined cell is
/// still x-monotone, but its floor or ceiling may step where another cell begins beside it, so a
/// contact may lie inside its left or right cell's x range (at a slice boundary of each) rather
/// than at its end. 0 joins nothing.
Decomposition decompose(const PolygonWithHoles& polygon, Kind kind, double min_contact = 1e-9,
                        double merge_width = 0.0);

/// The cells of every part of `region` that `keep` admits (every part, when `keep` is empty), as
/// one decomposition (cells and contacts numbered across the parts); merge_width as for decompose.
Decomposition decomposeParts(const Region& region, Kind kind, double merge_width,
                             const std::function<bool(const PolygonWithHoles&)>& keep = {});

}  // namespace coverbench::decomposition
