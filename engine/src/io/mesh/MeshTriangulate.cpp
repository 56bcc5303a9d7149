// Polygons to triangles for every mesh format (MeshInternal.h, Triangulator): convex polygons
// fanned, concave ones ear-clipped in their plane while the load's ear-clipping budget lasts.
#include "io/mesh/MeshInternal.h"

#include <cmath>

namespace lantern::mesh {
namespace {

void fan(const std::uint32_t* corners, std::size_t n, std::vector<std::uint32_t>& out) {
    for (std::size_t i = 1; i + 1 < n; ++i) {
        out.push_back(corners[0]);
        out.push_back(corners[i]);
        out.push_back(corners[i + 1]);
    }
}

// The polygon's 2D outline in the plane of its normal: the normal's largest axis dropped, the
// other two ordered so that the polygon turns counter-clockwise.
std::vector<glm::dvec2> project(const std::vector<glm::vec3>& positions,
                                const std::uint32_t* corners, std::size_t n,
                                const glm::dvec3& normal) {
    const glm::dvec3 a = glm::abs(normal);
    const int drop = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
    int u = (drop + 1) % 3, v = (drop + 2) % 3;
    if (normal[drop] < 0.0) std::swap(u, v);
    std::vector<glm::dvec2> q(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3& p = positions[corners[i]];
        q[i] = glm::dvec2(p[u], p[v]);
    }
    return q;
}

double cross2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Inside or on the boundary of the counter-clockwise triangle (a, b, c): a corner on the edge
// of a candidate ear blocks it (else the ear could cut across the outline there). A corner at
// the same place as one of the three (a repeated vertex) does not.
bool blocksEar(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b,
               const glm::dvec2& c) {
    if (p == a || p == b || p == c) return false;
    return cross2(a, b, p) >= 0.0 && cross2(b, c, p) >= 0.0 && cross2(c, a, p) >= 0.0;
}

} // namespace

std::size_t Triangulator::add(const std::uint32_t* corners, std::size_t n,
                              std::vector<std::uint32_t>& out) {
    if (n < 3) return 0;
    if (n == 3) {
        out.insert(out.end(), corners, corners + 3);
        return 1;
    }
    glm::dvec3 normal(0.0);  // Newell's method: robust for any planar-ish polygon
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 p(m_positions[corners[i]]), q(m_positions[corners[(i + 1) % n]]);
        normal += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x),
                             (p.x - q.x) * (p.y + q.y));
    }
    if (!(glm::length(normal) > 0.0) || convex(corners, n, normal)) {
        if (n == 4) {
            // The shorter diagonal, as tinyobjloader and most tools split a quad.
            const glm::vec3 *p = &m_positions[0];
            const float d02 = glm::length(p[corners[2]] - p[corners[0]]);
            const float d13 = glm::length(p[corners[3]] - p[corners[1]]);
            const std::uint32_t rot[4] = {corners[1], corners[2], corners[3], corners[0]};
            fan(d02 <= d13 ? corners : rot, 4, out);
        } else {
            fan(corners, n, out);
        }
        return n - 2;
    }
    return earClip(corners, n, normal, out);
}

bool Triangulator::convex(const std::uint32_t* corners, std::size_t n,
                          const glm::dvec3& normal) const {
    const double scale = glm::length(normal);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 a(m_positions[corners[(i + n - 1) % n]]), b(m_positions[corners[i]]),
            c(m_positions[corners[(i + 1) % n]]);
        const glm::dvec3 turn = glm::cross(b - a, c - b);
        if (glm::dot(turn, normal) < -1e-9 * glm::length(turn) * scale) return false;
    }
    return true;
}

std::size_t Triangulator::earClip(const std::uint32_t* corners, std::size_t n,
                                  const glm::dvec3& normal, std::vector<std::uint32_t>& out) {
    const std::uint64_t cost = std::uint64_t(n) * n;
    if (m_earWork + 4 * cost > kEarClipBudget) {
        if (!m_warned)
            m_diag.warn("faces", "a concave polygon of " + std::to_string(n) +
                                     " corners is fanned: the load's ear-clipping budget (" +
                                     std::to_string(kEarClipBudget) +
                                     " steps) is spent; later ones are fanned too");
        m_warned = true;
        fan(corners, n, out);
        return n - 2;
    }
    m_earWork += 4 * cost;
    const std::vector<glm::dvec2> q = project(m_positions, corners, n, normal);
    std::vector<std::size_t> prev(n), next(n);
    for (std::size_t i = 0; i < n; ++i) {
        prev[i] = (i + n - 1) % n;
        next[i] = (i + 1) % n;
    }
    // Each ear test walks the outline: at most 4 n^2 steps in all (a well-formed polygon needs
    // about n^2 / 2), then the rest is fanned.
    std::size_t left = n, i = 0, misses = 0, made = 0;
    std::uint64_t steps = 0;
    auto emit = [&](std::size_t a, std::size_t b, std::size_t c) {
        out.push_back(corners[a]);
        out.push_back(corners[b]);
        out.push_back(corners[c]);
        ++made;
    };
    while (left > 3 && misses <= left && steps <= 4 * cost) {
        const std::size_t a = prev[i], c = next[i];
        bool ear = cross2(q[a], q[i], q[c]) > 0.0;
        for (std::size_t j = next[c]; ear && j != a; j = next[j], ++steps)
            ear = !blocksEar(q[j], q[a], q[i], q[c]);
        if (!ear) {
            i = c;
            ++misses;
            continue;
        }
        emit(a, i, c);
        next[a] = c;
        prev[c] = a;
        --left;
        misses = 0;
        i = c;
    }
    // Three left, or no ear found (a self-intersecting outline): the rest as a fan.
    for (std::size_t j = next[i]; next[j] != i; j = next[j]) emit(i, j, next[j]);
    return made;
}

} // namespace lantern::mesh
