// `lantern view SCENE`: the interactive viewer (spec/cli.md, docs/viewer.md): a GLFW window on
// a Vulkan swapchain (lantern::glfw::Window), the scene's animation, an orbit/pan/zoom/fly
// camera, shading switches, quad view, an ImGui panel editing lights and materials live,
// screenshots and scripted runs. Public API only.
#include "common/CliSupport.h"
#include "common/Commands.h"
#include "view/ViewerState.h"
#include "view/ViewerUi.h"

#include <lantern/Window.h>
#include <lantern/glfw/GlfwWindow.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace lantern::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct ViewArgs {
    std::string scene;
    int width = 1280, height = 720;
    int sceneIndex = -1;
    double time = 0.0;
    bool paused = false;
    double fps = 24.0;
    std::string presentMode = "fifo";
    int framesInFlight = 2;
    bool watch = false;
    std::vector<std::string> screenshots;
    int afterFrames = 0;
    std::string screenshotDir = ".";
    bool noPanel = false, showHelp = false, stats = false;
    bool headlight = false, wireframe = false, normals = false;
    std::string background;
    std::uint64_t maxSize = std::uint64_t(1) << 30;
    CameraOptions camera;
    ShadingOptions shading;
    DeviceOptions device;
};

std::atomic<int> g_stopSignal{0};
extern "C" void onViewStopSignal(int signal) {
    g_stopSignal.store(signal);
}

std::string number(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(p * double(v.size() - 1) + 0.5))];
}

// World bounds over the animation (sampled), so framing and clipping hold for every frame.
Bounds animatedBounds(const Scene& scene, int root, double start, double end) {
    Bounds b;
    const int steps = end > start ? 16 : 0;
    for (int i = 0; i <= steps; ++i) {
        const double t = steps ? start + (end - start) * i / steps : start;
        const Bounds bt = computeBounds(scene, evaluatePose(scene, root, t));
        if (!bt.empty()) {
            b.extend(bt.min);
            b.extend(bt.max);
        }
    }
    return b;
}

class Viewer {
public:
    Viewer(const ViewArgs& args, Renderer& renderer, glfw::Window& window)
        : m_args(args), m_renderer(renderer), m_window(window) {}

    int run(std::shared_ptr<Scene> scene);

    // GLFW input (the callbacks forward here).
    void onKey(int key, int action, int mods);
    void onMouseButton(int button, int action, int mods);
    void onCursor(double x, double y);
    void onScroll(double dy);

private:
    bool adopt(std::shared_ptr<Scene> scene);
    void resolveLightingDefaults();
    void ensureFree();
    double perspectiveAspect() const;
    RenderOptions frameOptions() const;
    void advance(double dt);
    void flyMovement(double dt);
    void checkWatch();
    void applyRequests();
    void updateHeadlight();
    int writeCapture(const Image& image);
    std::string renderCommand(const std::string& output) const;
    std::string statusText() const;
    std::string backgroundText() const {
        return m_args.background.empty() ? "0,0,0" : m_args.background;
    }
    void updateTitle();
    void printStats() const;

    const ViewArgs& m_args;
    Renderer& m_renderer;
    glfw::Window& m_window;
    ViewerState m_st;
    PreparedScene m_prepared;
    std::unique_ptr<ViewerUi> m_ui;
    LightingModel m_sceneLighting;

    double m_mouseX = 0.0, m_mouseY = 0.0;
    bool m_haveCursor = false;
    int m_dragButton = -1, m_dragMods = 0;

    int m_presented = 0;
    int m_shotCounter = 0;
    Clock::time_point m_lastPresent{}, m_lastTitle{};
    std::vector<double> m_intervals, m_cpuMs, m_waitMs, m_presentMs, m_gpuMs, m_recentIntervals;

    fs::file_time_type m_loadedTime{}, m_seenTime{};
    std::uintmax_t m_loadedSize = 0, m_seenSize = 0;
    Clock::time_point m_seenAt{}, m_lastWatch{};
};

Viewer* viewerOf(GLFWwindow* w) {
    return static_cast<Viewer*>(glfwGetWindowUserPointer(w));
}

extern "C" void keyCallback(GLFWwindow* w, int key, int, int action, int mods) {
    viewerOf(w)->onKey(key, action, mods);
}
extern "C" void mouseButtonCallback(GLFWwindow* w, int button, int action, int mods) {
    viewerOf(w)->onMouseButton(button, action, mods);
}
extern "C" void cursorCallback(GLFWwindow* w, double x, double y) {
    viewerOf(w)->onCursor(x, y);
}
extern "C" void scrollCallback(GLFWwindow* w, double, double dy) {
    viewerOf(w)->onScroll(dy);
}

bool Viewer::adopt(std::shared_ptr<Scene> scene) {
    auto prepared = m_renderer.prepare(scene);
    if (!prepared) {
        report(prepared.error());
        return false;
    }
    m_st.scene = std::move(scene);
    m_prepared = std::move(*prepared);
    m_st.animations = m_st.scene->animations;
    if (m_st.animation >= int(m_st.animations.size())) m_st.animation = -1;
    m_st.applyAnimationChoice();
    if (m_st.sceneCamera >= int(m_st.scene->cameras.size())) {
        m_st.sceneCamera = -1;
        if (!m_st.camera.isFree()) m_st.camera.setBase(CameraSpec{});
    }
    m_st.camera.setBounds(animatedBounds(*m_st.scene, m_st.root, m_st.startTime(), m_st.endTime()));
    resolveLightingDefaults();
    return true;
}

// The scene's own lighting model, resolved into the options so that the panel and the keys
// start from what the scene shows (and the printed command line says it).
void Viewer::resolveLightingDefaults() {
    const Scene& s = *m_st.scene;
    const int root = m_st.root < 0 ? s.defaultRoot : m_st.root;
    m_sceneLighting = LightingModel{};
    if (root >= 0 && root < int(s.roots.size()) && s.roots[std::size_t(root)].lighting)
        m_sceneLighting = *s.roots[std::size_t(root)].lighting;
    RenderOptions& o = m_st.options;
    if (!o.shading) o.shading = m_sceneLighting.shading;
    if (!o.specular) o.specular = m_sceneLighting.specular;
    if (!o.localViewer) o.localViewer = m_sceneLighting.localViewer;
    if (!o.twoSided) o.twoSided = m_sceneLighting.twoSided;
}

double Viewer::perspectiveAspect() const {
    WindowTarget& t = m_window.target();
    const int w = std::max(t.width(), 1), h = std::max(t.height(), 1);
    if (!m_st.quad) return double(w) / double(h);
    const int vw = std::max(w - w / 2, 1), vh = std::max(h - h / 2, 1);
    return double(vw) / double(vh);
}

// The first camera move takes the scene's camera over exactly where it is.
void Viewer::ensureFree() {
    if (m_st.camera.isFree()) return;
    auto placement = resolveCameraPlacement(*m_st.scene, m_st.camera.base(), perspectiveAspect(),
                                            m_st.root, m_st.time);
    if (!placement) {
        report(placement.error());
        return;
    }
    m_st.camera.takeOver(*placement);
}

RenderOptions Viewer::frameOptions() const {
    RenderOptions o = m_st.options;
    WindowTarget& t = m_window.target();
    o.width = std::max(t.width(), 1);
    o.height = std::max(t.height(), 1);
    o.root = m_st.root;
    const CameraSpec spec = m_st.camera.spec(perspectiveAspect());
    o.camera = spec;
    o.views.clear();
    if (m_st.quad) o.views = quadLayout(o.width, o.height, spec);
    return o;
}

void Viewer::onKey(int key, int action, int mods) {
    if (action == GLFW_RELEASE || (m_ui && m_ui->wantsKeyboard())) return;
    const bool repeat = action == GLFW_REPEAT;
    RenderOptions& o = m_st.options;
    const double step = 1.0 / m_st.fps;
    switch (key) {
    case GLFW_KEY_LEFT:
    case GLFW_KEY_RIGHT:
        m_st.playing = false;
        m_st.time += key == GLFW_KEY_RIGHT ? step : -step;
        return;
    default:
        break;
    }
    if (repeat) return;
    switch (key) {
    case GLFW_KEY_ESCAPE:
        glfwSetWindowShouldClose(m_window.handle(), GLFW_TRUE);
        break;
    case GLFW_KEY_SPACE:
        m_st.playing = !m_st.playing;
        break;
    case GLFW_KEY_HOME:
        m_st.time = m_st.startTime();
        break;
    case GLFW_KEY_1:
        o.shading = ShadingMode::Flat;
        break;
    case GLFW_KEY_2:
        o.shading = ShadingMode::Gouraud;
        break;
    case GLFW_KEY_3:
        o.shading = ShadingMode::Phong;
        break;
    case GLFW_KEY_B:
        o.specular =
            o.specular == SpecularModel::Phong ? SpecularModel::Blinn : SpecularModel::Phong;
        break;
    case GLFW_KEY_P:
        ensureFree();
        m_st.camera.setOrthographic(!m_st.camera.orthographic());
        break;
    case GLFW_KEY_L:
        o.localViewer = !o.localViewer.value_or(false);
        break;
    case GLFW_KEY_T:
        o.twoSided = !o.twoSided.value_or(false);
        break;
    case GLFW_KEY_Z:
        o.wireframe = !o.wireframe;
        break;
    case GLFW_KEY_N:
        o.normals = !o.normals;
        break;
    case GLFW_KEY_V:
        m_st.quad = !m_st.quad;
        break;
    case GLFW_KEY_H:
        // Fixed to the camera as it is now, before any motion queued behind this key.
        m_st.headlight = !m_st.headlight;
        updateHeadlight();
        break;
    case GLFW_KEY_F:
        m_st.frameAllRequested = true;
        break;
    case GLFW_KEY_C: {
        const int n = int(m_st.scene->cameras.size());
        m_st.sceneCamera = m_st.camera.isFree() ? 0 : m_st.sceneCamera + 1;
        if (m_st.sceneCamera >= n) m_st.sceneCamera = -1;
        m_st.cameraPicked = true;
        break;
    }
    case GLFW_KEY_TAB:
        ensureFree();
        m_st.fly = !m_st.fly;
        break;
    case GLFW_KEY_F1:
        m_st.showHelp = !m_st.showHelp;
        break;
    case GLFW_KEY_F2:
        m_st.showPanel = !m_st.showPanel;
        break;
    case GLFW_KEY_F12:
        m_st.screenshotRequested = true;
        break;
    default:
        break;
    }
    (void)mods;
}

void Viewer::onMouseButton(int button, int action, int mods) {
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

void Viewer::onCursor(double x, double y) {
    const double dx = x - m_mouseX, dy = y - m_mouseY;
    m_mouseX = x;
    m_mouseY = y;
    m_haveCursor = true;
    if (m_dragButton < 0 || (dx == 0.0 && dy == 0.0)) return;
    ensureFree();
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

void Viewer::onScroll(double dy) {
    if (m_ui && m_ui->wantsMouse()) return;
    ensureFree();
    if (m_st.camera.isFree()) m_st.camera.zoom(dy);
}

void Viewer::flyMovement(double dt) {
    if (!m_st.fly || (m_ui && m_ui->wantsKeyboard())) return;
    GLFWwindow* w = m_window.handle();
    auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0 : 0.0; };
    const glm::dvec3 v{down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                       down(GLFW_KEY_W) - down(GLFW_KEY_S)};
    if (v == glm::dvec3(0.0)) return;
    const double fast = down(GLFW_KEY_LEFT_SHIFT) > 0 || down(GLFW_KEY_RIGHT_SHIFT) > 0 ? 4.0 : 1.0;
    ensureFree();
    m_st.camera.move(v * (0.5 * fast * dt)); // half the scene's radius per second
}

void Viewer::advance(double dt) {
    if (!m_st.playing) return;
    const double t0 = m_st.startTime(), t1 = m_st.endTime();
    if (!(t1 > t0)) return;
    m_st.time += dt * m_st.speed;
    if (m_st.time > t1 || m_st.time < t0)
        m_st.time = t0 + std::fmod(std::max(m_st.time - t0, 0.0), t1 - t0);
}

// --watch: reload once the file has changed and then stayed the same for 0.3 s (so a file
// being written is not read half-way), keeping the camera and the switches.
void Viewer::checkWatch() {
    if (!m_args.watch || m_st.source.rfind("builtin:", 0) == 0) return;
    const auto now = Clock::now();
    if (now - m_lastWatch < std::chrono::milliseconds(100)) return;
    m_lastWatch = now;
    std::error_code ec;
    const auto time = fs::last_write_time(m_st.source, ec);
    if (ec) return;
    const auto size = fs::file_size(m_st.source, ec);
    if (ec) return;
    if (time != m_seenTime || size != m_seenSize) {
        m_seenTime = time;
        m_seenSize = size;
        m_seenAt = now;
        return;
    }
    if ((time == m_loadedTime && size == m_loadedSize) ||
        now - m_seenAt < std::chrono::milliseconds(300))
        return;
    m_loadedTime = time;
    m_loadedSize = size;
    LoadOptions load;
    load.maxBytes = m_args.maxSize;
    load.log = stderrSink(m_args.device.verbose);
    auto scene = loadScene(m_st.source, load);
    if (!scene) {
        std::cerr << "lantern: the file changed but cannot be loaded; still showing the previous "
                     "version\n";
        report(scene.error());
        return;
    }
    if (auto r = m_window.target().waitIdle(); !r) report(r.error());
    if (adopt(std::make_shared<Scene>(std::move(*scene))))
        std::cout << "reloaded: " << m_st.source << std::endl;
}

void Viewer::applyRequests() {
    if (m_st.cameraPicked) {
        m_st.cameraPicked = false;
        CameraSpec spec = m_st.camera.base();
        spec.source =
            m_st.sceneCamera < 0 ? CameraSpec::Source::Automatic : CameraSpec::Source::SceneCamera;
        spec.sceneCamera = m_st.sceneCamera;
        spec.lookAt.reset();
        spec.projection.reset();
        if (auto p = resolveCameraPlacement(*m_st.scene, spec, perspectiveAspect(), m_st.root,
                                            m_st.time)) {
            m_st.camera.setBase(spec);
            m_st.fly = false;
        } else {
            report(p.error());
            m_st.sceneCamera = -1;
        }
    }
    if (m_st.frameAllRequested) {
        m_st.frameAllRequested = false;
        ensureFree();
        if (m_st.camera.isFree()) m_st.camera.frameAll(perspectiveAspect());
    }
    if (!m_st.camera.isFree()) m_st.fly = false;
}

// Headlight: the lights keep the place relative to the camera they had when it was switched on.
void Viewer::updateHeadlight() {
    RenderOptions& o = m_st.options;
    if (!m_st.headlight) {
        o.lightsViewFromWorld.reset();
        return;
    }
    if (o.lightsViewFromWorld) return;
    auto placement = resolveCameraPlacement(*m_st.scene, m_st.camera.spec(perspectiveAspect()),
                                            perspectiveAspect(), m_st.root, m_st.time);
    if (placement)
        o.lightsViewFromWorld = placement->viewFromWorld;
    else
        report(placement.error());
}

std::string Viewer::renderCommand(const std::string& output) const {
    const RenderOptions o = frameOptions();
    std::string s = "lantern render " + m_st.source + " -o " + output;
    s += " --width " + std::to_string(o.width) + " --height " + std::to_string(o.height);
    if (m_st.root >= 0) s += " --scene " + std::to_string(m_st.root);
    s += " --time " + number(m_st.time);
    s += std::string(" --shading ") + toString(o.shading.value_or(ShadingMode::Phong));
    s += std::string(" --specular ") + toString(o.specular.value_or(SpecularModel::Blinn));
    if (o.localViewer.value_or(false)) s += " --local-viewer";
    if (o.twoSided.value_or(false)) s += " --two-sided";
    if (o.clamp) s += " --clamp";
    if (o.glCompat) s += " --gl-compat";
    if (o.msaa > 1) s += " --msaa " + std::to_string(o.msaa);
    s += " --background " + backgroundText(); // the text it was parsed from: the same floats
    if (m_st.quad) s += " --layout quad";
    s += m_st.camera.commandLine(perspectiveAspect());
    return s;
}

int Viewer::writeCapture(const Image& image) {
    std::vector<std::string> paths = m_args.screenshots;
    if (paths.empty()) {
        char name[64];
        std::snprintf(name, sizeof name, "lantern-view-%04d", ++m_shotCounter);
        const fs::path base = fs::path(m_args.screenshotDir) / name;
        paths = {base.string() + ".exr", base.string() + ".png"};
    }
    std::string line = "screenshot:";
    for (const std::string& p : paths) {
        std::error_code ec;
        if (fs::path(p).has_parent_path()) fs::create_directories(fs::path(p).parent_path(), ec);
        if (auto w = writeImage(p, image); !w) return report(w.error());
        line += " " + p;
    }
    std::cout << line << "\n";
    // What reproduces the picture headless; the parts no command-line option can say, noted.
    std::cout << "render: " << renderCommand(paths.front()) << "\n";
    std::vector<std::string> notes;
    const RenderOptions& o = m_st.options;
    if (m_st.edited) notes.push_back("lights or materials were edited in the panel");
    if (o.lightsViewFromWorld) notes.push_back("the lights follow the camera");
    if (o.wireframe || o.normals) notes.push_back("the wireframe/normals overlays are on");
    if (m_st.animation >= 0)
        notes.push_back("only animation " + std::to_string(m_st.animation) + " plays");
    if ((m_sceneLighting.localViewer && !o.localViewer.value_or(false)) ||
        (m_sceneLighting.twoSided && !o.twoSided.value_or(false)))
        notes.push_back("the scene's local viewer or two-sided lighting was switched off");
    for (const std::string& n : notes)
        std::cout << "note: not in the command: " << n << "\n";
    std::cout.flush();
    return kOk;
}

std::string Viewer::statusText() const {
    const RenderOptions& o = m_st.options;
    std::string s = std::string(toString(o.shading.value_or(ShadingMode::Phong))) + ", " +
                    toString(o.specular.value_or(SpecularModel::Blinn)) +
                    (m_st.camera.orthographic() ? ", ortho" : "") + (m_st.fly ? ", fly" : "") +
                    (m_st.quad ? ", quad" : "") + (m_st.headlight ? ", headlight" : "");
    char t[64];
    std::snprintf(t, sizeof t, ", t=%.2f s%s", m_st.time, m_st.playing ? "" : " (paused)");
    return s + t;
}

void Viewer::updateTitle() {
    const auto now = Clock::now();
    if (now - m_lastTitle < std::chrono::milliseconds(500) || m_recentIntervals.empty()) return;
    m_lastTitle = now;
    const double ms = median(m_recentIntervals);
    m_recentIntervals.clear();
    char b[128];
    std::snprintf(b, sizeof b, " - %.1f ms (%.0f fps) - ", ms, ms > 0 ? 1000.0 / ms : 0.0);
    m_window.setTitle("lantern view: " + m_st.source + b + statusText());
}

void Viewer::printStats() const {
    // The first frames compile pipelines; they are left out.
    const std::size_t skip = std::min<std::size_t>(10, m_intervals.size() / 4);
    auto tail = [&](const std::vector<double>& v) {
        return std::vector<double>(v.begin() + std::ptrdiff_t(std::min(skip, v.size())), v.end());
    };
    const WindowTarget& t = m_window.target();
    std::fprintf(
        stderr,
        "lantern: view: %d frames at %dx%d, %s, %u frames in flight, %u swapchain images; "
        "frame time median %.2f ms (p10 %.2f, p90 %.2f); per frame (median): planning and "
        "recording %.2f ms, waiting for the frame slot and image %.2f ms, presenting %.2f ms, "
        "GPU %.2f ms\n",
        m_presented, t.width(), t.height(), toString(t.presentMode()), t.framesInFlight(),
        t.imageCount(), median(tail(m_intervals)), percentile(tail(m_intervals), 0.1),
        percentile(tail(m_intervals), 0.9), median(tail(m_cpuMs)), median(tail(m_waitMs)),
        median(tail(m_presentMs)), median(tail(m_gpuMs)));
}

int Viewer::run(std::shared_ptr<Scene> scene) {
    m_st.source = m_args.scene;
    m_st.root = m_args.sceneIndex;
    m_st.time = m_args.time;
    m_st.fps = m_args.fps;
    m_st.playing = !m_args.paused && m_args.afterFrames == 0;
    m_st.showPanel = !m_args.noPanel;
    m_st.showHelp = m_args.showHelp;
    m_st.headlight = m_args.headlight;
    if (auto r = m_args.shading.apply(m_st.options); !r) return report(r.error());
    RenderOptions cameraOptions;
    if (auto r = m_args.camera.apply(cameraOptions); !r) return report(r.error());
    m_st.quad = m_args.camera.layout == "quad";
    m_st.camera.setBase(cameraOptions.camera);
    if (!m_args.camera.cameras.empty()) m_st.sceneCamera = m_args.camera.cameras.front();
    m_st.options.wireframe = m_args.wireframe;
    m_st.options.normals = m_args.normals;
    // The window shows an opaque background unless told otherwise (premultiplied over black).
    auto background = parseBackground(backgroundText());
    if (!background) return report(background.error());
    m_st.options.background = *background;
    if (!adopt(std::move(scene))) return kFailed;
    if (m_args.watch) {
        std::error_code ec;
        m_loadedTime = m_seenTime = fs::last_write_time(m_st.source, ec);
        m_loadedSize = m_seenSize = fs::file_size(m_st.source, ec);
    }

    GLFWwindow* w = m_window.handle();
    glfwSetWindowUserPointer(w, this);
    glfwSetKeyCallback(w, keyCallback);
    glfwSetMouseButtonCallback(w, mouseButtonCallback);
    glfwSetCursorPosCallback(w, cursorCallback);
    glfwSetScrollCallback(w, scrollCallback);
    auto ui = ViewerUi::create(w, m_window.target()); // chains to the callbacks above
    if (!ui) return report(ui.error());
    m_ui = std::move(*ui);

    struct sigaction sa {};
    sa.sa_handler = onViewStopSignal;
    sa.sa_flags = SA_RESETHAND;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);

    int code = kOk;
    auto last = Clock::now();
    bool captureNext = false;
    while (!m_window.shouldClose() && g_stopSignal.load() == 0) {
        // Wait for the frame slot first, then sample input: the frames-in-flight wait does
        // not age the input that the frame shows.
        if (auto r = m_window.target().waitForFrameSlot(); !r) {
            code = report(r.error());
            break;
        }
        // While minimised this waits for events (waking 4 times a second for --watch and
        // signals) instead of spinning.
        if (!m_window.pollEvents(0.25)) {
            checkWatch();
            last = Clock::now();
            continue;
        }
        const auto now = Clock::now();
        const double dt = std::min(std::chrono::duration<double>(now - last).count(), 0.25);
        last = now;
        flyMovement(dt);
        advance(dt);
        checkWatch();
        applyRequests();
        updateHeadlight();
        if (m_st.screenshotRequested) {
            m_st.screenshotRequested = false;
            captureNext = true;
        }
        const bool scripted = m_args.afterFrames > 0 && m_presented + 1 >= m_args.afterFrames;
        FrameRequest request;
        request.capture = captureNext || (scripted && !m_args.screenshots.empty());
        m_ui->build(m_st, statusText());
        auto frame = m_window.target().render(m_prepared, frameOptions(), m_st.time, request,
                                              m_ui->recorder());
        if (!frame) {
            code = report(frame.error());
            break;
        }
        if (frame->status != FrameStatus::Presented) continue;
        ++m_presented;
        if (m_lastPresent != Clock::time_point{}) {
            const double ms =
                std::chrono::duration<double, std::milli>(now - m_lastPresent).count();
            m_intervals.push_back(ms);
            m_recentIntervals.push_back(ms);
        }
        m_lastPresent = now;
        m_cpuMs.push_back(frame->stats.cpuMs);
        m_waitMs.push_back(frame->stats.waitMs);
        m_presentMs.push_back(frame->presentMs);
        if (frame->stats.gpuMs >= 0) m_gpuMs.push_back(frame->stats.gpuMs);
        if (frame->capture) {
            captureNext = false;
            if (int c = writeCapture(*frame->capture); c != kOk) {
                code = c;
                break;
            }
        }
        updateTitle();
        if (scripted) break;
    }
    if (auto r = m_window.target().waitIdle(); !r && code == kOk) code = report(r.error());
    m_ui.reset();
    if (m_args.stats) printStats();
    if (const int sig = g_stopSignal.load(); sig != 0 && code == kOk) code = 128 + sig;
    if (m_renderer.device().validationEnabled && m_renderer.validationMessageCount() > 0) {
        std::cerr << "lantern: error: the Vulkan validation layer reported "
                  << m_renderer.validationMessageCount() << " messages\n";
        if (code == kOk) code = kFailed;
    }
    return code;
}

int runView(const ViewArgs& a) {
    if (!a.camera.viewports.empty())
        return report(makeError(ErrorCode::Usage,
                                "the viewer sizes its views with the window: use --layout quad",
                                "--viewport"));
    if (a.afterFrames < 0)
        return report(makeError(ErrorCode::Usage, "--after-frames must be >= 0", "--after-frames"));
    if (!a.screenshots.empty() && a.afterFrames == 0)
        return report(
            makeError(ErrorCode::Usage, "--screenshot needs --after-frames N", "--screenshot"));
    if (auto r = checkImagePaths(a.screenshots, "--screenshot"); !r) return report(r.error());
    const auto mode = parsePresentMode(a.presentMode);
    if (!mode)
        return report(
            makeError(ErrorCode::InvalidInput,
                      "unknown present mode \"" + a.presentMode + "\" (fifo, mailbox, immediate)",
                      "--present-mode"));
    if (a.watch && a.scene.rfind("builtin:", 0) == 0)
        std::cerr << "lantern: warning: --watch has no file to watch for " << a.scene << "\n";

    LoadOptions load;
    load.maxBytes = a.maxSize;
    load.log = stderrSink(a.device.verbose);
    auto scene = loadScene(a.scene, load);
    if (!scene) return report(scene.error());
    if (a.sceneIndex < -1 || a.sceneIndex >= int(scene->roots.size()))
        return report(makeError(ErrorCode::InvalidInput,
                                "scene " + std::to_string(a.sceneIndex) +
                                    " does not exist (the file has " +
                                    std::to_string(scene->roots.size()) + " scenes)",
                                "--scene"));
    {
        // The camera options must hold, and name a camera that exists, before a window opens.
        RenderOptions check;
        if (auto r = a.camera.apply(check); !r) return report(r.error());
        if (auto p = resolveCameraPlacement(*scene, check.camera, 1.0, a.sceneIndex, a.time); !p)
            return report(p.error());
    }

    RendererDesc base = a.device.desc();
    base.framesInFlight = a.framesInFlight;
    auto desc = glfw::forPresentation(base);
    if (!desc) return report(desc.error());
    auto renderer = Renderer::create(*desc);
    if (!renderer) return report(renderer.error());
    if (a.device.verbose)
        std::cerr << "lantern: device: " << renderer->device().name << " ("
                  << renderer->device().driver << ")\n";
    glfw::WindowDesc wd;
    wd.width = a.width;
    wd.height = a.height;
    wd.title = "lantern view: " + a.scene;
    wd.presentMode = *mode;
    wd.overlay = true;
    auto window = glfw::Window::create(*renderer, wd);
    if (!window) return report(window.error());
    if (a.device.verbose)
        std::cerr << "lantern: window: " << window->target().width() << "x"
                  << window->target().height() << ", present mode "
                  << toString(window->target().presentMode()) << ", "
                  << window->target().imageCount() << " swapchain images, "
                  << window->target().framesInFlight() << " frames in flight\n";
    Viewer viewer(a, *renderer, *window);
    return viewer.run(std::make_shared<Scene>(std::move(*scene)));
}

} // namespace

Runner addViewCommand(CLI::App& app) {
    auto args = std::make_shared<ViewArgs>();
    CLI::App* cmd = app.add_subcommand(
        "view", "Open a window and play the scene: orbit/pan/zoom/fly, shading keys, a side panel "
                "editing lights and materials (F1 lists the keys)");
    cmd->add_option("scene", args->scene, "glTF/GLB file, or builtin:NAME")->required();
    cmd->add_option("--width", args->width, "Window width")
        ->capture_default_str()
        ->check(CLI::Range(1, 16384));
    cmd->add_option("--height", args->height, "Window height")
        ->capture_default_str()
        ->check(CLI::Range(1, 16384));
    cmd->add_option("--scene", args->sceneIndex, "glTF scene index (default: the file's default)");
    cmd->add_option("--time", args->time, "Animation time to start at, in seconds")
        ->capture_default_str();
    cmd->add_flag("--paused", args->paused, "Start with the animation paused");
    cmd->add_option("--fps", args->fps, "Frame rate the arrow keys step by")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->add_option("--present-mode", args->presentMode,
                    "fifo (vsync, the default), mailbox or immediate (falls back to what the "
                    "display offers)")
        ->capture_default_str();
    cmd->add_option("--frames-in-flight", args->framesInFlight,
                    "Frames the CPU may be ahead of the GPU (1-4; 2: double buffering)")
        ->capture_default_str()
        ->check(CLI::Range(1, 4));
    cmd->add_flag("--watch", args->watch,
                  "Reload the file when it changes on disk, keeping the camera");
    cmd->add_option(
        "--screenshot", args->screenshots,
        "With --after-frames: write the picture to PATH (.exr or .png; repeatable) and exit");
    cmd->add_option("--after-frames", args->afterFrames,
                    "Exit after N frames (writing the --screenshot files of frame N)");
    cmd->add_option("--screenshot-dir", args->screenshotDir,
                    "Folder for F12 screenshots (lantern-view-NNNN.exr and .png)")
        ->capture_default_str();
    cmd->add_option("--background", args->background,
                    "Background colour R,G,B or R,G,B,A, linear (default: opaque black)");
    cmd->add_flag("--no-panel", args->noPanel, "Start with the side panel hidden (F2 shows it)");
    cmd->add_flag("--show-help", args->showHelp, "Start with the key help shown (F1)");
    cmd->add_flag("--headlight", args->headlight, "Start with the lights following the camera (H)");
    cmd->add_flag("--wireframe", args->wireframe, "Start with the wireframe overlay on (Z)");
    cmd->add_flag("--normals", args->normals, "Start with the normals displayed (N)");
    cmd->add_flag("--stats", args->stats, "Print frame-time statistics when the viewer exits");
    cmd->add_option("--max-size", args->maxSize, "Largest file, buffer or image accepted, in bytes")
        ->capture_default_str();
    args->camera.add(*cmd);
    args->shading.add(*cmd);
    args->device.add(*cmd);
    return [args, cmd]() {
        if (!cmd->parsed()) return -1;
        return runView(*args);
    };
}

} // namespace lantern::cli
