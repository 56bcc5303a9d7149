// sameGeometry (GltfEncode.h): a loaded primitive against the mesh it was written from, whatever
// the vertex order. Each loaded vertex is matched to the nearest original vertex (position,
// normal and uv each within the encoding's tolerance); then every loaded triangle, through some
// choice of its corners' matches, must be an original triangle with the same winding.
#include "GltfEncode.h"

#include <array>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

namespace lantern::test {
namespace {

using Key = std::array<long long, 3>;

struct KeyHash {
    std::size_t operator()(const Key& k) const {
        return std::size_t(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
    }
};

double distance(const std::vector<float>& a, std::size_t i, const std::vector<float>& b,
                std::size_t j, std::size_t n) {
    double sum = 0;
    for (std::size_t c = 0; c < n; ++c) {
        const double d = double(a[i * n + c]) - double(b[j * n + c]);
        sum += d * d;
    }
    return std::sqrt(sum);
}

/// The triangle as its rotation that starts with the smallest index (the winding is kept).
std::array<std::uint32_t, 3> canonical(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (b < a && b <= c) return {b, c, a};
    if (c < a && c < b) return {c, a, b};
    return {a, b, c};
}

/// Original vertices by position cell, one entry per set of exact duplicates (their first).
class VertexIndex {
public:
    VertexIndex(const TestMesh& m, double cell) : m_mesh(m), m_cell(cell) {
        std::map<std::array<float, 8>, std::uint32_t> seen;
        for (std::uint32_t i = 0; i < m.vertexCount(); ++i) {
            const std::array<float, 8> key = {m.positions[3 * i], m.positions[3 * i + 1],
                                              m.positions[3 * i + 2], m.normals[3 * i],
                                              m.normals[3 * i + 1], m.normals[3 * i + 2],
                                              m.texcoords[2 * i], m.texcoords[2 * i + 1]};
            const auto [it, fresh] = seen.emplace(key, i);
            m_representative.push_back(it->second);
            if (fresh) m_cells[cellOf(m.positions, i)].push_back(i);
        }
    }
    std::uint32_t representative(std::uint32_t i) const { return m_representative[i]; }

    /// Every original vertex within every tolerance for loaded vertex `i` (an original may hold
    /// vertices closer together than an encoding's error), or none (and the distances of the
    /// candidate nearest by position in `nearest`).
    std::vector<std::uint32_t> match(const TestMesh& loaded, std::uint32_t i,
                                     const Tolerance& t, Tolerance& nearest) const {
        const Key k = cellOf(loaded.positions, i);
        std::vector<std::uint32_t> within;
        nearest = {1e300, 0.0, 0.0};
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy)
                for (long long dz = -1; dz <= 1; ++dz) {
                    auto it = m_cells.find({k[0] + dx, k[1] + dy, k[2] + dz});
                    if (it == m_cells.end()) continue;
                    for (std::uint32_t j : it->second) {
                        const double dp = distance(loaded.positions, i, m_mesh.positions, j, 3);
                        const double dn = distance(loaded.normals, i, m_mesh.normals, j, 3);
                        const double dt = distance(loaded.texcoords, i, m_mesh.texcoords, j, 2);
                        if (dp < nearest.position) nearest = {dp, dn, dt};
                        if (dp > t.position || dn > t.normal || dt > t.texcoord) continue;
                        within.push_back(j);
                    }
                }
        return within;
    }

private:
    Key cellOf(const std::vector<float>& positions, std::uint32_t i) const {
        return {std::llround(std::floor(positions[3 * i] / m_cell)),
                std::llround(std::floor(positions[3 * i + 1] / m_cell)),
                std::llround(std::floor(positions[3 * i + 2] / m_cell))};
    }
    const TestMesh& m_mesh;
    double m_cell;
    std::vector<std::uint32_t> m_representative;
    std::unordered_map<Key, std::vector<std::uint32_t>, KeyHash> m_cells;
};

} // namespace

::testing::AssertionResult sameGeometry(const TestMesh& loaded, const TestMesh& original,
                                        const Tolerance& tolerance) {
    if (loaded.indices.size() != original.indices.size())
        return ::testing::AssertionFailure() << loaded.indices.size() / 3 << " triangles, expected "
                                             << original.indices.size() / 3;
    // Cells at least as large as the position tolerance: a match lies in a neighbouring cell.
    const VertexIndex index(original, std::max(2 * tolerance.position, 1e-9));
    std::vector<std::vector<std::uint32_t>> match(loaded.vertexCount());
    for (std::uint32_t i = 0; i < loaded.vertexCount(); ++i) {
        Tolerance nearest{};
        match[i] = index.match(loaded, i, tolerance, nearest);
        if (match[i].empty())
            return ::testing::AssertionFailure()
                   << "loaded vertex " << i << " (" << loaded.positions[3 * i] << ", "
                   << loaded.positions[3 * i + 1] << ", " << loaded.positions[3 * i + 2]
                   << ") matches no original vertex within the tolerances (" << tolerance.position
                   << ", " << tolerance.normal << ", " << tolerance.texcoord
                   << "); the nearest position is at " << nearest.position
                   << " (its normal at " << nearest.normal << ", its uv at " << nearest.texcoord
                   << ")";
    }
    std::set<std::array<std::uint32_t, 3>> triangles;
    for (std::size_t t = 0; t + 2 < original.indices.size(); t += 3)
        triangles.insert(canonical(index.representative(original.indices[t]),
                                   index.representative(original.indices[t + 1]),
                                   index.representative(original.indices[t + 2])));
    // A loaded triangle must be an original one for some choice of its corners' matches.
    for (std::size_t t = 0; t + 2 < loaded.indices.size(); t += 3) {
        const auto& a = match[loaded.indices[t]];
        const auto& b = match[loaded.indices[t + 1]];
        const auto& c = match[loaded.indices[t + 2]];
        bool found = false;
        for (std::size_t i = 0; i < a.size() && !found; ++i)
            for (std::size_t j = 0; j < b.size() && !found; ++j)
                for (std::size_t k = 0; k < c.size() && !found; ++k)
                    found = triangles.count(canonical(a[i], b[j], c[k])) > 0;
        if (!found)
            return ::testing::AssertionFailure()
                   << "loaded triangle " << t / 3 << " (nearest original vertices " << a[0]
                   << ", " << b[0] << ", " << c[0] << " of " << a.size() << ", " << b.size()
                   << ", " << c.size()
                   << " within the tolerances) is not an original triangle with that winding";
    }
    return ::testing::AssertionSuccess();
}

} // namespace lantern::test
