#pragma once
// The exact kernel of the judge's two CGAL units (exact_validity.cpp, exact_coverage.cpp); only
// they include this header.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include "coverbench/geometry.hpp"

namespace coverbench::judge {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using P2 = K::Point_2;
using V2 = K::Vector_2;
using S2 = K::Segment_2;

/// A point of the wall or the path as the exact rational its doubles are.
inline P2 exactPoint(Point p) { return P2(p.x, p.y); }

}  // namespace coverbench::judge
