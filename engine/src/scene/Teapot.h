// Teapot.h: Newell's teapot tessellated from its bicubic Bezier patches with analytic normals,
// and the 24 materials of the OpenGL Red Book's teapots example. Both tables are embedded at
// build time from assets/data/*.json (cmake/EmbedTeapotData.cmake); nothing is read at run time.
#pragma once

#include <lantern/Scene.h>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace lantern::scene {

// --- The embedded figures (generated TeapotData.cpp) ----------------------------------------

/// The teaset's 269 control points, in its units: y up, standing on y = 0, spout towards +x.
/// They are Newell's coordinates divided by 3.525 (his spout tip) and lowered by 0.15 (his
/// lowest ring), turned from z up to y up.
std::span<const std::array<double, 3>> teapotControlPoints();
/// The 28 patches (rim, body, handle, spout, lid; no bottom): 16 indices into
/// teapotControlPoints() each, row-major, u along a row and v down the rows, as in the file.
std::span<const std::array<std::uint16_t, 16>> teapotPatchIndices();

/// One material of the Red Book example (GL's glMaterial values).
struct ClassicMaterial {
    std::string_view name;
    std::array<double, 3> ambient, diffuse, specular;
    double shininess;  ///< GL units: the example's fraction of 128, already multiplied
};
/// The 24 materials in the example's order: 6 gems, 6 metals, 6 plastics, 6 rubbers.
std::span<const ClassicMaterial> redbookMaterials();

// --- Bezier patches -------------------------------------------------------------------------

/// A bicubic Bezier patch: 16 control points row-major, u along a row, v down the rows.
using BezierPatch = std::array<glm::dvec3, 16>;

/// A point of a patch with its partial derivatives.
struct PatchPoint {
    glm::dvec3 position{0.0};
    glm::dvec3 du{0.0}, dv{0.0};  ///< dP/du, dP/dv
    glm::dvec3 duv{0.0};          ///< d2P/dudv (the limit normal at a collapsed edge needs it)
};
PatchPoint evaluatePatch(const BezierPatch& patch, double u, double v);

/// The unit normal du x dv at (u, v) in [0,1]^2. Where a tangent vanishes (an edge of the
/// patch collapsed to a point, as at the lid's top) the cross product is zero or noise, and
/// the limit of the normal from inside the patch is returned instead. Always finite and unit.
glm::dvec3 patchNormal(const BezierPatch& patch, double u, double v);

/// True when the boundary curve of `patch` at v = 0 (edge 0), u = 1 (1), v = 1 (2) or u = 0 (3)
/// is collapsed to a point: its four control points lie within 1 % of the patch's size of one
/// another. The lid's top row is (Newell's data offsets two of its points by 0.002).
bool isCollapsedEdge(const BezierPatch& patch, int edge);

/// Newell's teapot as 28 patches in the teaset's units, each parameterised so that du x dv
/// points out of the teapot.
std::vector<BezierPatch> teapotPatches();

// --- Tessellation ---------------------------------------------------------------------------

/// The default subdivision level: segments along each patch edge. 10 gives 5 560 triangles
/// per teapot, 133 440 for the 24 of builtin:teapots: at lavapipe's single-threaded geometry
/// rate (12 M triangles/s unlit, 6.8 M lit: ../shared/numerics.md section 5.2) 11-20 ms of a
/// 1280x720 frame, where the body's silhouette is within 0.12 pixel of the true curve (9
/// degrees per segment on a 37.5-pixel radius; level 8: 0.18 px, 12 ms lit; level 12: 0.08 px,
/// 28 ms lit).
inline constexpr int kDefaultTeapotLevel = 10;
inline constexpr int kMaxTeapotLevel = 128;  ///< 916 992 triangles per teapot

/// The teapot tessellated `level` x `level` quads per patch (clamped to 1..kMaxTeapotLevel),
/// in the teaset's units, with the analytic unit normal at every vertex. Vertices shared by
/// neighbouring patches are welded (one position, so no cracks; one vertex where the normals
/// agree), triangles collapsed at the lid's pole are dropped, and every triangle is
/// counter-clockwise seen from outside. No texture coordinates.
Primitive makeTeapot(int level = kDefaultTeapotLevel);

} // namespace lantern::scene
