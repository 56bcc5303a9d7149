// XServer.h: what the window tests need around a real X server: an Xvfb on a free display
// with its own authorization cookie (stopped, with everything started on it, when the test
// ends), child processes run in the background, xdotool, and reading a window's pixels back
// from the server (XGetImage).
#pragma once

#include <lantern/Image.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lantern::test {

/// The path of an executable found on $PATH, or empty.
std::string findProgram(const std::string& name);

/// A process started in the background; killed (SIGKILL) and reaped when destroyed if it is
/// still running, so no test leaves one behind.
class ChildProcess {
public:
    /// Starts `args` with `environment` added; stdout and stderr go to the given files.
    static std::unique_ptr<ChildProcess> start(const std::vector<std::string>& args,
                                               const std::vector<std::string>& environment,
                                               const std::filesystem::path& stdoutFile,
                                               const std::filesystem::path& stderrFile);
    ~ChildProcess();

    int pid() const { return m_pid; }
    bool running();
    /// Waits up to `timeout` for the process to end; its exit code (128 + signal when killed),
    /// or nullopt when it is still running.
    std::optional<int> wait(std::chrono::milliseconds timeout);
    /// SIGTERM, then SIGKILL after `grace`; returns the exit code.
    int stop(std::chrono::milliseconds grace = std::chrono::milliseconds(3000));
    /// User + system CPU seconds the process has used so far (from /proc).
    double cpuSeconds() const;

private:
    int m_pid = -1;
    std::optional<int> m_exit;
};

/// Pixels of a window read from the X server: 8-bit RGB, top row first.
struct XImageRgb {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
};

/// The 8-bit sRGB encoding of a linear value (clamped to [0, 1]), as an sRGB swapchain holds it.
std::uint8_t srgb8(float linear);

/// The largest difference between the X server's pixels and the sRGB encoding of `image`
/// (premultiplied over black, as the swapchain shows it) over [x0,x1) x [y0,y1) (-1: to the
/// edge); 256 when the sizes differ.
int maxDifference(const XImageRgb& x, const Image& image, int x0 = 0, int y0 = 0, int x1 = -1,
                  int y1 = -1);

/// An Xvfb server for one test.
class XServer {
public:
    /// Why no X server can be started here (Xvfb or xauth is not installed), naming the
    /// packages; empty when both are there. The window tests skip with this reason.
    static std::string missing();
    /// Starts Xvfb (screen `screen`, e.g. "1024x768x24") on a free display with a fresh
    /// MIT-MAGIC-COOKIE-1 in an auth file under `dir`, and waits until it accepts clients.
    /// nullptr and `error` on failure.
    static std::unique_ptr<XServer> start(const std::filesystem::path& dir, std::string& error,
                                          const std::string& screen = "1024x768x24");
    ~XServer();

    const std::string& display() const { return m_display; }
    /// DISPLAY and XAUTHORITY for processes run on this server.
    std::vector<std::string> environment() const;
    /// Sets DISPLAY and XAUTHORITY in this process (for in-process GLFW windows).
    void exportToThisProcess() const;

    /// Runs xdotool with `args` on this server; its stdout, or nullopt when it failed.
    std::optional<std::string> xdotool(const std::vector<std::string>& args) const;
    /// The id of the first visible window whose name matches `pattern`, waiting up to `timeout`.
    std::optional<std::string> waitForWindow(const std::string& pattern,
                                             std::chrono::milliseconds timeout) const;
    /// The window's contents as the server has them.
    std::optional<XImageRgb> grab(unsigned long window) const;

private:
    std::unique_ptr<ChildProcess> m_process;
    std::string m_display;
    std::filesystem::path m_authFile;
};

} // namespace lantern::test
