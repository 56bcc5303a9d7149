// ViewerUi.h: the viewer's Dear ImGui layer (Debian's libimgui with its GLFW and Vulkan
// backends): set up on a WindowTarget's overlay render pass, the side panel that edits lights
// and materials live and picks cameras and animations, and the help overlay.
#pragma once

#include "view/ViewerState.h"

#include <lantern/Window.h>
#include <memory>

struct GLFWwindow;

namespace lantern::cli {

class ViewerUi {
public:
    /// Initialises ImGui for `window` (installing its GLFW callbacks after the viewer's, which
    /// it chains to) and uploads its font through `target`.
    static Result<std::unique_ptr<ViewerUi>> create(GLFWwindow* window, WindowTarget& target);
    /// The target must be idle (WindowTarget::waitIdle) before this runs.
    ~ViewerUi();

    /// Builds this frame's panel and help overlay from `state` (editing it), ready to record.
    void build(ViewerState& state, const std::string& status);
    /// Records the built frame into the overlay render pass.
    OverlayRecorder recorder() const;

    bool wantsMouse() const;
    bool wantsKeyboard() const;

private:
    ViewerUi() = default;
    bool m_vulkan = false, m_glfw = false;
};

} // namespace lantern::cli
