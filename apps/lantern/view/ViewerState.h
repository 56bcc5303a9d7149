// ViewerState.h: what `lantern view` shows and how, shared by its frame loop (Viewer), its input
// (ViewerInput) and its ImGui panel (ViewerUi), and the camera changes they ask of it. Public
// API only; no window system here.
#pragma once

#include "view/ViewerCamera.h"

#include <lantern/Lantern.h>
#include <optional>
#include <string>
#include <vector>

namespace lantern::cli {

struct ViewerState {
    /// The scene being shown. Materials, lights, node transforms, cameras and animations are
    /// edited in place between frames (Renderer::prepare's rule); geometry never changes.
    std::shared_ptr<Scene> scene;
    std::string source;                ///< the path or builtin:NAME it came from
    std::vector<Animation> animations; ///< all of the file's animations
    int animation = -1;                ///< the one playing; -1: all of them
    int root = -1;

    double time = 0.0; ///< seconds
    double fps = 24.0; ///< the arrow keys step one frame of this rate
    bool playing = true;
    double speed = 1.0;

    RenderOptions options; ///< shading switches, background...; cameras and views set per frame
    bool quad = false;
    bool headlight = false; ///< lights follow the camera (options.lightsViewFromWorld)
    int sceneCamera = -1;   ///< the scene camera picked (-1: the scene's default)
    ViewerCamera camera;
    bool fly = false;

    bool showPanel = true;
    bool showHelp = false;
    bool edited = false; ///< lights or materials changed in the panel (not in the command line)

    // Requests the panel makes; the loop carries them out before the next frame.
    bool frameAllRequested = false;
    std::optional<ViewDirection> viewRequested; ///< look from a named view, framing all
    bool screenshotRequested = false;
    bool cameraPicked = false;

    /// The animation's time range: [start, end] of the playing animation(s); end == start when
    /// nothing moves.
    double startTime() const;
    double endTime() const;
    /// Keeps only the chosen animation(s) in the scene.
    void applyAnimationChoice();

    /// The aspect (width / height) of the perspective view in a `width` x `height` window: the
    /// whole window, or its bottom-right quarter in quad view.
    double perspectiveAspect(int width, int height) const;
    /// The first camera move takes the scene's camera over exactly where it is (`aspect`: the
    /// perspective view's); errors are reported and leave the camera as it was.
    void ensureFree(double aspect);
    /// Carries out a scene camera picked and frame all (the panel's and the keys' requests).
    void applyRequests(double aspect);
    /// Headlight: the lights keep the place relative to the camera they had when it was
    /// switched on (options.lightsViewFromWorld set once, reset when off).
    void updateHeadlight(double aspect);
    /// The options of a frame in a `width` x `height` window: these options with the camera
    /// and, in quad view, the four views.
    RenderOptions frameOptions(int width, int height) const;
    /// "phong, blinn, quad, t=1.25 s (paused)": the panel's and the title's summary.
    std::string statusText() const;
};

/// One line of the help overlay (and of docs/viewer.md).
struct KeyHelp {
    const char* keys;
    const char* action;
};
const std::vector<KeyHelp>& viewerKeys();

} // namespace lantern::cli
