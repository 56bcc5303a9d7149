// reference/Torus.h: the reference's torus (AnalyticKind::Torus), around the model's Z axis
// through the origin: the ring of radius `major` in the XY plane swept by a circle of radius
// `minor`.
#pragma once

#include <lantern/Scene.h>

#include <glm/vec3.hpp>

namespace lantern::ref {

/// The ray o + t d's parameters t where it meets the torus, ascending (up to 4); how many.
int torusRoots(double major, double minor, const glm::dvec3& o, const glm::dvec3& d, double ts[4]);

/// The outward normal at a point p on the torus, up to length.
glm::dvec3 torusNormal(double major, const glm::dvec3& p);

/// The torus as triangles: `segments` around the ring, `sides` around the tube, with exact
/// normals, counter-clockwise seen from outside.
Primitive makeTorus(double major, double minor, int segments, int sides);

} // namespace lantern::ref
