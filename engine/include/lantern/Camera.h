// The classic camera model in double precision: gluLookAt, glOrtho, glFrustum,
// gluPerspective, glViewport, GL's matrix stack, and the one conversion to Vulkan clip space.
//
// Conventions: right-handed eye space, the camera looks down -Z with +Y up; column-major
// glm::dmat4 (m[column][row]); matrices are named by the spaces they map (clipFromView).
// The GL functions return exactly the matrices of the GL/GLU reference pages (clip z in
// -w..w, y up). Lantern renders with vulkanClipFromView(), which folds GL's -1..1 depth into
// Vulkan's 0..1 (optionally reversed) and flips y, computed in double so no precision is lost.
#pragma once

#include <lantern/Result.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lantern {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// --- GL/GLU matrices (unchecked: arguments must be valid; see the check* functions) ---------

/// gluLookAt: viewFromWorld for an eye at `eye` looking at `target` with `up` roughly up.
glm::dmat4 lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up);
/// glOrtho: clipFromView (GL clip space) for the box [l,r]x[b,t] between depths n and f
/// (n and f are distances along -Z and may be negative).
glm::dmat4 ortho(double l, double r, double b, double t, double n, double f);
/// glFrustum: clipFromView (GL clip space); n > 0, f > n, f may be +infinity.
glm::dmat4 frustum(double l, double r, double b, double t, double n, double f);
/// gluPerspective: clipFromView (GL clip space); fovy in degrees in (0, 180), aspect = w/h,
/// n > 0, f > n, f may be +infinity (the limit f -> infinity of GLU's matrix).
glm::dmat4 perspective(double fovyDegrees, double aspect, double n, double f);
/// glViewport (with glDepthRange n..f): windowFromNdc, mapping NDC x,y,z in -1..1 to window
/// x in [x, x+w], y in [y, y+h] (GL's origin: bottom-left) and depth in [n, f].
glm::dmat4 viewport(double x, double y, double w, double h, double depthNear = 0.0,
                    double depthFar = 1.0);
/// The vertical field of view in degrees of a physical lens: 2 atan(filmHeight / (2 focal)).
/// Any unit works as long as both lengths use it (millimetres by convention).
double fovyFromLens(double focalLengthMm, double filmHeightMm);

/// gluProject: window coordinates (GL's: origin bottom-left, depth in 0..1 for glDepthRange
/// 0..1) of `object` seen through GL matrices and `viewport` (x, y, width, height). The
/// homogeneous divide is by clip w; a point with w == 0 has no image and gives nullopt.
std::optional<glm::dvec3> project(const glm::dvec3& object, const glm::dmat4& viewFromModel,
                                  const glm::dmat4& clipFromView, const glm::dvec4& viewport);
/// gluUnProject: the model-space point whose window coordinates are `window` (the inverse of
/// project()); nullopt when the matrices are singular or the point is at infinity.
std::optional<glm::dvec3> unProject(const glm::dvec3& window, const glm::dmat4& viewFromModel,
                                    const glm::dmat4& clipFromView, const glm::dvec4& viewport);

/// How depth is stored: Vulkan's 0..1 with near at 0 (Standard) or near at 1 (ReversedZ,
/// the default: with a float depth buffer its precision is nearly uniform in distance).
enum class DepthMode { ReversedZ, Standard };
const char* toString(DepthMode mode) noexcept;  ///< "reversed", "standard"
/// Parses "reversed" or "standard" (as the command line's --depth spells them).
std::optional<DepthMode> parseDepthMode(std::string_view text) noexcept;

/// The one matrix that converts GL clip space to Vulkan clip space: y flipped (Vulkan's y
/// points down the framebuffer) and z mapped from -w..w to 0..w (Standard) or w..0 (ReversedZ):
///   Standard:  [1 0 0 0; 0 -1 0 0; 0 0 1/2 1/2; 0 0 0 1]   (rows)
///   ReversedZ: [1 0 0 0; 0 -1 0 0; 0 0 -1/2 1/2; 0 0 0 1]
/// The y flip happens in clip space and Vulkan measures winding in its y-down framebuffer, so
/// a face counter-clockwise in GL's window is counter-clockwise for Vulkan too: front faces are
/// counter-clockwise, as in GL (clockwise for mirroring transforms, whose winding reverses).
glm::dmat4 vulkanFromGlClip(DepthMode mode);

// --- Camera description ---------------------------------------------------------------------

enum class ProjectionKind {
    Perspective,   ///< symmetric: yfov, aspect, near, far (gluPerspective, glTF perspective)
    Frustum,       ///< off-axis perspective: left, right, bottom, top at the near plane (glFrustum)
    Orthographic,  ///< off-axis orthographic box (glOrtho, glTF orthographic)
};

/// A projection in GL's terms, kept symbolic so that it can be rebuilt for any viewport aspect
/// and depth mode.
struct Projection {
    ProjectionKind kind = ProjectionKind::Perspective;
    double yfov = 0.7853981633974483;  ///< Perspective: vertical field of view, radians
    double aspect = 0.0;  ///< Perspective: width/height; 0 means "the viewport's aspect"
    double left = -1.0, right = 1.0, bottom = -1.0, top = 1.0;  ///< Frustum/Orthographic
    double znear = 0.1;   ///< distance to the near plane (>0 for Perspective/Frustum)
    double zfar = kInfinity;  ///< distance to the far plane; +infinity allowed for perspective
    /// Frustum/Orthographic: widen the left/right or bottom/top range about its centre so the
    /// box has the viewport's aspect, as a GL program's reshape callback does (the Red Book's
    /// teapots). Off (the default), the box is used as given and stretches with the viewport.
    bool fitViewportAspect = false;

    static Projection makePerspective(double yfovRadians, double aspect, double znear,
                                      double zfar);
    static Projection makeFrustum(double l, double r, double b, double t, double n, double f);
    static Projection makeOrtho(double l, double r, double b, double t, double n, double f);
    /// A physical camera: a lens of the given focal length in front of a film (sensor) of the
    /// given size, all in the same unit (millimetres by convention: 50 mm on 36 x 24 mm film).
    /// yfov = 2 atan(filmHeight / (2 focal)), aspect = filmWidth / filmHeight (a viewport of
    /// another aspect stretches the image, as GL does; pass filmWidth 0 to use the viewport's).
    /// Check the result with checkProjection (a focal length <= 0 gives fovy >= 180).
    static Projection makeLens(double focalLength, double filmWidth, double filmHeight,
                               double znear, double zfar);
};

/// The GL clip-from-view matrix of a projection for a viewport of the given aspect (w/h).
glm::dmat4 glClipFromView(const Projection& projection, double viewportAspect);

/// The projection as drawn in a viewport of the given aspect: `projection` itself, or with
/// fitViewportAspect its box widened to that aspect.
Projection fittedProjection(const Projection& projection, double viewportAspect);

/// The Vulkan clip-from-view matrix: vulkanFromGlClip(mode) * glClipFromView(...), evaluated
/// in closed form in double precision (no cancellation for far/near ratios up to 1e300).
glm::dmat4 vulkanClipFromView(const Projection& projection, double viewportAspect,
                              DepthMode mode);

/// gluLookAt parameters, world space.
struct LookAt {
    glm::dvec3 eye{0.0, 0.0, 0.0};
    glm::dvec3 target{0.0, 0.0, -1.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
};

/// A camera as a scene holds it: a projection and, optionally, a lookAt that places it
/// (LANTERN_camera.lookAt; otherwise the camera's node transform places it).
struct Camera {
    std::string name;
    Projection projection;
    std::optional<LookAt> lookAt;
};

/// The GL default camera: at the origin looking down -Z, orthographic 2x2x2 cube
/// (glOrtho(-1,1,-1,1,-1,1)) and an identity view.
Camera glDefaultCamera();

// --- Checked construction (for user input) ------------------------------------------------

/// Refuses eye == target, a zero up, an up parallel to the view direction and non-finite
/// values; `object` names the input in the error ("--look-at", "cameras[2].extensions...").
Result<void> checkLookAt(const LookAt& lookAt, const std::string& object);
/// Refuses what GL refuses or what cannot render: near <= 0 for perspective and frustum,
/// far == near (far <= near for perspective), left == right, bottom == top, fovy outside
/// (0, 180) degrees, aspect < 0 (0 stands for the viewport's), any non-finite value except a
/// perspective or frustum far of +inf, and a view volume whose matrix does not fit single
/// precision (the GPU's): an entry that overflows float, or a scale or near term that would
/// flush to zero. Extreme valid values (fovy 1e-4 or 179.9 degrees, aspect 1e-4 or 1e4, near
/// 1e-6 with far 1e12) pass and render.
Result<void> checkProjection(const Projection& projection, const std::string& object);

// --- GL's matrix stack ----------------------------------------------------------------------

/// GL's modelview stack: each transformation multiplies the current matrix on the right,
/// so the transformation specified last is the first applied to a vertex
/// (translate(); rotate(); draws a vertex rotated, then translated). Double precision.
class TransformStack {
public:
    TransformStack();
    void push();          ///< glPushMatrix
    bool pop();           ///< glPopMatrix; false (and no change) on an empty stack
    void loadIdentity();  ///< glLoadIdentity
    void load(const glm::dmat4& m);   ///< glLoadMatrix
    void multiply(const glm::dmat4& m);  ///< glMultMatrix: current = current * m
    void translate(const glm::dvec3& t);                 ///< glTranslate
    void rotate(double degrees, const glm::dvec3& axis); ///< glRotate (axis normalised)
    void scale(const glm::dvec3& s);                     ///< glScale
    void lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up);
    const glm::dmat4& top() const { return m_stack.back(); }
    std::size_t depth() const { return m_stack.size(); }

private:
    std::vector<glm::dmat4> m_stack;
};

/// The matrix that transforms normals of a model with `viewFromModel`: the cofactor matrix of
/// its upper 3x3 (proportional to the inverse transpose, but defined for singular matrices),
/// divided by its largest absolute entry so that it stays finite for scales from 1e-300 to
/// 1e300. Normals must be renormalised after applying it. Zero matrix in, zero matrix out.
glm::dmat3 normalMatrix(const glm::dmat4& viewFromModel);

} // namespace lantern
