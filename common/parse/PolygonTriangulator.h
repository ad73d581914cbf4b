// Splits a planar polygon, convex or concave, into triangles by ear clipping (Eberly,
// "Triangulation by Ear Clipping", 2002) in the plane it is projected onto along the dominant axis
// of its Newell normal. Used for NFF polygons (gears-s2.nff has concave 144-gons) and OBJ faces.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "math/Vec.h"

namespace prism {

// Newell's normal of a polygon: perpendicular to its best-fit plane, pointing the way its vertices
// wind counter-clockwise, with length twice the polygon's area. Exact for planar polygons, robust
// for nearly planar and concave ones, zero when the polygon has no area.
Vec3 newellNormal(std::span<const Vec3> polygon);

// Triangulates a simple polygon (no self-intersections; non-planar ones are split as their
// projection is). Returns indices into polygon, three per triangle, each triangle wound like the
// polygon so its normal agrees with newellNormal(). A polygon with n distinct vertices yields
// n - 2 triangles, none of them flat (vertices where the outline goes straight on are kept, so
// no T-junctions appear); repeated vertices and edges that double back are dropped (fewer
// triangles, same area); a polygon without area yields none. Always terminates: when rounding or
// a self-intersecting input leaves no clean ear, the most convex vertex is clipped.
std::vector<uint32_t> triangulatePolygon(std::span<const Vec3> polygon);

}  // namespace prism
