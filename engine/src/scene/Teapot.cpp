// Newell's teapot: bicubic Bezier patch evaluation with analytic normals (limit normals at
// collapsed edges), patch orientation, and tessellation into a welded triangle mesh.
#include "scene/Teapot.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace lantern::scene {
namespace {

/// An edge whose control points lie within this fraction of the patch's size of one another
/// is treated as a single point; a tangent shorter than this fraction as vanishing. In the
/// teapot the lid's top row spans 0.16 % of its patch; every other tangent is above 6 %.
constexpr double kCollapsed = 1e-2;

struct Bernstein {
    double b[4];  ///< the cubic Bernstein polynomials at t
    double d[4];  ///< their derivatives
};

Bernstein bernstein(double t) {
    const double s = 1.0 - t;
    return {{s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t},
            {-3.0 * s * s, 3.0 * s * s - 6.0 * t * s, 6.0 * t * s - 3.0 * t * t, 3.0 * t * t}};
}

/// The diagonal of the control points' bounding box: the scale of "small" for a patch.
double patchSize(const BezierPatch& patch) {
    glm::dvec3 lo = patch[0], hi = patch[0];
    for (const glm::dvec3& p : patch) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return glm::length(hi - lo);
}

/// The control-point indices of boundary edge `edge` (see isCollapsedEdge), in order.
std::array<int, 4> edgeIndices(int edge) {
    switch (edge) {
    case 0: return {0, 1, 2, 3};      // v = 0: the first row
    case 1: return {3, 7, 11, 15};    // u = 1: the last column
    case 2: return {12, 13, 14, 15};  // v = 1: the last row
    default: return {0, 4, 8, 12};    // u = 0: the first column
    }
}

} // namespace

PatchPoint evaluatePatch(const BezierPatch& patch, double u, double v) {
    const Bernstein bu = bernstein(u), bv = bernstein(v);
    PatchPoint p;
    for (int r = 0; r < 4; ++r) {
        // Along the row first, then down the rows, so that an edge evaluates to exactly the
        // same numbers in two patches that share it in the same direction.
        glm::dvec3 row(0.0), rowDu(0.0);
        for (int c = 0; c < 4; ++c) {
            row += bu.b[c] * patch[std::size_t(r * 4 + c)];
            rowDu += bu.d[c] * patch[std::size_t(r * 4 + c)];
        }
        p.position += bv.b[r] * row;
        p.du += bv.b[r] * rowDu;
        p.dv += bv.d[r] * row;
        p.duv += bv.d[r] * rowDu;
    }
    return p;
}

bool isCollapsedEdge(const BezierPatch& patch, int edge) {
    const double tolerance = kCollapsed * patchSize(patch);
    const std::array<int, 4> e = edgeIndices(edge);
    for (int i = 1; i < 4; ++i)
        if (glm::length(patch[std::size_t(e[std::size_t(i)])] - patch[std::size_t(e[0])]) >
            tolerance)
            return false;
    return true;
}

glm::dvec3 patchNormal(const BezierPatch& patch, double u, double v) {
    const double size = patchSize(patch);
    const double shortTangent = kCollapsed * size;
    // Below this a cross product has no reliable direction (relative to the patch's area).
    const double noArea = 1e-12 * size * size;
    PatchPoint p = evaluatePatch(patch, u, v);
    glm::dvec3 n = glm::cross(p.du, p.dv);
    // On a collapsed edge du (or dv) vanishes. Stepping h into the patch gives
    // du(u, v + h) = du + h duv + O(h^2), so the normal's limit is the direction of duv x dv
    // (h > 0 from the edge v = 0, h < 0 from v = 1); symmetrically for a collapsed dv.
    if (glm::length(p.du) < shortTangent)
        n = (v < 0.5 ? 1.0 : -1.0) * glm::cross(p.duv, p.dv);
    else if (glm::length(p.dv) < shortTangent)
        n = (u < 0.5 ? 1.0 : -1.0) * glm::cross(p.du, p.duv);
    // A corner where both tangents vanish: walk towards the patch's centre until the surface
    // has area. A patch with no area anywhere has no normal; +Y keeps the result unit.
    for (double t = 1.0 / 1024.0; !(glm::length(n) > noArea) && t <= 0.5; t *= 2.0) {
        p = evaluatePatch(patch, u + (0.5 - u) * t, v + (0.5 - v) * t);
        n = glm::cross(p.du, p.dv);
    }
    const double length = glm::length(n);
    return length > noArea && std::isfinite(length) ? n / length : glm::dvec3(0.0, 1.0, 0.0);
}

std::vector<BezierPatch> teapotPatches() {
    const auto points = teapotControlPoints();
    std::vector<BezierPatch> patches;
    for (const auto& indices : teapotPatchIndices()) {
        BezierPatch patch;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) {
                // Every patch of the teaset is parameterised with du x dv pointing into the
                // teapot (its winding number is 1 on that side; tests/unit/TeapotTest.cpp
                // checks the result). Reading each row backwards mirrors u and turns the
                // patch outwards without moving a point.
                const auto& q = points[indices[std::size_t(r * 4 + (3 - c))]];
                patch[std::size_t(r * 4 + c)] = glm::dvec3(q[0], q[1], q[2]);
            }
        patches.push_back(patch);
    }
    return patches;
}

namespace {

constexpr std::uint32_t kNone = ~0u;

// The patches' vertices before welding, in double precision.
struct PatchMesh {
    std::vector<glm::dvec3> positions, normals;
    std::vector<std::uint32_t> indices;
    double extent = 0.0; ///< the largest patch's size
};

// Appends `patch` tessellated into n x n quads.
void tessellatePatch(const BezierPatch& patch, int n, PatchMesh& mesh) {
    std::vector<glm::dvec3>& positions = mesh.positions;
    mesh.extent = std::max(mesh.extent, patchSize(patch));
    bool collapsed[4];
    for (int e = 0; e < 4; ++e)
        collapsed[e] = isCollapsedEdge(patch, e);
    const std::uint32_t base = std::uint32_t(positions.size());
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double u = double(i) / n, v = double(j) / n;
            glm::dvec3 position = evaluatePatch(patch, u, v).position;
            // A collapsed edge becomes one point (its first control point, a corner), so
            // that the triangles there become a fan instead of slivers of random winding.
            const int edgeAt[4] = {j == 0 ? 0 : -1, i == n ? 1 : -1, j == n ? 2 : -1,
                                   i == 0 ? 3 : -1};
            for (int e : edgeAt)
                if (e >= 0 && collapsed[e]) position = patch[std::size_t(edgeIndices(e)[0])];
            positions.push_back(position);
            mesh.normals.push_back(patchNormal(patch, u, v));
        }
    const auto at = [&](int i, int j) { return base + std::uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            // Counter-clockwise in (u, v), hence around du x dv, which points outwards.
            const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1),
                                d = at(i, j + 1);
            mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        }
}

// Weld. Neighbouring patches evaluate a shared edge to the same points up to rounding
// (exactly when they run it in the same direction): vertices closer than `samePoint` take
// one position, and become one vertex where their normals agree (everywhere the surface
// is smooth across the seam; a crease keeps one vertex per side). Returns, per vertex, the
// vertex it is welded to (itself for the one kept).
std::vector<std::uint32_t> weldVertices(PatchMesh& mesh) {
    std::vector<glm::dvec3>& positions = mesh.positions;
    const std::vector<glm::dvec3>& normals = mesh.normals;
    const double samePoint = 1e-9 * mesh.extent;
    const double sameNormal = 1e-6;
    const std::size_t count = positions.size();
    std::vector<std::uint32_t> order(count);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return positions[a].x < positions[b].x; });
    std::vector<std::uint32_t> weldedTo(count, kNone);
    std::vector<std::uint32_t> cluster;
    for (std::size_t k = 0; k < count; ++k) {
        const std::uint32_t a = order[k];
        if (weldedTo[a] != kNone) continue;
        cluster.assign(1, a);
        for (std::size_t m = k + 1; m < count; ++m) {
            const std::uint32_t b = order[m];
            if (positions[b].x - positions[a].x > samePoint) break;
            if (weldedTo[b] == kNone && glm::length(positions[b] - positions[a]) <= samePoint) {
                positions[b] = positions[a];
                cluster.push_back(b);
            }
        }
        for (std::size_t i = 0; i < cluster.size(); ++i) {
            const std::uint32_t x = cluster[i];
            if (weldedTo[x] != kNone) continue;
            weldedTo[x] = x;
            for (std::size_t j = i + 1; j < cluster.size(); ++j)
                if (weldedTo[cluster[j]] == kNone &&
                    glm::length(normals[cluster[j]] - normals[x]) <= sameNormal)
                    weldedTo[cluster[j]] = x;
        }
    }
    return weldedTo;
}

// The kept vertices in float, and the triangles that still cover something.
Primitive weldedPrimitive(const PatchMesh& mesh, const std::vector<std::uint32_t>& weldedTo) {
    const std::vector<std::uint32_t>& indices = mesh.indices;
    const std::size_t count = mesh.positions.size();
    Primitive prim;
    std::vector<std::uint32_t> newIndex(count, kNone);
    for (std::uint32_t v = 0; v < count; ++v) {
        if (weldedTo[v] != v) continue;
        newIndex[v] = std::uint32_t(prim.positions.size());
        prim.positions.push_back(glm::vec3(mesh.positions[v]));
        prim.normals.push_back(glm::vec3(mesh.normals[v]));
    }
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const std::uint32_t a = newIndex[weldedTo[indices[t]]],
                            b = newIndex[weldedTo[indices[t + 1]]],
                            c = newIndex[weldedTo[indices[t + 2]]];
        const glm::vec3 pa = prim.positions[a], pb = prim.positions[b], pc = prim.positions[c];
        // Triangles at a collapsed edge have two corners in one point: they cover nothing.
        if (a == b || b == c || a == c || pa == pb || pb == pc || pa == pc) continue;
        prim.indices.insert(prim.indices.end(), {a, b, c});
    }
    return prim;
}

} // namespace

Primitive makeTeapot(int level) {
    const int n = std::clamp(level, 1, kMaxTeapotLevel);
    PatchMesh mesh;
    for (const BezierPatch& patch : teapotPatches())
        tessellatePatch(patch, n, mesh);
    const std::vector<std::uint32_t> weldedTo = weldVertices(mesh);
    return weldedPrimitive(mesh, weldedTo);
}

} // namespace lantern::scene
