// Viewer.h: the frame loop of `lantern view`: the scene (and its reloads with --watch), input
// sampled after the frame-slot wait, the panel, a frame rendered to the window, screenshots
// and the frame-time statistics. Public API only.
#pragma once

#include "view/ViewArgs.h"
#include "view/ViewerInput.h"
#include "view/ViewerLod.h"
#include "view/ViewerState.h"
#include "view/ViewerStats.h"
#include "view/ViewerUi.h"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <lantern/glfw/GlfwWindow.h>
#include <memory>
#include <optional>
#include <string>

namespace lantern::cli {

class Viewer {
public:
    Viewer(const ViewArgs& args, Renderer& renderer, glfw::Window& window)
        : m_args(args), m_renderer(renderer), m_window(window), m_input(m_st, window) {}

    /// Shows `scene` until the window closes (Esc), a SIGINT or SIGTERM, or --after-frames;
    /// returns the exit status.
    int run(std::shared_ptr<Scene> scene);

private:
    using Clock = std::chrono::steady_clock;

    int start(std::shared_ptr<Scene> scene);
    std::optional<int> runFrame();
    int finish(int code);
    bool adopt(std::shared_ptr<Scene> scene);
    void resolveLightingDefaults();
    double perspectiveAspect() const;
    RenderOptions frameOptions() const;
    void advance(double dt);
    void checkWatch();
    int writeCapture(const Image& image);
    std::string renderCommand(const std::string& output) const;
    std::string backgroundText() const {
        return m_args.background.empty() ? "0,0,0" : m_args.background;
    }
    void updateTitle();

    const ViewArgs& m_args;
    Renderer& m_renderer;
    glfw::Window& m_window;
    ViewerState m_st;
    ViewerInput m_input;
    PreparedScene m_prepared;
    std::unique_ptr<ViewerUi> m_ui;
    LightingModel m_sceneLighting;
    ViewerStats m_stats;
    ViewerLod m_lod;  ///< the level of detail while the camera moves
    double m_lastFrameMs = 0.0;

    Clock::time_point m_last{}; ///< when the last frame sampled its input
    bool m_captureNext = false;
    int m_shotCounter = 0;

    std::filesystem::file_time_type m_loadedTime{}, m_seenTime{};
    std::uintmax_t m_loadedSize = 0, m_seenSize = 0;
    Clock::time_point m_seenAt{}, m_lastWatch{};
};

} // namespace lantern::cli
