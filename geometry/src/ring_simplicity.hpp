// The CGAL part of ringIsSimple (geometry.cpp), behind a plain header.
#pragma once

#include "coverbench/geometry.hpp"

namespace coverbench::detail {

/// True when no two edges of the ring meet except consecutive edges at their shared vertex
/// (CGAL's is_simple_2). The ring has at least 3 vertices, no two consecutive ones equal.
bool edgesMeetOnlyAtSharedVertices(const Ring& ring);

}  // namespace coverbench::detail
