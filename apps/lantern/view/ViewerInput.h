// ViewerInput.h: the viewer's window input: GLFW's key, mouse-button, cursor and scroll events
// and the fly keys held down, turned into changes of the ViewerState (camera moves, switches,
// requests). The panel takes the mouse and keyboard first when it wants them.
#pragma once

#include "view/ViewerState.h"

#include <lantern/glfw/GlfwWindow.h>

namespace lantern::cli {

class ViewerUi;

class ViewerInput {
public:
    ViewerInput(ViewerState& state, glfw::Window& window) : m_st(state), m_window(window) {}
    ViewerInput(const ViewerInput&) = delete;
    ViewerInput& operator=(const ViewerInput&) = delete;

    /// Routes the window's key, mouse-button, cursor and scroll events here (through the
    /// window's user pointer). Call before the panel installs its own callbacks, which chain
    /// to these.
    void install();
    /// The panel whose wants come first; null: none (before it exists and after it is gone).
    void setUi(const ViewerUi* ui) { m_ui = ui; }
    /// Fly mode's movement from the keys held down (W A S D, Q E, shift), over `dt` seconds.
    void flyMovement(double dt);

    void onKey(int key, int action, int mods);
    void onMouseButton(int button, int action, int mods);
    void onCursor(double x, double y);
    void onScroll(double dy);

private:
    // The keys pressed (not repeated), by group; each returns false for a key not its own.
    bool playbackKey(int key);
    bool shadingKey(int key);
    bool cameraKey(int key);
    bool viewKey(int key, int mods);
    double perspectiveAspect() const;

    ViewerState& m_st;
    glfw::Window& m_window;
    const ViewerUi* m_ui = nullptr;
    double m_mouseX = 0.0, m_mouseY = 0.0;
    bool m_haveCursor = false;
    int m_dragButton = -1, m_dragMods = 0;
};

} // namespace lantern::cli
