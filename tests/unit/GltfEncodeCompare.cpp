// sameGeometry (GltfEncode.h): a loaded primitive against the mesh it was written from, whatever
// the vertex order. Each loaded vertex is matched to the nearest original vertex (position,
// normal and uv each within the encoding's tolerance); then every loaded triangle, through the
// match, must be an original triangle with the same winding.
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

    /// The best original vertex within every tolerance for loaded vertex `i`, or -1 (and the
    /// position distance of the nearest candidate in `nearest`).
    long long match(const TestMesh& loaded, std::uint32_t i, const Tolerance& t,
                    double& nearest) const {
        const Key k = cellOf(loaded.positions, i);
        long long best = -1;
        double bestScore = 1e300;
        nearest = 1e300;
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy)
                for (long long dz = -1; dz <= 1; ++dz) {
                    auto it = m_cells.find({k[0] + dx, k[1] + dy, k[2] + dz});
                    if (it == m_cells.end()) continue;
                    for (std::uint32_t j : it->second) {
                        const double dp = distance(loaded.positions, i, m_mesh.positions, j, 3);
                        const double dn = distance(loaded.normals, i, m_mesh.normals, j, 3);
                        const double dt = distance(loaded.texcoords, i, m_mesh.texcoords, j, 2);
                        nearest = std::min(nearest, dp);
                        if (dp > t.position || dn > t.normal || dt > t.texcoord) continue;
                        const double score = dp / t.position + dn / t.normal + dt / t.texcoord;
                        if (score < bestScore) {
                            bestScore = score;
                            best = j;
                        }
                    }
                }
        return best;
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
    std::vector<std::uint32_t> match(loaded.vertexCount());
    for (std::uint32_t i = 0; i < loaded.vertexCount(); ++i) {
        double nearest = 0;
        const long long j = index.match(loaded, i, tolerance, nearest);
        if (j < 0)
            return ::testing::AssertionFailure()
                   << "loaded vertex " << i << " (" << loaded.positions[3 * i] << ", "
                   << loaded.positions[3 * i + 1] << ", " << loaded.positions[3 * i + 2]
                   << ") matches no original vertex within the tolerances (" << tolerance.position
                   << ", " << tolerance.normal << ", " << tolerance.texcoord
                   << "); nearest position at " << nearest;
        match[i] = std::uint32_t(j);
    }
    std::set<std::array<std::uint32_t, 3>> triangles;
    for (std::size_t t = 0; t + 2 < original.indices.size(); t += 3)
        triangles.insert(canonical(index.representative(original.indices[t]),
                                   index.representative(original.indices[t + 1]),
                                   index.representative(original.indices[t + 2])));
    for (std::size_t t = 0; t + 2 < loaded.indices.size(); t += 3) {
        const auto tri = canonical(match[loaded.indices[t]], match[loaded.indices[t + 1]],
                                   match[loaded.indices[t + 2]]);
        if (!triangles.count(tri))
            return ::testing::AssertionFailure()
                   << "loaded triangle " << t / 3 << " (original vertices " << tri[0] << ", "
                   << tri[1] << ", " << tri[2] << ") is not an original triangle with that winding";
    }
    return ::testing::AssertionSuccess();
}

} // namespace lantern::test
