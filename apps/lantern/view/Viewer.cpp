// The viewer's frame loop (Viewer.h): set-up from the options, one turn per frame, the scene's
// reloads, screenshots with the `lantern render` command that reproduces them, and the end.
#include "view/Viewer.h"

#include "common/CliSupport.h"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>

namespace lantern::cli {
namespace {

namespace fs = std::filesystem;

std::string number(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
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

} // namespace

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
    if (auto why = nothingToDraw(*m_st.scene, m_st.root))
        std::cerr << "lantern: warning: " << m_st.source << ": nothing to draw (" << *why
                  << "); the window shows the background\n";
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
    return m_st.perspectiveAspect(t.width(), t.height());
}

RenderOptions Viewer::frameOptions() const {
    WindowTarget& t = m_window.target();
    return m_st.frameOptions(t.width(), t.height());
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
    const LoadOptions load = m_args.file.load(stderrSink(m_args.device.verbose));
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
    if (o.shadows.all) s += " --shadows";
    const ShadowOptions defaults;
    if (o.shadows.filter != defaults.filter)
        s += std::string(" --shadow-filter ") + shadowFilterName(o.shadows.filter);
    if (o.shadows.cascades != defaults.cascades)
        s += " --shadow-cascades " + std::to_string(o.shadows.cascades);
    if (o.shadows.filter == ShadowFilter::Pcss && o.shadows.lightRadius != defaults.lightRadius)
        s += " --shadow-light-radius " + number(o.shadows.lightRadius);
    if (o.shadows.filter == ShadowFilter::Pcss && o.shadows.sunRadius != defaults.sunRadius)
        s += " --shadow-sun-radius " + number(o.shadows.sunRadius);
    if (o.shadows.kernel != defaults.kernel) s += " --shadow-kernel " + std::to_string(o.shadows.kernel);
    if (o.shadows.resolution != defaults.resolution)
        s += " --shadow-resolution " + std::to_string(o.shadows.resolution);
    if (o.shadows.slopeBias != defaults.slopeBias) s += " --shadow-bias " + number(o.shadows.slopeBias);
    if (o.shadows.normalOffset != defaults.normalOffset)
        s += " --shadow-normal-offset " + number(o.shadows.normalOffset);
    if (o.transparency) s += std::string(" --transparency ") + transparencyName(*o.transparency);
    if (!o.instancing) s += " --no-instancing";
    if (!o.culling) s += " --no-culling";
    if (o.lodError > 0.0) s += " --lod-error " + number(o.lodError);
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

void Viewer::updateTitle() {
    const std::optional<double> ms = m_stats.recentMs();
    if (!ms) return;
    char b[128];
    std::snprintf(b, sizeof b, " - %.1f ms (%.0f fps) - ", *ms, *ms > 0 ? 1000.0 / *ms : 0.0);
    m_window.setTitle("lantern view: " + m_st.source + b + m_st.statusText());
}

int Viewer::run(std::shared_ptr<Scene> scene) {
    if (const int started = start(std::move(scene)); started != kOk) return started;
    installStopHandlers();
    m_last = Clock::now();
    int code = kOk;
    while (!m_window.shouldClose() && stopSignal() == 0)
        if (const std::optional<int> end = runFrame()) {
            code = *end;
            break;
        }
    return finish(code);
}

// The state from the options, the scene, the input and the panel.
int Viewer::start(std::shared_ptr<Scene> scene) {
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

    m_input.install();
    auto ui = ViewerUi::create(m_window.handle(), m_window.target()); // chains to m_input's
    if (!ui) return report(ui.error());
    m_ui = std::move(*ui);
    m_input.setUi(m_ui.get());
    return kOk;
}

// One turn of the loop: nothing to go on, or the exit status that ends it.
std::optional<int> Viewer::runFrame() {
    // Wait for the frame slot first, then sample input: the frames-in-flight wait does
    // not age the input that the frame shows.
    if (auto r = m_window.target().waitForFrameSlot(); !r) return report(r.error());
    // While minimised this waits for events (waking 4 times a second for --watch and
    // signals) instead of spinning.
    if (!m_window.pollEvents(0.25)) {
        checkWatch();
        m_last = Clock::now();
        return std::nullopt;
    }
    const auto now = Clock::now();
    const double dt = std::min(std::chrono::duration<double>(now - m_last).count(), 0.25);
    m_last = now;
    m_input.flyMovement(dt);
    advance(dt);
    checkWatch();
    m_st.applyRequests(perspectiveAspect());
    m_st.updateHeadlight(perspectiveAspect());
    if (m_st.screenshotRequested) {
        m_st.screenshotRequested = false;
        m_captureNext = true;
    }
    const bool scripted = m_args.afterFrames > 0 && m_stats.presented() + 1 >= m_args.afterFrames;
    FrameRequest request;
    request.capture = m_captureNext || (scripted && !m_args.screenshots.empty());
    m_ui->build(m_st, m_st.statusText());
    RenderOptions options = frameOptions();
    options.lodError = m_lod.bound(m_st.camera.commandLine(perspectiveAspect()), options.lodError,
                                   m_lastFrameMs, now);
    auto frame = m_window.target().render(m_prepared, options, m_st.time, request, m_ui->recorder());
    m_lastFrameMs = 1000.0 * std::chrono::duration<double>(Clock::now() - now).count();
    if (!frame) return report(frame.error());
    if (frame->status != FrameStatus::Presented) return std::nullopt;
    m_stats.add(now, *frame);
    if (frame->capture) {
        m_captureNext = false;
        // A frame that held NaN or Inf (shown with those values as 0) is never saved: as
        // `lantern render`, the screenshot is refused; a scripted run exits 3.
        if (frame->stats.nonFinite > 0) {
            std::cerr << "lantern: error: screenshot not written: the frame holds "
                      << frame->stats.nonFinite
                      << " non-finite values (shown as 0); this command names the object drawn "
                         "there: "
                      << renderCommand("out/nonfinite.exr") << "\n";
            if (scripted) return kFailed;
        } else if (int c = writeCapture(*frame->capture); c != kOk) {
            return c;
        }
    }
    updateTitle();
    if (scripted) return kOk;
    return std::nullopt;
}

int Viewer::finish(int code) {
    if (auto r = m_window.target().waitIdle(); !r && code == kOk) code = report(r.error());
    m_input.setUi(nullptr);
    m_ui.reset();
    if (m_args.stats) {
        m_stats.print(m_window.target());
        m_lod.print();
    }
    if (const int sig = stopSignal(); sig != 0 && code == kOk) code = 128 + sig;
    if (m_renderer.device().validationEnabled && m_renderer.validationMessageCount() > 0) {
        std::cerr << "lantern: error: the Vulkan validation layer reported "
                  << m_renderer.validationMessageCount() << " messages\n";
        if (code == kOk) code = kFailed;
    }
    return code;
}

} // namespace lantern::cli
