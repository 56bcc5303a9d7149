// The teapot: the embedded tables equal assets/data/*.json; analytic patch normals equal
// finite-difference normals of the patch surface (limit normals at the lid's pole); the mesh
// has unit finite normals, consistent counter-clockwise winding and faces outward (winding
// numbers); the built-in scenes place and size the teapots as GLUT and the Red Book do.
#include "TestSupport.h"

#include "scene/Builtins.h"
#include "scene/Teapot.h"

#include <lantern/Io.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <set>

namespace {

using namespace lantern;
using namespace lantern::scene;

nlohmann::json readJson(const std::string& name) {
    const auto path = test::sourceDir() / "assets" / "data" / name;
    std::ifstream in(path);
    EXPECT_TRUE(in) << "cannot open " << path;
    return nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// --- The embedded tables --------------------------------------------------------------------

TEST(TeapotData, EmbeddedPatchesEqualTheJson) {
    const nlohmann::json j = readJson("utah-teapot.json");
    ASSERT_FALSE(j.is_discarded());
    const auto points = teapotControlPoints();
    const auto patches = teapotPatchIndices();
    ASSERT_EQ(points.size(), j["vertices"].size());
    ASSERT_EQ(patches.size(), j["patches"].size());
    EXPECT_EQ(points.size(), 269u);
    EXPECT_EQ(patches.size(), 28u);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k)
            ASSERT_EQ(points[i][k], j["vertices"][i][k].get<double>())
                << "vertices[" << i << "][" << k << "]";
    for (std::size_t p = 0; p < patches.size(); ++p)
        for (std::size_t k = 0; k < 16; ++k)
            ASSERT_EQ(patches[p][k], j["patches"][p][k].get<int>())
                << "patches[" << p << "][" << k << "]";
}

TEST(TeapotData, EmbeddedMaterialsEqualTheJson) {
    const nlohmann::json j = readJson("redbook-materials.json");
    ASSERT_FALSE(j.is_discarded());
    const auto materials = redbookMaterials();
    ASSERT_EQ(materials.size(), j["materials"].size());
    EXPECT_EQ(materials.size(), 24u);
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const auto& m = j["materials"][i];
        SCOPED_TRACE("materials[" + std::to_string(i) + "]");
        EXPECT_EQ(materials[i].name, m["name"].get<std::string>());
        for (std::size_t k = 0; k < 3; ++k) {
            EXPECT_EQ(materials[i].ambient[k], m["ambient"][k].get<double>());
            EXPECT_EQ(materials[i].diffuse[k], m["diffuse"][k].get<double>());
            EXPECT_EQ(materials[i].specular[k], m["specular"][k].get<double>());
        }
        EXPECT_EQ(materials[i].shininess, m["shininess"].get<double>());
    }
}

// --- Patch normals --------------------------------------------------------------------------

/// du x dv of the patch surface by second-order finite differences (one-sided at the edges).
glm::dvec3 finiteDifferenceNormal(const BezierPatch& patch, double u, double v, double h) {
    auto at = [&](double a, double b) { return evaluatePatch(patch, a, b).position; };
    auto derivative = [&](double x, auto point) {
        if (x - h < 0.0) return (-3.0 * point(x) + 4.0 * point(x + h) - point(x + 2 * h)) / (2 * h);
        if (x + h > 1.0) return (3.0 * point(x) - 4.0 * point(x - h) + point(x - 2 * h)) / (2 * h);
        return (point(x + h) - point(x - h)) / (2 * h);
    };
    const glm::dvec3 du = derivative(u, [&](double x) { return at(x, v); });
    const glm::dvec3 dv = derivative(v, [&](double y) { return at(u, y); });
    return glm::normalize(glm::cross(du, dv));
}

TEST(TeapotPatches, AnalyticNormalsMatchFiniteDifferences) {
    struct Case {
        const char* name;
        std::vector<double> us, vs;
        double h;
        double tolerance;  // radians
        const char* why;
    };
    const std::vector<double> inside = {0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95};
    const std::vector<double> all = {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0};
    const Case cases[] = {
        {"interior", inside, inside, 1e-5, 1e-7,
         "central differences: error h^2 |P'''| / |P'| ~ 1e-10, rounding eps/h ~ 1e-11"},
        {"edges and corners",
         all,
         {0.0, 1.0},
         1e-5,
         1e-6,
         "one-sided second-order differences along the patch boundary"},
        {"edges and corners (u)", {0.0, 1.0}, all, 1e-5, 1e-6, "the other two edges"},
    };
    const auto patches = teapotPatches();
    for (const Case& c : cases) {
        double worst = 0.0;
        for (std::size_t p = 0; p < patches.size(); ++p)
            for (double u : c.us)
                for (double v : c.vs) {
                    bool onCollapsed = false;
                    for (int e = 0; e < 4; ++e) {
                        const bool onEdge = (e == 0 && v == 0.0) || (e == 1 && u == 1.0) ||
                                            (e == 2 && v == 1.0) || (e == 3 && u == 0.0);
                        onCollapsed |= onEdge && isCollapsedEdge(patches[p], e);
                    }
                    if (onCollapsed) continue;  // the limit normal: next test
                    const double a = angleBetween(patchNormal(patches[p], u, v),
                                                  finiteDifferenceNormal(patches[p], u, v, c.h));
                    worst = std::max(worst, a);
                    EXPECT_LE(a, c.tolerance)
                        << c.name << ": patch " << p << " at (" << u << ", " << v << "); " << c.why;
                }
        RecordProperty(std::string(c.name) + " worst angle", std::to_string(worst));
    }
}

TEST(TeapotPatches, PoleHasTheLimitNormal) {
    // The lid's four top patches: their first row is nearly one point (Newell's data offsets
    // two of its control points by 0.002), where du vanishes. The normal there must be the
    // limit of the normals inside the patch, the same for every u and every patch: straight up.
    const auto patches = teapotPatches();
    int collapsedEdges = 0;
    for (std::size_t p = 0; p < patches.size(); ++p)
        for (int e = 0; e < 4; ++e) {
            if (!isCollapsedEdge(patches[p], e)) continue;
            ++collapsedEdges;
            for (double t = 0.0; t <= 1.0; t += 0.125) {
                const double u = e == 1 ? 1.0 : e == 3 ? 0.0 : t;
                const double v = e == 0 ? 0.0 : e == 2 ? 1.0 : t;
                const glm::dvec3 n = patchNormal(patches[p], u, v);
                EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
                EXPECT_LE(angleBetween(n, {0.0, 1.0, 0.0}), 1e-9)
                    << "patch " << p << " edge " << e << " at t = " << t;
                // Approaching the edge, the surface's own normal tends to the same direction
                // (the knob's top turns it by about 1.1 d at v = d) until, closer than about 0.002
                // in v, the tiny loop of the offset points dominates du and folds the surface over.
                for (double d : {1e-1, 3e-2, 1e-2}) {
                    const double ui = e == 1 ? 1.0 - d : e == 3 ? d : u;
                    const double vi = e == 0 ? d : e == 2 ? 1.0 - d : v;
                    EXPECT_LE(angleBetween(n, finiteDifferenceNormal(patches[p], ui, vi, d / 10)),
                              2.0 * d)
                        << "patch " << p << " edge " << e << " at t = " << t << ", " << d
                        << " inside";
                }
            }
            // Why the limit is needed: on the row itself du x dv of the data points down
            // (into the lid) for mid u, though it is finite there.
            const PatchPoint raw = evaluatePatch(patches[p], 0.5, 0.0);
            EXPECT_LT(glm::cross(raw.du, raw.dv).y, 0.0) << "patch " << p;
        }
    EXPECT_EQ(collapsedEdges, 4) << "the top row of each of the lid's four top patches";
}

TEST(TeapotPatches, DegeneratePatchNormalsStayUnit) {
    // Inputs the teapot does not have: a patch collapsed to a point and one to a curve.
    struct Case {
        const char* name;
        BezierPatch patch;
    };
    BezierPatch point, curve, corner;
    for (int i = 0; i < 16; ++i) {
        point[std::size_t(i)] = glm::dvec3(1.0, 2.0, 3.0);
        curve[std::size_t(i)] = glm::dvec3(double(i % 4), 0.0, 0.0);
        // A triangle-like patch: its first row and first column both collapse at the corner.
        const int r = i / 4, c = i % 4;
        corner[std::size_t(i)] = r == 0 || c == 0 ? glm::dvec3(0.0) : glm::dvec3(c, r, 0.0);
    }
    const Case cases[] = {{"point", point}, {"curve", curve}, {"collapsed corner", corner}};
    for (const Case& c : cases)
        for (double u : {0.0, 0.5, 1.0})
            for (double v : {0.0, 0.5, 1.0}) {
                const glm::dvec3 n = patchNormal(c.patch, u, v);
                EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z))
                    << c.name;
                EXPECT_NEAR(glm::length(n), 1.0, 1e-12) << c.name << " at " << u << ", " << v;
            }
    // The collapsed corner still has a true normal: the patch lies in z = 0, facing +z.
    EXPECT_NEAR(patchNormal(corner, 0.0, 0.0).z, 1.0, 1e-9);
}

// --- The mesh -------------------------------------------------------------------------------

TEST(TeapotMesh, TriangleCountAndUnitFiniteNormals) {
    struct Case {
        int level;
        std::size_t triangles;
        const char* why;
    };
    const Case cases[] = {
        {1, 52, "28 patches x 2, less one per pole quad of the lid's 4 top patches"},
        {2, 216, "28 x 2 x 4 - 4 x 2"},
        {kDefaultTeapotLevel, 28u * 2 * 100 - 4 * 10, "the default level"},
        {32, 28u * 2 * 1024 - 4 * 32, "a fine level"},
        {0, 52, "levels below 1 are clamped to 1"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE("level " + std::to_string(c.level) + ": " + c.why);
        const Primitive p = makeTeapot(c.level);
        EXPECT_EQ(p.triangleCount(), c.triangles);
        ASSERT_EQ(p.normals.size(), p.positions.size());
        EXPECT_TRUE(p.texcoords.empty());
        for (std::size_t i = 0; i < p.normals.size(); ++i) {
            const glm::vec3 n = p.normals[i], x = p.positions[i];
            ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) << i;
            ASSERT_TRUE(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z)) << i;
            ASSERT_NEAR(glm::length(n), 1.0f, 1e-6f) << "vertex " << i;
        }
        for (std::uint32_t index : p.indices) ASSERT_LT(index, p.positions.size());
    }
}

TEST(TeapotMesh, SeamsAreWeldedAndWindingIsConsistent) {
    const Primitive p = makeTeapot(kDefaultTeapotLevel);
    // By position, not index (a crease keeps two vertices at one point): no directed edge may
    // appear twice (two neighbours wound the same way), and every vertex position is unique
    // per normal (the weld merged the seams' duplicates).
    using Key = std::array<float, 3>;
    auto key = [&](std::uint32_t i) {
        return Key{p.positions[i].x, p.positions[i].y, p.positions[i].z};
    };
    std::map<std::pair<Key, Key>, int> directed;
    for (std::size_t t = 0; t < p.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            const auto edge =
                std::make_pair(key(p.indices[t + e]), key(p.indices[t + (e + 1) % 3]));
            EXPECT_LE(++directed[edge], 1) << "triangle " << t / 3 << " edge " << e;
        }
    std::size_t twinned = 0;
    for (const auto& [edge, count] : directed) twinned += directed.count({edge.second, edge.first});
    // Interior edges of a closed-up mesh come in pairs; boundary edges are the bottom rim,
    // the lid's and the rim's inner edges, the spout's opening and the handle's and spout's
    // ends (inside the body).
    EXPECT_GT(double(twinned) / double(directed.size()), 0.95);
    std::set<std::pair<Key, std::array<float, 3>>> vertices;
    for (std::size_t i = 0; i < p.positions.size(); ++i)
        EXPECT_TRUE(
            vertices
                .insert({key(std::uint32_t(i)), {p.normals[i].x, p.normals[i].y, p.normals[i].z}})
                .second)
            << "vertex " << i << " duplicates another";
}

TEST(TeapotMesh, TrianglesTurnWithTheSurfaceNormals) {
    // Counter-clockwise around the analytic normals: each face normal (from the winding)
    // within 90 degrees of its vertices' normals. Level 3 is too coarse for this: at the
    // spout's curled lip a third of a patch bends by more than that.
    for (int level : {kDefaultTeapotLevel, 32}) {
        const Primitive p = makeTeapot(level);
        for (std::size_t t = 0; t < p.indices.size(); t += 3) {
            const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]],
                            c = p.positions[p.indices[t + 2]];
            const glm::dvec3 face = glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
            ASSERT_GT(glm::length(face), 0.0) << "level " << level << " triangle " << t / 3;
            for (std::size_t k = 0; k < 3; ++k)
                EXPECT_GT(glm::dot(face, glm::dvec3(p.normals[p.indices[t + k]])), 0.0)
                    << "level " << level << " triangle " << t / 3
                    << " is wound against its normals";
        }
    }
}

/// Signed solid angle of triangle abc seen from q, over 4 pi (Van Oosterom and Strackee).
double windingContribution(const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b,
                           const glm::dvec3& c) {
    const glm::dvec3 A = a - q, B = b - q, C = c - q;
    const double la = glm::length(A), lb = glm::length(B), lc = glm::length(C);
    const double num = glm::dot(A, glm::cross(B, C));
    const double den =
        la * lb * lc + glm::dot(A, B) * lc + glm::dot(A, C) * lb + glm::dot(B, C) * la;
    return 2.0 * std::atan2(num, den) / (4.0 * 3.14159265358979323846);
}

TEST(TeapotMesh, FacesOutward) {
    struct Case {
        int level;
        std::size_t every;  // test every n-th triangle
        const char* why;
    };
    const Case cases[] = {
        {3, 1, "every triangle of a coarse mesh"},
        {kDefaultTeapotLevel, 11, "a sample of the default mesh (the winding sum is quadratic)"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE("level " + std::to_string(c.level) + ": " + c.why);
        const Primitive p = makeTeapot(c.level);
        std::vector<std::array<glm::dvec3, 3>> tris;
        for (std::size_t t = 0; t < p.indices.size(); t += 3)
            tris.push_back({glm::dvec3(p.positions[p.indices[t]]),
                            glm::dvec3(p.positions[p.indices[t + 1]]),
                            glm::dvec3(p.positions[p.indices[t + 2]])});
        const std::size_t meshTriangles = tris.size();
        // Close the bottom (the teaset has none): a fan from the centre to the boundary edges
        // at y = 0, each reversed, so that the winding number is 1 inside, 0 outside.
        std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
        for (std::size_t t = 0; t < p.indices.size(); t += 3)
            for (int e = 0; e < 3; ++e)
                edges.insert({p.indices[t + e], p.indices[t + (e + 1) % 3]});
        int capTriangles = 0;
        for (const auto& [a, b] : edges)
            if (!edges.count({b, a}) && p.positions[a].y == 0.0f && p.positions[b].y == 0.0f) {
                tris.push_back(
                    {glm::dvec3(p.positions[b]), glm::dvec3(p.positions[a]), glm::dvec3(0.0)});
                ++capTriangles;
            }
        EXPECT_EQ(capTriangles, 4 * c.level) << "the bottom rim: 4 body patches";

        for (std::size_t t = 0; t < meshTriangles; t += c.every) {
            const auto& [a, b, cc] = tris[t];
            const glm::dvec3 centre = (a + b + cc) / 3.0;
            const glm::dvec3 face = glm::cross(b - a, cc - a);
            ASSERT_GT(glm::length(face), 0.0) << "triangle " << t << " has no area";
            // Outward: the winding number is about 1 more just behind the face (against its
            // normal) than just in front, and in front it is not negative (a face turned
            // inwards has -1 in front of it; parts of the handle and spout inside the body
            // have 1 in front, 2 behind). Holes (the spout's mouth, the gap between lid and
            // rim, the handle's and spout's open ends) shift the sums by up to ~0.25 near them.
            const double eps = 1e-4 * std::sqrt(glm::length(face));
            const glm::dvec3 n = glm::normalize(face);
            double front = 0.0, back = 0.0;
            for (const auto& tri : tris) {
                front += windingContribution(centre + eps * n, tri[0], tri[1], tri[2]);
                back += windingContribution(centre - eps * n, tri[0], tri[1], tri[2]);
            }
            EXPECT_GT(front, -0.5) << "triangle " << t << " at " << centre.x << ", " << centre.y
                                   << ", " << centre.z << " faces inwards";
            EXPECT_GT(back, 0.5) << "triangle " << t;
        }
    }
}

// --- The scenes -----------------------------------------------------------------------------

TEST(TeapotScenes, GlutTeapotHasGlutsSize) {
    // glutSolidTeapot(1.0): Newell's teapot halved, centred on his z = 1.5: the handle's back
    // at x = -3.0 / 2, the lowest ring (z = 0.15) at (0.15 - 1.5) / 2, the knob (z = 3.15) at
    // (3.15 - 1.5) / 2. Tolerance: the 6-digit control points and float vertices.
    auto scene = loadScene("builtin:teapot");
    ASSERT_TRUE(scene) << scene.error().describe();
    const Bounds b = computeBounds(*scene, evaluatePose(*scene, -1, 0.0));
    EXPECT_NEAR(b.min.x, -1.5, 1e-5);
    EXPECT_NEAR(b.min.y, -0.675, 1e-5);
    EXPECT_NEAR(b.max.y, 0.825, 1e-5);
    EXPECT_NEAR(b.max.z, -b.min.z, 1e-6) << "symmetric about z = 0";
    EXPECT_NEAR(b.max.z, 1.0, 1e-5) << "the body's widest ring: Newell's radius 2.0, halved";
}

TEST(TeapotScenes, DefaultIsTheRedBookGrid) {
    for (const char* name : {"builtin:default", "builtin:teapots"}) {
        SCOPED_TRACE(name);
        auto scene = loadScene(name);
        ASSERT_TRUE(scene) << scene.error().describe();
        ASSERT_TRUE(scene->validate());
        ASSERT_EQ(scene->materials.size(), 24u);
        const auto materials = redbookMaterials();
        std::set<std::pair<double, double>> places;
        for (const Node& n : scene->nodes) {
            if (n.mesh < 0) continue;
            const Primitive& prim = scene->meshes[std::size_t(n.mesh)].primitives.at(0);
            const Material& m = scene->materials.at(std::size_t(prim.material));
            const ClassicMaterial& expected = materials[std::size_t(prim.material)];
            EXPECT_EQ(m.name, expected.name);
            EXPECT_EQ(m.front.shininess, expected.shininess);
            EXPECT_EQ(m.front.diffuse, glm::dvec4(expected.diffuse[0], expected.diffuse[1],
                                                  expected.diffuse[2], 1.0));
            // renderTeapot(x, y): material i at column i / 6, row i % 6 from the top.
            const double x = 2.0 + 4.0 * (prim.material / 6), y = 17.0 - 3.0 * (prim.material % 6);
            EXPECT_EQ(n.translation.x, x) << m.name;
            EXPECT_NEAR(n.translation.y, y - 0.675, 1e-12)
                << m.name << ": centred as GLUT centres it";
            places.insert({n.translation.x, n.translation.y});
        }
        EXPECT_EQ(places.size(), 24u);
        ASSERT_EQ(scene->lights.size(), 1u);
        EXPECT_EQ(scene->lights[0].type, LightType::Directional);
        EXPECT_EQ(scene->lights[0].ambient, glm::dvec3(0.0));
        ASSERT_TRUE(scene->roots.at(0).lighting);
        EXPECT_EQ(scene->roots[0].lighting->globalAmbient, glm::dvec3(0.2));
        EXPECT_FALSE(scene->roots[0].lighting->localViewer);
        ASSERT_EQ(scene->cameras.size(), 1u);
        EXPECT_EQ(scene->cameras[0].projection.kind, ProjectionKind::Orthographic);
        EXPECT_DOUBLE_EQ(scene->cameras[0].projection.top - scene->cameras[0].projection.bottom,
                         19.2);
    }
}

} // namespace
