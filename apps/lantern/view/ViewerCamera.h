// ViewerCamera.h: the viewer's camera. It starts as the scene's camera (or the command line's
// spec) untouched, so the first picture is what `lantern render` gives; the first orbit, pan,
// zoom, fly or projection switch takes it over as a free camera placed exactly where the
// scene's was, then moved as in common 3D viewers (turntable orbit about a pivot with +Y up).
// Public API only; no window system here.
#pragma once

#include <glm/vec3.hpp>
#include <lantern/Renderer.h>
#include <string>

namespace lantern::cli {

class ViewerCamera {
public:
    /// The scene's camera (or the command line's): used as is until taken over.
    void setBase(const CameraSpec& spec) {
        m_base = spec;
        m_free = false;
    }
    const CameraSpec& base() const { return m_base; }
    /// The bounds the camera frames and clips against (world space, over the animation).
    void setBounds(const Bounds& bounds);

    bool isFree() const { return m_free; }
    /// Becomes a free camera at `placement` (the base camera as resolved for the view).
    void takeOver(const CameraPlacement& placement);

    // Mouse and keys, in pixels of a view `viewHeight` pixels tall; all need isFree().
    void orbit(double dxPixels, double dyPixels);
    void pan(double dxPixels, double dyPixels, double viewHeight);
    /// Dolly (perspective) or scale (orthographic) by 0.9^steps: positive steps come closer.
    void zoom(double steps);
    /// Fly mode's mouse look: turns about the eye.
    void look(double dxPixels, double dyPixels);
    /// Fly mode's movement: right, up and forward in scene radii.
    void move(const glm::dvec3& rightUpForward);
    /// Frames the bounds (`aspect`: width / height of the view).
    void frameAll(double aspect);
    /// Turns to look along the named view's direction (as `--view`; straight up and down
    /// stop 0.5 degrees short, as orbiting does) and frames all.
    void lookFrom(ViewDirection view, double aspect);
    void setOrthographic(bool orthographic);
    bool orthographic() const { return m_orthographic; }

    /// The spec to render a view of aspect `aspect` with: the base, or the free camera as an
    /// explicit lookAt and projection.
    CameraSpec spec(double aspect) const;
    /// The same as `lantern render` options ("--look-at ... --perspective ..."); exact doubles.
    std::string commandLine(double aspect) const;

    glm::dvec3 forward() const;
    glm::dvec3 eye() const { return m_target - forward() * m_distance; }
    const glm::dvec3& target() const { return m_target; }

private:
    Projection projection(double aspect) const;

    CameraSpec m_base;
    bool m_free = false;
    glm::dvec3 m_center{0.0};
    double m_radius = 1.0;
    glm::dvec3 m_target{0.0};
    double m_distance = 1.0;
    double m_yaw = 0.0, m_pitch = 0.0; ///< radians; yaw 0, pitch 0 looks down -Z
    double m_yfovDeg = 45.0;           ///< degrees, as --perspective takes it
    bool m_orthographic = false;
    double m_halfHeight = 1.0; ///< orthographic: half the view's height at the target
};

} // namespace lantern::cli
