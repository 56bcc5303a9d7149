// The viewer's keys and mouse (docs/viewer.md): orbit, pan, zoom and fly; playback, shading and
// view switches; help, panel and screenshot keys.
#include "view/ViewerInput.h"

#include "view/ViewerUi.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <algorithm>

namespace lantern::cli {
namespace {

ViewerInput* inputOf(GLFWwindow* w) {
    return static_cast<ViewerInput*>(glfwGetWindowUserPointer(w));
}

extern "C" void keyCallback(GLFWwindow* w, int key, int, int action, int mods) {
    inputOf(w)->onKey(key, action, mods);
}
extern "C" void mouseButtonCallback(GLFWwindow* w, int button, int action, int mods) {
    inputOf(w)->onMouseButton(button, action, mods);
}
extern "C" void cursorCallback(GLFWwindow* w, double x, double y) {
    inputOf(w)->onCursor(x, y);
}
extern "C" void scrollCallback(GLFWwindow* w, double, double dy) {
    inputOf(w)->onScroll(dy);
}

} // namespace

void ViewerInput::install() {
    GLFWwindow* w = m_window.handle();
    glfwSetWindowUserPointer(w, this);
    glfwSetKeyCallback(w, keyCallback);
    glfwSetMouseButtonCallback(w, mouseButtonCallback);
    glfwSetCursorPosCallback(w, cursorCallback);
    glfwSetScrollCallback(w, scrollCallback);
}

double ViewerInput::perspectiveAspect() const {
    WindowTarget& t = m_window.target();
    return m_st.perspectiveAspect(t.width(), t.height());
}

void ViewerInput::onKey(int key, int action, int mods) {
    if (action == GLFW_RELEASE || (m_ui && m_ui->wantsKeyboard())) return;
    if (key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT) { // these repeat while held
        const double step = 1.0 / m_st.fps;
        m_st.playing = false;
        m_st.time += key == GLFW_KEY_RIGHT ? step : -step;
        return;
    }
    if (action == GLFW_REPEAT) return;
    if (!playbackKey(key) && !shadingKey(key) && !viewKey(key, mods)) cameraKey(key);
}

// Blender's numeric keypad: 1 front, 3 right, 7 top, with Ctrl the opposite side; 9 the
// isometric corner, 0 the automatic three-quarter view.
bool ViewerInput::viewKey(int key, int mods) {
    const bool opposite = mods & GLFW_MOD_CONTROL;
    std::optional<ViewDirection> v;
    switch (key) {
    case GLFW_KEY_KP_1: v = opposite ? ViewDirection::Back : ViewDirection::Front; break;
    case GLFW_KEY_KP_3: v = opposite ? ViewDirection::Left : ViewDirection::Right; break;
    case GLFW_KEY_KP_7: v = opposite ? ViewDirection::Bottom : ViewDirection::Top; break;
    case GLFW_KEY_KP_9: v = ViewDirection::Iso; break;
    case GLFW_KEY_KP_0: v = ViewDirection::ThreeQuarter; break;
    default: return false;
    }
    m_st.viewRequested = v;
    return true;
}

bool ViewerInput::playbackKey(int key) {
    switch (key) {
    case GLFW_KEY_ESCAPE:
        glfwSetWindowShouldClose(m_window.handle(), GLFW_TRUE);
        return true;
    case GLFW_KEY_SPACE:
        m_st.playing = !m_st.playing;
        return true;
    case GLFW_KEY_HOME:
        m_st.time = m_st.startTime();
        return true;
    case GLFW_KEY_F1:
        m_st.showHelp = !m_st.showHelp;
        return true;
    case GLFW_KEY_F2:
        m_st.showPanel = !m_st.showPanel;
        return true;
    case GLFW_KEY_F12:
        m_st.screenshotRequested = true;
        return true;
    default:
        return false;
    }
}

bool ViewerInput::shadingKey(int key) {
    RenderOptions& o = m_st.options;
    switch (key) {
    case GLFW_KEY_1:
        o.shading = ShadingMode::Flat;
        return true;
    case GLFW_KEY_2:
        o.shading = ShadingMode::Gouraud;
        return true;
    case GLFW_KEY_3:
        o.shading = ShadingMode::Phong;
        return true;
    case GLFW_KEY_B:
        o.specular =
            o.specular == SpecularModel::Phong ? SpecularModel::Blinn : SpecularModel::Phong;
        return true;
    case GLFW_KEY_L:
        o.localViewer = !o.localViewer.value_or(false);
        return true;
    case GLFW_KEY_T:
        o.twoSided = !o.twoSided.value_or(false);
        return true;
    case GLFW_KEY_O: {  // sorted -> exact -> weighted -> sorted
        const TransparencyMethod now =
            o.transparency.value_or(o.glCompat ? TransparencyMethod::Sorted : TransparencyMethod::Exact);
        o.transparency = now == TransparencyMethod::Sorted  ? TransparencyMethod::Exact
                         : now == TransparencyMethod::Exact ? TransparencyMethod::Weighted
                                                            : TransparencyMethod::Sorted;
        return true;
    }
    case GLFW_KEY_Z:
        o.wireframe = !o.wireframe;
        return true;
    case GLFW_KEY_N:
        o.normals = !o.normals;
        return true;
    default:
        return false;
    }
}

bool ViewerInput::cameraKey(int key) {
    switch (key) {
    case GLFW_KEY_P:
        m_st.ensureFree(perspectiveAspect());
        m_st.camera.setOrthographic(!m_st.camera.orthographic());
        return true;
    case GLFW_KEY_V:
        m_st.quad = !m_st.quad;
        return true;
    case GLFW_KEY_H:
        // Fixed to the camera as it is now, before any motion queued behind this key.
        m_st.headlight = !m_st.headlight;
        m_st.updateHeadlight(perspectiveAspect());
        return true;
    case GLFW_KEY_F:
        m_st.frameAllRequested = true;
        return true;
    case GLFW_KEY_C: {
        const int n = int(m_st.scene->cameras.size());
        m_st.sceneCamera = m_st.camera.isFree() ? 0 : m_st.sceneCamera + 1;
        if (m_st.sceneCamera >= n) m_st.sceneCamera = -1;
        m_st.cameraPicked = true;
        return true;
    }
    case GLFW_KEY_TAB:
        m_st.ensureFree(perspectiveAspect());
        m_st.fly = !m_st.fly;
        return true;
    default:
        return false;
    }
}

void ViewerInput::onMouseButton(int button, int action, int mods) {
    if (action == GLFW_PRESS) {
        if (m_ui && m_ui->wantsMouse()) return;
        m_dragButton = button;
        m_dragMods = mods;
        // The drag starts where the last motion event left the pointer: querying the server
        // instead would return where it is by now, after motion still queued behind this event.
        if (!m_haveCursor) glfwGetCursorPos(m_window.handle(), &m_mouseX, &m_mouseY);
    } else if (button == m_dragButton) {
        m_dragButton = -1;
    }
}

void ViewerInput::onCursor(double x, double y) {
    const double dx = x - m_mouseX, dy = y - m_mouseY;
    m_mouseX = x;
    m_mouseY = y;
    m_haveCursor = true;
    if (m_dragButton < 0 || (dx == 0.0 && dy == 0.0)) return;
    m_st.ensureFree(perspectiveAspect());
    if (!m_st.camera.isFree()) return;
    const double viewHeight = std::max(m_window.target().height() / (m_st.quad ? 2 : 1), 1);
    const bool shift = m_dragMods & GLFW_MOD_SHIFT, ctrl = m_dragMods & GLFW_MOD_CONTROL;
    if (m_dragButton == GLFW_MOUSE_BUTTON_RIGHT || (m_dragButton == GLFW_MOUSE_BUTTON_LEFT && ctrl))
        m_st.camera.zoom(-dy * 0.05);
    else if (m_dragButton == GLFW_MOUSE_BUTTON_MIDDLE || shift)
        m_st.camera.pan(dx, dy, viewHeight);
    else if (m_st.fly)
        m_st.camera.look(dx, dy);
    else
        m_st.camera.orbit(dx, dy);
}

void ViewerInput::onScroll(double dy) {
    if (m_ui && m_ui->wantsMouse()) return;
    m_st.ensureFree(perspectiveAspect());
    if (m_st.camera.isFree()) m_st.camera.zoom(dy);
}

void ViewerInput::flyMovement(double dt) {
    if (!m_st.fly || (m_ui && m_ui->wantsKeyboard())) return;
    GLFWwindow* w = m_window.handle();
    auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0 : 0.0; };
    const glm::dvec3 v{down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                       down(GLFW_KEY_W) - down(GLFW_KEY_S)};
    if (v == glm::dvec3(0.0)) return;
    const double fast = down(GLFW_KEY_LEFT_SHIFT) > 0 || down(GLFW_KEY_RIGHT_SHIFT) > 0 ? 4.0 : 1.0;
    m_st.ensureFree(perspectiveAspect());
    m_st.camera.move(v * (0.5 * fast * dt)); // half the scene's radius per second
}

} // namespace lantern::cli
