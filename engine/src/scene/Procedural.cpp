// Procedural meshes (UV sphere with analytic normals, plane, cube) and angle-weighted vertex
// normals.
#include <lantern/Scene.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

std::vector<glm::vec3> computeSmoothNormals(const std::vector<glm::vec3>& positions,
                                            const std::vector<std::uint32_t>& indices) {
    std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
    const std::size_t count = indices.empty() ? positions.size() : indices.size();
    auto index = [&](std::size_t i) { return indices.empty() ? std::uint32_t(i) : indices[i]; };
    for (std::size_t t = 0; t + 2 < count; t += 3) {
        const std::uint32_t v[3] = {index(t), index(t + 1), index(t + 2)};
        if (v[0] >= positions.size() || v[1] >= positions.size() || v[2] >= positions.size())
            continue;
        const glm::dvec3 p[3] = {glm::dvec3(positions[v[0]]), glm::dvec3(positions[v[1]]),
                                 glm::dvec3(positions[v[2]])};
        const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double len = glm::length(n);
        if (!(len > 0.0) || !std::isfinite(len)) continue;  // degenerate: contributes nothing
        const glm::dvec3 unit = n / len;
        for (int c = 0; c < 3; ++c) {
            const glm::dvec3 e1 = p[(c + 1) % 3] - p[c], e2 = p[(c + 2) % 3] - p[c];
            const double l1 = glm::length(e1), l2 = glm::length(e2);
            if (!(l1 > 0.0) || !(l2 > 0.0)) continue;
            const double cosA = std::clamp(glm::dot(e1, e2) / (l1 * l2), -1.0, 1.0);
            sum[v[c]] += unit * std::acos(cosA);
        }
    }
    std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < sum.size(); ++i) {
        const double len = glm::length(sum[i]);
        if (len > 1e-300 && std::isfinite(len)) normals[i] = glm::vec3(sum[i] / len);
    }
    return normals;
}

Primitive makeSphere(double radius, int segments, int rings) {
    segments = std::max(segments, 3);
    rings = std::max(rings, 2);
    Primitive p;
    // (rings + 1) latitude rows of (segments + 1) vertices; the seam column is duplicated so
    // texture coordinates can wrap. Position = r * (sin(phi) sin(theta), cos(phi), sin(phi) cos(theta)).
    for (int i = 0; i <= rings; ++i) {
        const double phi = kPi * double(i) / double(rings);
        for (int j = 0; j <= segments; ++j) {
            const double theta = 2.0 * kPi * double(j) / double(segments);
            const glm::dvec3 n(std::sin(phi) * std::sin(theta), std::cos(phi),
                               std::sin(phi) * std::cos(theta));
            p.positions.push_back(glm::vec3(n * radius));
            p.normals.push_back(glm::vec3(n));
            p.texcoords.push_back(glm::vec2(float(j) / float(segments), float(i) / float(rings)));
        }
    }
    const auto idx = [&](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = idx(i, j), b = idx(i + 1, j), c = idx(i + 1, j + 1),
                                d = idx(i, j + 1);
            // Counter-clockwise seen from outside; the pole rows keep one triangle per quad.
            if (i != 0) p.indices.insert(p.indices.end(), {a, b, d});
            if (i != rings - 1) p.indices.insert(p.indices.end(), {d, b, c});
        }
    }
    return p;
}

Primitive makePlane(double size, int subdivisions) {
    subdivisions = std::max(subdivisions, 1);
    Primitive p;
    const int n = subdivisions;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double u = double(j) / n, v = double(i) / n;
            p.positions.emplace_back(float((u - 0.5) * size), float((v - 0.5) * size), 0.0f);
            p.normals.emplace_back(0.0f, 0.0f, 1.0f);
            p.texcoords.emplace_back(float(u), float(1.0 - v));
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const std::uint32_t a = std::uint32_t(i * (n + 1) + j), b = a + 1,
                                c = a + std::uint32_t(n + 1) + 1, d = a + std::uint32_t(n + 1);
            p.indices.insert(p.indices.end(), {a, b, c, a, c, d});
        }
    return p;
}

Primitive makeCube(double size) {
    Primitive p;
    const float h = float(size * 0.5);
    // Each face: normal, and two in-plane axes u, v with u x v = normal (counter-clockwise).
    const glm::vec3 faces[6][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    for (const auto& f : faces) {
        const std::uint32_t base = std::uint32_t(p.positions.size());
        const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const glm::vec2& c : corners) {
            p.positions.push_back(h * (f[0] + c.x * f[1] + c.y * f[2]));
            p.normals.push_back(f[0]);
            p.texcoords.emplace_back((c.x + 1) * 0.5f, (1 - c.y) * 0.5f);
        }
        p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return p;
}

} // namespace lantern
