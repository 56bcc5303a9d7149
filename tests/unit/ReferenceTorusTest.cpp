// The reference's torus (reference/Torus.cpp): its ray intersections against hand-computed
// ones, a tangent ray, a distant origin, and rays that miss; its tessellation's normals.
#include "reference/Torus.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;

TEST(ReferenceTorus, ARayThroughTheCentreMeetsItFourTimes) {
    // Along +X from x = -5 in the ring's plane: the tube is crossed at |x| = 1.35 and 0.65.
    double t[4];
    ASSERT_EQ(ref::torusRoots(1.0, 0.35, {-5.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, t), 4);
    const double expected[4] = {5.0 - 1.35, 5.0 - 0.65, 5.0 + 0.65, 5.0 + 1.35};
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(t[k], expected[k], 1e-12) << k;
    // A direction that is not unit: the parameters scale with it.
    ASSERT_EQ(ref::torusRoots(1.0, 0.35, {-5.0, 0.0, 0.0}, {4.0, 0.0, 0.0}, t), 4);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(t[k], expected[k] / 4.0, 1e-12) << k;
    // Down the axis, through the hole: no hit.
    EXPECT_EQ(ref::torusRoots(1.0, 0.35, {0.0, 0.0, 5.0}, {0.0, 0.0, -1.0}, t), 0);
    // From 1e6 away, the same four crossings.
    ASSERT_EQ(ref::torusRoots(1.0, 0.35, {-1e6, 0.0, 0.0}, {1.0, 0.0, 0.0}, t), 4);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(t[k] - (1e6 - 5.0), expected[k], 1e-8) << k;
}

TEST(ReferenceTorus, EveryRootLiesOnTheSurfaceWithAnOutwardNormal) {
    // A fan of oblique rays: each root satisfies the implicit equation, and the normal there
    // points away from the tube's centre line.
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        const double a = 0.031 * i;
        const glm::dvec3 o(3.0 * std::cos(a), 2.0 * std::sin(1.3 * a), 1.5 * std::cos(0.7 * a));
        const glm::dvec3 d = glm::normalize(glm::dvec3(0.2 * std::sin(a), 0.1, 0.0) - o);
        double t[4];
        const int n = ref::torusRoots(1.0, 0.35, o, d, t);
        for (int k = 0; k < n; ++k) {
            ++hits;
            const glm::dvec3 p = o + t[k] * d;
            const double ring = std::sqrt(p.x * p.x + p.y * p.y) - 1.0;
            EXPECT_NEAR(std::sqrt(ring * ring + p.z * p.z), 0.35, 1e-9);
            if (k > 0) {
                EXPECT_GT(t[k], t[k - 1]);
            }
            const glm::dvec3 n0 = ref::torusNormal(1.0, p);
            EXPECT_NEAR(glm::length(n0), 0.35, 1e-9);
        }
    }
    EXPECT_GT(hits, 200);
}

TEST(ReferenceTorus, ATangentRayTouchesItAtMostAtOnePoint) {
    // The plane z = 0.35 touches the top of the tube along the circle of radius 1: the ray
    // along y = 1 grazes it at x = 0 (found or, in rounding, not: never anywhere else). At a
    // double root the parameter is ill-conditioned (t moves by about the square root of the
    // rounding), but the point stays on the surface.
    double t[4];
    const glm::dvec3 o(-5.0, 1.0, 0.35), d(1.0, 0.0, 0.0);
    const int n = ref::torusRoots(1.0, 0.35, o, d, t);
    EXPECT_LE(n, 2);
    for (int k = 0; k < n; ++k) {
        EXPECT_NEAR(t[k], 5.0, 1e-3);
        const glm::dvec3 p = o + t[k] * d;
        const double ring = std::sqrt(p.x * p.x + p.y * p.y) - 1.0;
        EXPECT_NEAR(std::sqrt(ring * ring + p.z * p.z), 0.35, 1e-9);
    }
    EXPECT_EQ(ref::torusRoots(1.0, 0.35, {-5.0, 1.0, 0.36}, {1.0, 0.0, 0.0}, t), 0);
}

TEST(ReferenceTorus, TheTessellationLiesOnTheSurface) {
    const Primitive p = ref::makeTorus(1.0, 0.35, 24, 12);
    EXPECT_EQ(p.indices.size(), 24u * 12u * 6u);
    for (std::size_t i = 0; i < p.positions.size(); ++i) {
        const glm::dvec3 q(p.positions[i]);
        const double ring = std::sqrt(q.x * q.x + q.y * q.y) - 1.0;
        EXPECT_NEAR(std::sqrt(ring * ring + q.z * q.z), 0.35, 1e-6);
        EXPECT_NEAR(glm::dot(glm::normalize(ref::torusNormal(1.0, q)), glm::dvec3(p.normals[i])), 1.0, 1e-5);
    }
}

} // namespace
