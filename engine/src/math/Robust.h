// Robust.h: cross products and 3x3 determinants accurate to a few ulps of their result, for
// transforms whose scales differ by many orders (1e-6 and 1e6 under a rotation), where the
// textbook formulas cancel catastrophically (the determinant of such a matrix comes out with
// the wrong sign, so mirroring and normals would flip).
#pragma once

#include <cmath>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

namespace lantern::math {

/// a*b - c*d with one rounding error (Kahan's algorithm with a fused multiply-add).
inline double differenceOfProducts(double a, double b, double c, double d) {
    const double w = c * d;
    const double error = std::fma(-c, d, w); // w - c*d, exactly
    const double f = std::fma(a, b, -w);
    return f + error;
}

/// a x b with each component correctly computed to within about one ulp.
inline glm::dvec3 accurateCross(const glm::dvec3& a, const glm::dvec3& b) {
    return {differenceOfProducts(a.y, b.z, a.z, b.y), differenceOfProducts(a.z, b.x, a.x, b.z),
            differenceOfProducts(a.x, b.y, a.y, b.x)};
}

/// a . b summed as if in twice the precision (Ogita, Rump and Oishi's Dot2), then rounded.
inline double accurateDot(const glm::dvec3& a, const glm::dvec3& b) {
    double sum = 0.0, compensation = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double p = a[i] * b[i];
        const double productError = std::fma(a[i], b[i], -p);
        const double s = sum + p;
        const double z = s - sum;
        const double sumError = (sum - (s - z)) + (p - z);
        sum = s;
        compensation += productError + sumError;
    }
    return sum + compensation;
}

/// det(m) = m[0] . (m[1] x m[2]), with the accurate cross and dot: its sign is right unless
/// |det| is below about 1e-16 |m[0]| |m[1] x m[2]|.
inline double accurateDeterminant(const glm::dmat3& m) {
    return accurateDot(m[0], accurateCross(m[1], m[2]));
}

/// The inverse of a rigid transform, exact in structure: [R^T | -R^T t].
inline glm::dmat4 inverseRigid(const glm::dmat4& m) {
    const glm::dmat3 rt = glm::transpose(glm::dmat3(m));
    glm::dmat4 inv(rt);
    inv[3] = glm::dvec4(-(rt * glm::dvec3(m[3])), 1.0);
    return inv;
}

} // namespace lantern::math
