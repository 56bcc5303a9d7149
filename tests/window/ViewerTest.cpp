// `lantern view` for real: each test starts its own Xvfb, runs the viewer on it (validation on)
// and drives it with xdotool as a user would. Every screenshot the viewer takes is compared
// with `lantern render` run on the command line the viewer prints for it (the same engine, so
// the very same floats), pictures are checked to change when a key says they should, and the
// X server's own copy of the window is compared with the viewer's screenshot. Each viewer must
// exit with status 0 and without a validation message.
#include "GltfTestBuilder.h"
#include "TestSupport.h"
#include "XServer.h"

#include <lantern/Lantern.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

namespace lantern::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string readText(const fs::path& p) {
    std::ifstream in(p);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> linesStartingWith(const std::string& text, const std::string& prefix) {
    std::vector<std::string> out;
    std::stringstream ss(text);
    std::string line;
    while (std::getline(ss, line))
        if (line.rfind(prefix, 0) == 0) out.push_back(line.substr(prefix.size()));
    return out;
}

std::vector<std::string> words(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream ss(text);
    std::string w;
    while (ss >> w) out.push_back(w);
    return out;
}

// Pixels whose colour differs by more than 1/255 in some channel.
std::size_t differingPixels(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) return a.pixelCount();
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            if (std::abs(a.rgba[i * 4 + std::size_t(c)] - b.rgba[i * 4 + std::size_t(c)]) > 1.0f / 255.0f) {
                ++n;
                break;
            }
    return n;
}

Image readImage(const fs::path& p) {
    auto image = readExr(p);
    EXPECT_TRUE(image) << (image ? "" : image.error().describe());
    return image ? std::move(*image) : Image{};
}

// A `lantern view` process on the test's X server.
class ViewerRun {
public:
    ViewerRun(const XServer& server, const fs::path& dir) : m_server(server), m_dir(dir) {}

    ::testing::AssertionResult start(const std::vector<std::string>& args) {
        std::vector<std::string> full{cliPath().string(), "view"};
        full.insert(full.end(), args.begin(), args.end());
        const auto validation = validationFlag();
        full.insert(full.end(), validation.begin(), validation.end());
        full.insert(full.end(), {"--screenshot-dir", m_dir.string()});
        m_process = ChildProcess::start(full, m_server.environment(), m_dir / "viewer.out",
                                        m_dir / "viewer.err");
        if (!m_process) return ::testing::AssertionFailure() << "cannot start the viewer";
        const auto id = m_server.waitForWindow("^lantern view", 90s);
        if (!id)
            return ::testing::AssertionFailure()
                   << "no viewer window appeared; stderr: " << readText(m_dir / "viewer.err");
        m_window = *id;
        if (!m_server.xdotool({"windowfocus", "--sync", m_window}))
            return ::testing::AssertionFailure() << "xdotool cannot focus the window";
        return ::testing::AssertionSuccess();
    }

    const std::string& window() const { return m_window; }
    ChildProcess& process() { return *m_process; }

    /// Presses keys (xdotool names) in order.
    bool keys(const std::vector<std::string>& names) {
        std::vector<std::string> args{"key", "--delay", "30"};
        args.insert(args.end(), names.begin(), names.end());
        return m_server.xdotool(args).has_value();
    }

    /// Presses F12 after `before` and waits for the screenshot and its `render:` line.
    /// Returns the EXR path and the render command line.
    std::optional<std::pair<fs::path, std::string>> screenshot(const std::vector<std::string>& before = {}) {
        ++m_shots;
        char name[64];
        std::snprintf(name, sizeof name, "lantern-view-%04d", m_shots);
        const fs::path exr = m_dir / (std::string(name) + ".exr");
        std::vector<std::string> k = before;
        k.push_back("F12");
        if (!keys(k)) return std::nullopt;
        const auto deadline = std::chrono::steady_clock::now() + 90s;
        while (std::chrono::steady_clock::now() < deadline) {
            const auto lines = linesStartingWith(readText(m_dir / "viewer.out"), "render: ");
            if (int(lines.size()) >= m_shots && fs::exists(exr)) return std::make_pair(exr, lines[std::size_t(m_shots - 1)]);
            if (!m_process->running()) break;
            std::this_thread::sleep_for(50ms);
        }
        return std::nullopt;
    }

    /// Escape, then the exit status (nullopt when the viewer did not exit within 30 s).
    std::optional<int> quit() {
        keys({"Escape"});
        return m_process->wait(30000ms);
    }

    std::string out() const { return readText(m_dir / "viewer.out"); }
    std::string err() const { return readText(m_dir / "viewer.err"); }

private:
    const XServer& m_server;
    fs::path m_dir;
    std::unique_ptr<ChildProcess> m_process;
    std::string m_window;
    int m_shots = 0;
};

class ViewerTest : public ::testing::Test {
protected:
    void SetUp() override {
        LANTERN_SKIP_IF_MISSING(XServer::missing());
        LANTERN_SKIP_IF_MISSING(missingProgram("xdotool", "xdotool"));
        LANTERN_SKIP_IF_MISSING(missingVulkanDevice());
        m_dir = testOutputDir();
        std::string error;
        m_server = XServer::start(m_dir, error);
        // Xvfb is there but this machine gives it no display (no /tmp/.X11-unix, say).
        if (!m_server) GTEST_SKIP() << "no X display could be started here: " << error;
    }

    // Runs the `lantern render` command a screenshot printed, into expected-N.exr, and checks
    // the viewer's picture against it: the same engine, options and camera give the same floats.
    void expectSameAsRender(const fs::path& shot, const std::string& command) {
        SCOPED_TRACE(command);
        auto args = words(command);
        ASSERT_GE(args.size(), 3u);
        ASSERT_EQ(args[0], "lantern");
        std::vector<std::string> cli(args.begin() + 1, args.end());
        const fs::path expectedPath = m_dir / ("expected-" + shot.filename().string());
        auto o = std::find(cli.begin(), cli.end(), "-o");
        ASSERT_NE(o, cli.end());
        *(o + 1) = expectedPath.string();
        const ProcessResult r = runLantern(cli);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Image actual = readImage(shot), expected = readImage(expectedPath);
        EXPECT_EQ(maxAbsDifference(actual, expected), 0.0f)
            << saveComparison(actual, expected, "viewer-" + shot.stem().string());
    }

    void expectCleanExit(ViewerRun& viewer) {
        const auto code = viewer.quit();
        ASSERT_TRUE(code) << "the viewer did not exit after Escape";
        EXPECT_EQ(*code, 0) << viewer.err();
        EXPECT_EQ(viewer.err().find("validation"), std::string::npos) << viewer.err();
    }

    fs::path m_dir;
    std::unique_ptr<XServer> m_server;
};

TEST_F(ViewerTest, ShadingAndProjectionKeysChangeThePictureAsRenderWould) {
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({"builtin:spheres", "--width", "200", "--height", "120", "--no-panel"}));
    struct Step {
        std::vector<std::string> keys;
        const char* expect;  // a word the printed render command must hold
        const char* why;
    };
    const Step steps[] = {
        {{}, "--shading phong", "the scene as `lantern render` shows it"},
        {{"1"}, "--shading flat", "1: flat shading"},
        {{"2"}, "--shading gouraud", "2: gouraud shading"},
        {{"3", "b"}, "--specular phong", "3 then B: phong shading with Phong's specular term"},
        {{"p"}, "--ortho", "P: orthographic projection (takes the scene camera over)"},
        {{"p"}, "--perspective", "P again: back to perspective"},
    };
    std::vector<Image> shots;
    for (const Step& s : steps) {
        SCOPED_TRACE(s.why);
        auto shot = viewer.screenshot(s.keys);
        ASSERT_TRUE(shot) << viewer.err();
        EXPECT_NE(shot->second.find(s.expect), std::string::npos) << shot->second;
        expectSameAsRender(shot->first, shot->second);
        shots.push_back(readImage(shot->first));
        if (shots.size() > 1) {
            // Each switch changes a visible part of the picture.
            EXPECT_GT(differingPixels(shots.back(), shots[shots.size() - 2]), std::size_t(200));
        }
    }
    // The window shows exactly the last screenshot (sRGB-encoded by the blit).
    int difference = 256;
    for (int i = 0; i < 50 && difference > 1; ++i) {
        if (auto x = m_server->grab(std::stoul(viewer.window()))) difference = maxDifference(*x, shots.back());
        std::this_thread::sleep_for(40ms);
    }
    EXPECT_LE(difference, 1);
    expectCleanExit(viewer);
}

// Two blended squares crossing each other (a glTF written here): where they cross, sorting by
// object is wrong, so the three methods give three pictures.
fs::path crossingSquares(const fs::path& dir) {
    lantern::test::GltfBuilder g;
    const int positions = g.addFloats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3");
    const int normals = g.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int indices = g.addIndices({0, 1, 2, 0, 2, 3});
    const double colours[2][4] = {{0.9, 0.2, 0.1, 0.5}, {0.1, 0.3, 0.9, 0.5}};
    for (int i = 0; i < 2; ++i) {
        g.doc["materials"].push_back({{"pbrMetallicRoughness",
                                       {{"baseColorFactor", colours[i]}, {"metallicFactor", 0.0}}},
                                      {"alphaMode", "BLEND"}, {"doubleSided", true}});
        const int mesh = g.addMesh({{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}},
                                    {"indices", indices}, {"material", i}});
        const double angle = i == 0 ? 0.6 : -0.6;  // about Y, through the origin
        g.addNode({{"mesh", mesh}, {"rotation", {0.0, std::sin(angle / 2), 0.0, std::cos(angle / 2)}}});
    }
    return g.write(dir, "crossing");
}

// O cycles the transparency method live (exact, the default, then weighted, then sorted); each
// screenshot is what `lantern render` with the printed --transparency gives, and the three differ.
TEST_F(ViewerTest, TransparencyKeyCyclesTheMethodsAsRenderWould) {
    const fs::path file = crossingSquares(m_dir);
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({file.string(), "--width", "200", "--height", "120", "--no-panel"}));
    const std::pair<std::vector<std::string>, const char*> steps[] = {
        {{}, nullptr}, {{"o"}, "--transparency weighted"}, {{"o"}, "--transparency sorted"},
        {{"o"}, "--transparency exact"}};
    std::vector<Image> shots;
    for (const auto& [keys, expect] : steps) {
        auto shot = viewer.screenshot(keys);
        ASSERT_TRUE(shot) << viewer.err();
        if (expect) {
            EXPECT_NE(shot->second.find(expect), std::string::npos) << shot->second;
        }
        expectSameAsRender(shot->first, shot->second);
        shots.push_back(readImage(shot->first));
    }
    EXPECT_EQ(maxAbsDifference(shots[0], shots[3]), 0.0f) << "exact, then exact again";
    EXPECT_GT(differingPixels(shots[0], shots[1]), std::size_t(100)) << "weighted differs from exact";
    EXPECT_GT(differingPixels(shots[0], shots[2]), std::size_t(100)) << "sorted differs from exact";
    expectCleanExit(viewer);
}

TEST_F(ViewerTest, OrbitPanZoomAndQuadViewMoveTheCameraAsPrinted) {
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({"builtin:spheres", "--width", "200", "--height", "140", "--no-panel"}));
    const std::string w = viewer.window();
    auto before = viewer.screenshot();
    ASSERT_TRUE(before);
    // Left drag orbits, middle drag pans, the wheel zooms (xdotool: button 4 is wheel up).
    ASSERT_TRUE(m_server->xdotool({"mousemove", "--window", w, "60", "70", "mousedown", "1",
                                   "mousemove", "--window", w, "110", "80", "mouseup", "1"}));
    ASSERT_TRUE(m_server->xdotool({"mousemove", "--window", w, "100", "70", "mousedown", "2",
                                   "mousemove", "--window", w, "90", "60", "mouseup", "2"}));
    ASSERT_TRUE(m_server->xdotool({"click", "4"}));
    auto moved = viewer.screenshot();
    ASSERT_TRUE(moved);
    EXPECT_NE(moved->second.find("--look-at"), std::string::npos) << moved->second;
    expectSameAsRender(moved->first, moved->second);
    EXPECT_GT(differingPixels(readImage(before->first), readImage(moved->first)), std::size_t(1000));
    // V: quad view; the perspective quarter keeps the moved camera.
    auto quad = viewer.screenshot({"v"});
    ASSERT_TRUE(quad);
    EXPECT_NE(quad->second.find("--layout quad"), std::string::npos) << quad->second;
    expectSameAsRender(quad->first, quad->second);
    // F frames everything again.
    auto framed = viewer.screenshot({"v", "f"});
    ASSERT_TRUE(framed);
    expectSameAsRender(framed->first, framed->second);
    // Tab: fly mode; holding W moves the eye forward.
    ASSERT_TRUE(viewer.keys({"Tab"}));
    ASSERT_TRUE(m_server->xdotool({"keydown", "w"}));
    std::this_thread::sleep_for(400ms);
    ASSERT_TRUE(m_server->xdotool({"keyup", "w"}));
    auto flown = viewer.screenshot();
    ASSERT_TRUE(flown);
    expectSameAsRender(flown->first, flown->second);
    EXPECT_GT(differingPixels(readImage(framed->first), readImage(flown->first)), std::size_t(500));
    // C: back to the scene's camera 0, exactly as render --camera 0 shows it.
    auto sceneCamera = viewer.screenshot({"c"});
    ASSERT_TRUE(sceneCamera);
    EXPECT_NE(sceneCamera->second.find("--camera 0"), std::string::npos) << sceneCamera->second;
    expectSameAsRender(sceneCamera->first, sceneCamera->second);
    EXPECT_EQ(maxAbsDifference(readImage(sceneCamera->first), readImage(before->first)), 0.0f);
    expectCleanExit(viewer);
}

TEST_F(ViewerTest, AnimationPlaysPausesAndStepsByFrames) {
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({"builtin:spheres-animated", "--width", "160", "--height", "100",
                              "--no-panel", "--paused", "--fps", "10"}));
    auto timeOf = [](const std::string& command) {
        const auto at = command.find("--time ");
        return at == std::string::npos ? -1.0 : std::stod(command.substr(at + 7));
    };
    auto start = viewer.screenshot();
    ASSERT_TRUE(start);
    EXPECT_EQ(timeOf(start->second), 0.0);
    // Right, Right: two frames of 1/10 s forward.
    auto stepped = viewer.screenshot({"Right", "Right"});
    ASSERT_TRUE(stepped);
    EXPECT_NEAR(timeOf(stepped->second), 0.2, 1e-12);
    expectSameAsRender(stepped->first, stepped->second);
    EXPECT_GT(differingPixels(readImage(start->first), readImage(stepped->first)), std::size_t(50))
        << "the lamp and the middle sphere moved";
    // Left: one frame back.
    auto back = viewer.screenshot({"Left"});
    ASSERT_TRUE(back);
    EXPECT_NEAR(timeOf(back->second), 0.1, 1e-12);
    // Space plays, Space pauses: time went on by itself.
    ASSERT_TRUE(viewer.keys({"space"}));
    std::this_thread::sleep_for(600ms);
    auto played = viewer.screenshot({"space"});
    ASSERT_TRUE(played);
    EXPECT_GT(timeOf(played->second), 0.2);
    expectSameAsRender(played->first, played->second);
    // Paused, it stays put.
    std::this_thread::sleep_for(300ms);
    auto still = viewer.screenshot();
    ASSERT_TRUE(still);
    EXPECT_EQ(timeOf(still->second), timeOf(played->second));
    expectCleanExit(viewer);
}

TEST_F(ViewerTest, ResizeAndMinimiseKeepItRunningWithoutSpinning) {
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({"builtin:teapot", "--width", "160", "--height", "120"}));
    const std::string w = viewer.window();
    ASSERT_TRUE(m_server->xdotool({"windowsize", "--sync", w, "240", "150"}));
    auto resized = viewer.screenshot();
    ASSERT_TRUE(resized) << viewer.err();
    const Image big = readImage(resized->first);
    EXPECT_EQ(big.width, 240);
    EXPECT_EQ(big.height, 150);
    expectSameAsRender(resized->first, resized->second);

    // A window manager minimises a window by unmapping it; without one, xdotool does that.
    ASSERT_TRUE(m_server->xdotool({"windowunmap", "--sync", w}));
    std::this_thread::sleep_for(500ms);
    const double cpu0 = viewer.process().cpuSeconds();
    std::this_thread::sleep_for(2000ms);
    const double cpu = viewer.process().cpuSeconds() - cpu0;
    EXPECT_LT(cpu, 0.4) << "the minimised viewer used " << cpu << " s of CPU in 2 s: it spins";
    EXPECT_TRUE(viewer.process().running());
    ASSERT_TRUE(m_server->xdotool({"windowmap", "--sync", w}));
    ASSERT_TRUE(m_server->xdotool({"windowfocus", "--sync", w}));
    auto restored = viewer.screenshot({"1"});
    ASSERT_TRUE(restored) << viewer.err();
    expectSameAsRender(restored->first, restored->second);

    // Shrink to a sliver and back: still drawing.
    ASSERT_TRUE(m_server->xdotool({"windowsize", "--sync", w, "1", "1"}));
    std::this_thread::sleep_for(300ms);
    ASSERT_TRUE(m_server->xdotool({"windowsize", "--sync", w, "120", "90"}));
    auto again = viewer.screenshot();
    ASSERT_TRUE(again) << viewer.err();
    EXPECT_EQ(readImage(again->first).width, 120);
    expectCleanExit(viewer);
}

TEST_F(ViewerTest, PanelAndHelpAreDrawnOverThePictureButNotIntoScreenshots) {
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({"builtin:spheres", "--width", "360", "--height", "200", "--show-help"}));
    auto shot = viewer.screenshot();
    ASSERT_TRUE(shot);
    expectSameAsRender(shot->first, shot->second);
    const Image picture = readImage(shot->first);
    const unsigned long window = std::stoul(viewer.window());
    auto withUi = m_server->grab(window);
    ASSERT_TRUE(withUi);
    EXPECT_GT(maxDifference(*withUi, picture), 40) << "the panel and the help are on screen";
    // F1 and F2 hide them: the window shows the screenshot exactly again.
    ASSERT_TRUE(viewer.keys({"F1", "F2"}));
    int difference = 256;
    for (int i = 0; i < 100 && difference > 1; ++i) {
        std::this_thread::sleep_for(40ms);
        if (auto x = m_server->grab(window)) difference = maxDifference(*x, picture);
    }
    EXPECT_LE(difference, 1);
    expectCleanExit(viewer);
}

struct ScriptedRow {
    const char* name;
    std::vector<std::string> args;
    bool sameAsRender;  // false: an overlay or mode no render option expresses
    const char* why;
};

TEST_F(ViewerTest, AScriptedScreenshotOfANonFiniteFrameIsRefusedWithExit3) {
    // The readback hook of test builds plants a NaN at pixel (10, 10), as a shader bug would.
    const fs::path png = m_dir / "nonfinite.png";
    std::vector<std::string> args{cliPath().string(), "view", "builtin:spheres", "--width", "64",
                                  "--height", "48", "--after-frames", "2", "--screenshot", png.string()};
    std::vector<std::string> env = m_server->environment();
    env.push_back("LANTERN_TEST_NONFINITE_PIXEL=10,10");
    const ProcessResult r = runProcess(args, env, 120.0);
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_FALSE(fs::exists(png)) << "a frame with NaN was saved";
    EXPECT_NE(r.err.find("screenshot not written: the frame holds 1 non-finite values"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("lantern render builtin:spheres"), std::string::npos) << r.err;
}

TEST_F(ViewerTest, ScriptedRunsWriteTheScreenshotAndExit) {
    const ScriptedRow rows[] = {
        {"plain", {}, true, "the default view of the scene, as render gives it"},
        {"quad", {"--layout", "quad"}, true, "the quad layout, as render --layout quad"},
        {"overlays", {"--wireframe", "--normals"}, false, "wireframe and normals drawn over"},
        {"headlight", {"--headlight"}, false, "lights fixed to the starting camera: the same picture"},
    };
    std::optional<Image> plain;
    for (const ScriptedRow& row : rows) {
        SCOPED_TRACE(std::string(row.name) + ": " + row.why);
        const fs::path exr = m_dir / (std::string(row.name) + ".exr"), png = m_dir / (std::string(row.name) + ".png");
        std::vector<std::string> args{cliPath().string(), "view", "builtin:spheres", "--width", "160",
                                      "--height", "100", "--after-frames", "3", "--screenshot",
                                      exr.string(), "--screenshot", png.string()};
        const auto validation = validationFlag();
        args.insert(args.end(), validation.begin(), validation.end());
        args.insert(args.end(), row.args.begin(), row.args.end());
        const ProcessResult r = runProcess(args, m_server->environment(), 120.0);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
        ASSERT_TRUE(fs::exists(exr));
        ASSERT_TRUE(fs::exists(png));
        const auto commands = linesStartingWith(r.out, "render: ");
        ASSERT_EQ(commands.size(), 1u) << r.out;
        const Image image = readImage(exr);
        if (row.sameAsRender) {
            EXPECT_EQ(linesStartingWith(r.out, "note: ").size(), 0u) << r.out;
            expectSameAsRender(exr, commands[0]);
        } else {
            EXPECT_EQ(linesStartingWith(r.out, "note: ").size(), 1u) << r.out;
        }
        if (std::string(row.name) == "plain") plain = image;
        if (std::string(row.name) == "overlays") {
            ASSERT_TRUE(plain);
            EXPECT_GT(differingPixels(image, *plain), std::size_t(500)) << "the overlays are drawn";
        }
        if (std::string(row.name) == "headlight") {
            ASSERT_TRUE(plain);
            EXPECT_EQ(maxAbsDifference(image, *plain), 0.0f)
                << "fixing the lights to the camera where it stands moves nothing";
        }
    }
}

TEST_F(ViewerTest, HeadlightKeepsTheLightingWhenTheCameraOrbits) {
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({"builtin:teapot", "--width", "160", "--height", "120", "--no-panel"}));
    const std::string w = viewer.window();
    auto orbit = [&] {
        return m_server->xdotool({"mousemove", "--window", w, "40", "60", "mousedown", "1", "mousemove",
                                  "--window", w, "120", "60", "mouseup", "1"})
            .has_value();
    };
    // With world lights, orbiting half-way round shows the teapot's unlit side; with the
    // headlight, the lit side turns with the camera. Compare the brightness of both.
    ASSERT_TRUE(viewer.keys({"h"}));
    ASSERT_TRUE(orbit());
    auto withHeadlight = viewer.screenshot();
    ASSERT_TRUE(withHeadlight);
    ASSERT_NE(viewer.out().find("note: not in the command: the lights follow the camera"), std::string::npos);
    auto worldLights = viewer.screenshot({"h"});
    ASSERT_TRUE(worldLights);
    expectSameAsRender(worldLights->first, worldLights->second);
    const Image a = readImage(withHeadlight->first), b = readImage(worldLights->first);
    EXPECT_GT(differingPixels(a, b), std::size_t(300));
    expectCleanExit(viewer);
}

TEST_F(ViewerTest, WatchReloadsTheFileAndKeepsTheCamera) {
    const fs::path source = sharedDir() / "assets/gltf-samples/Box/glTF-Embedded/Box.gltf";
    ASSERT_TRUE(fs::exists(source)) << source;
    const fs::path scene = m_dir / "box.gltf";
    fs::copy_file(source, scene);
    {
        // Probe: the loader must accept the sample on this build.
        const ProcessResult probe = runLantern({"info", scene.string()});
        if (probe.err.find("glTF loading is not built yet") != std::string::npos)
            GTEST_SKIP() << "this build has no glTF loader yet (" << probe.err << ")";
        ASSERT_EQ(probe.exitCode, 0) << probe.err;
    }
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({scene.string(), "--width", "160", "--height", "120", "--no-panel", "--watch"}));
    const std::string w = viewer.window();
    ASSERT_TRUE(m_server->xdotool({"mousemove", "--window", w, "40", "60", "mousedown", "1", "mousemove",
                                   "--window", w, "90", "40", "mouseup", "1"}));
    auto first = viewer.screenshot();
    ASSERT_TRUE(first);
    // The file changes on disk (written beside it and renamed into place): a green box.
    std::string text = readText(scene);
    const std::string red = "0.800000011920929,\n                    0.0,\n                    0.0,";
    const auto at = text.find(red);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, red.size(), "0.0,\n                    0.800000011920929,\n                    0.0,");
    {
        std::ofstream out(m_dir / "box.tmp");
        out << text;
    }
    fs::rename(m_dir / "box.tmp", scene);
    const auto deadline = std::chrono::steady_clock::now() + 30s;
    while (viewer.out().find("reloaded: ") == std::string::npos && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(50ms);
    ASSERT_NE(viewer.out().find("reloaded: "), std::string::npos) << viewer.err();
    auto second = viewer.screenshot();
    ASSERT_TRUE(second);
    expectSameAsRender(second->first, second->second);
    // The camera stayed: the same --look-at and projection; the picture did not.
    auto cameraOf = [](const std::string& command) { return command.substr(command.find(" --look-at")); };
    EXPECT_EQ(cameraOf(first->second), cameraOf(second->second));
    EXPECT_GT(differingPixels(readImage(first->first), readImage(second->first)), std::size_t(300));
    expectCleanExit(viewer);
}

TEST_F(ViewerTest, WatchKeepsTheLastGoodSceneWhileTheFileIsHalfWritten) {
    const fs::path source = sharedDir() / "assets/gltf-samples/Box/glTF-Embedded/Box.gltf";
    ASSERT_TRUE(fs::exists(source)) << source;
    const fs::path scene = m_dir / "box.gltf";
    fs::copy_file(source, scene);
    ASSERT_EQ(runLantern({"info", scene.string()}).exitCode, 0);
    ViewerRun viewer(*m_server, m_dir);
    ASSERT_TRUE(viewer.start({scene.string(), "--width", "160", "--height", "120", "--no-panel", "--watch"}));
    auto first = viewer.screenshot();
    ASSERT_TRUE(first);
    // A writer that truncates the file in place and stops half-way (an editor saving, a copy
    // still running): the viewer must refuse that version and keep the last good one.
    const std::string text = readText(scene);
    {
        std::ofstream out(scene, std::ios::trunc);
        out << text.substr(0, text.size() / 2);
    }
    const auto deadline = std::chrono::steady_clock::now() + 30s;
    while (viewer.err().find("cannot be loaded; still showing the previous version") == std::string::npos &&
           std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(50ms);
    ASSERT_NE(viewer.err().find("cannot be loaded; still showing the previous version"), std::string::npos)
        << viewer.err();
    EXPECT_NE(viewer.err().find(scene.filename().string()), std::string::npos) << "the error names the file";
    auto during = viewer.screenshot();
    ASSERT_TRUE(during);
    EXPECT_EQ(differingPixels(readImage(first->first), readImage(during->first)), std::size_t(0));
    // The writer finishes: the complete file is loaded again.
    {
        std::ofstream out(scene, std::ios::trunc);
        out << text;
    }
    while (viewer.out().find("reloaded: ") == std::string::npos && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(50ms);
    EXPECT_NE(viewer.out().find("reloaded: "), std::string::npos) << viewer.err();
    expectCleanExit(viewer);
}

} // namespace
} // namespace lantern::test
