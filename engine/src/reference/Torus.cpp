// The torus of the reference (AnalyticKind::Torus): its exact ray intersections, normal and
// tessellation. A ray meets a torus where a quartic in the ray parameter vanishes; its real
// roots are isolated between the roots of its derivatives (found the same way, down to a
// line) and each is bisected to the last bit, so no root is missed and none is approximate.
#include "reference/Torus.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::ref {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// p(x) for coefficients c[0] + c[1] x + ... + c[n] x^n.
double evaluate(const double* c, int n, double x) {
    double v = c[n];
    for (int k = n - 1; k >= 0; --k) v = v * x + c[k];
    return v;
}

// The root of p in [lo, hi], where p is monotone and changes sign (or is zero at an end).
double bisect(const double* c, int n, double lo, double hi) {
    double flo = evaluate(c, n, lo);
    if (flo == 0.0) return lo;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        const double f = evaluate(c, n, mid);
        if (f == 0.0) return mid;
        if ((f < 0.0) == (flo < 0.0)) {
            lo = mid;
            flo = f;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

// The real roots of the degree-n polynomial c in [lo, hi], ascending; returns how many.
int rootsIn(const double* c, int n, double lo, double hi, double* out) {
    while (n > 0 && c[n] == 0.0) --n;
    if (n == 0) return 0;
    // Between consecutive roots of the derivative p is monotone: one root at most each.
    double derivative[4];
    for (int k = 1; k <= n; ++k) derivative[k - 1] = k * c[k];
    double cuts[6];
    int count = 0;
    cuts[count++] = lo;
    count += rootsIn(derivative, n - 1, lo, hi, cuts + count);
    cuts[count++] = hi;
    int found = 0;
    for (int i = 0; i + 1 < count; ++i) {
        const double a = evaluate(c, n, cuts[i]), b = evaluate(c, n, cuts[i + 1]);
        if (a == 0.0 && found > 0 && out[found - 1] == cuts[i]) continue;  // met already
        if ((a <= 0.0 && b >= 0.0) || (a >= 0.0 && b <= 0.0))
            out[found++] = bisect(c, n, cuts[i], cuts[i + 1]);
    }
    return found;
}

} // namespace

int torusRoots(double major, double minor, const glm::dvec3& o, const glm::dvec3& d, double ts[4]) {
    const double length = glm::length(d);
    if (!(length > 0.0) || !std::isfinite(length)) return 0;
    const glm::dvec3 u = d / length;
    // Only where the ray is inside the sphere around the torus: from its entry point on,
    // where the coefficients are small (no cancellation from a distant origin).
    const double bound = major + minor;
    const double b = glm::dot(o, u), cSphere = glm::dot(o, o) - bound * bound;
    const double disc = b * b - cSphere;
    if (!(disc > 0.0)) return 0;
    const double s0 = -b - std::sqrt(disc), s1 = -b + std::sqrt(disc);
    const glm::dvec3 p = o + s0 * u;
    // (|p + s u|^2 + R^2 - r^2)^2 - 4 R^2 ((px + s ux)^2 + (py + s uy)^2), with |u| = 1.
    const double R2 = major * major;
    const double B = 2.0 * glm::dot(p, u), C = glm::dot(p, p) + R2 - minor * minor;
    const double uxy = u.x * u.x + u.y * u.y, pu = p.x * u.x + p.y * u.y, pxy = p.x * p.x + p.y * p.y;
    const double c[5] = {C * C - 4.0 * R2 * pxy, 2.0 * B * C - 8.0 * R2 * pu,
                         B * B + 2.0 * C - 4.0 * R2 * uxy, 2.0 * B, 1.0};
    double s[4];
    const int n = rootsIn(c, 4, 0.0, s1 - s0, s);
    for (int k = 0; k < n; ++k) ts[k] = (s0 + s[k]) / length;
    return n;
}

glm::dvec3 torusNormal(double major, const glm::dvec3& p) {
    // The gradient of the implicit function, up to a positive factor: the outward normal.
    const glm::dvec3 ring = glm::length(glm::dvec2(p.x, p.y)) > 0.0
                                ? major * glm::normalize(glm::dvec3(p.x, p.y, 0.0))
                                : glm::dvec3(major, 0.0, 0.0);
    return p - ring;
}

Primitive makeTorus(double major, double minor, int segments, int sides) {
    Primitive prim;
    for (int i = 0; i <= segments; ++i) {
        const double a = kTwoPi * i / segments;
        const glm::dvec3 radial(std::cos(a), std::sin(a), 0.0);
        for (int j = 0; j <= sides; ++j) {
            const double b = kTwoPi * j / sides;
            const glm::dvec3 n = std::cos(b) * radial + glm::dvec3(0.0, 0.0, std::sin(b));
            prim.positions.push_back(glm::vec3(major * radial + minor * n));
            prim.normals.push_back(glm::vec3(n));
        }
    }
    const auto at = [&](int i, int j) { return std::uint32_t(i * (sides + 1) + j); };
    for (int i = 0; i < segments; ++i)
        for (int j = 0; j < sides; ++j) {
            prim.indices.insert(prim.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            prim.indices.insert(prim.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return prim;
}

} // namespace lantern::ref
