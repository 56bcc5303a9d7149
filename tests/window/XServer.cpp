// Xvfb, background processes, xdotool and XGetImage for the window tests.
#include "XServer.h"

#include "TestSupport.h"

#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <random>
#include <sstream>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace lantern::test {
namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string findProgram(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::stringstream ss(path ? path : "/usr/bin:/bin");
    std::string dir;
    while (std::getline(ss, dir, ':')) {
        const fs::path p = fs::path(dir) / name;
        if (!dir.empty() && ::access(p.c_str(), X_OK) == 0) return p.string();
    }
    return {};
}

std::unique_ptr<ChildProcess> ChildProcess::start(const std::vector<std::string>& args,
                                                  const std::vector<std::string>& environment,
                                                  const fs::path& stdoutFile,
                                                  const fs::path& stderrFile) {
    const pid_t pid = fork();
    if (pid < 0) return nullptr;
    if (pid == 0) {
        // Dies with the test even when the test itself is killed (a ctest timeout), so no
        // Xvfb or viewer outlives it.
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        const int out = ::open(stdoutFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(stderrFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out >= 0) dup2(out, 1);
        if (err >= 0) dup2(err, 2);
        const int null = ::open("/dev/null", O_RDONLY);
        if (null >= 0) dup2(null, 0);
        execChild(args, environment);
    }
    auto p = std::unique_ptr<ChildProcess>(new ChildProcess());
    p->m_pid = pid;
    return p;
}

ChildProcess::~ChildProcess() {
    if (m_pid > 0 && !m_exit) {
        ::kill(m_pid, SIGKILL);
        int status = 0;
        waitpid(m_pid, &status, 0);
    }
}

bool ChildProcess::running() { return !wait(0ms).has_value(); }

std::optional<int> ChildProcess::wait(std::chrono::milliseconds timeout) {
    if (m_exit) return m_exit;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
        int status = 0;
        const pid_t r = waitpid(m_pid, &status, WNOHANG);
        if (r == m_pid) {
            m_exit = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            return m_exit;
        }
        if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
        std::this_thread::sleep_for(10ms);
    }
}

int ChildProcess::stop(std::chrono::milliseconds grace) {
    if (m_exit) return *m_exit;
    ::kill(m_pid, SIGTERM);
    if (auto code = wait(grace)) return *code;
    ::kill(m_pid, SIGKILL);
    return wait(10000ms).value_or(-1);
}

double ChildProcess::cpuSeconds() const {
    std::ifstream in("/proc/" + std::to_string(m_pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Fields after the command name (which may contain spaces) start after the last ')'.
    const auto close = text.rfind(')');
    if (close == std::string::npos) return 0.0;
    std::stringstream ss(text.substr(close + 2));
    std::string field;
    std::vector<std::string> fields;
    while (ss >> field) fields.push_back(field);
    // utime and stime are fields 14 and 15 of the file, 12 and 13 after the name.
    if (fields.size() < 13) return 0.0;
    return double(std::stoull(fields[11]) + std::stoull(fields[12])) / double(sysconf(_SC_CLK_TCK));
}

std::uint8_t srgb8(float linear) {
    const double c = std::clamp(double(linear), 0.0, 1.0);
    const double e = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return std::uint8_t(std::lround(e * 255.0));
}

int maxDifference(const XImageRgb& x, const Image& image, int x0, int y0, int x1, int y1) {
    if (x1 < 0) x1 = image.width;
    if (y1 < 0) y1 = image.height;
    if (x.width != image.width || x.height != image.height) return 256;
    int worst = 0;
    for (int y = y0; y < y1; ++y)
        for (int px = x0; px < x1; ++px) {
            const float* p = image.pixel(px, y);
            const std::uint8_t* q = &x.rgb[(std::size_t(y) * std::size_t(x.width) + std::size_t(px)) * 3];
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(srgb8(p[c])) - int(q[c])));
        }
    return worst;
}

std::string XServer::missing() {
    std::string reason;
    for (const auto& [program, package] :
         {std::pair<const char*, const char*>{"Xvfb", "xvfb"}, {"xauth", "xauth"}}) {
        if (!findProgram(program).empty()) continue;
        reason += (reason.empty() ? "" : ", ") + std::string(program) +
                  " is not installed (Debian package " + package + ")";
    }
    if (!reason.empty())
        reason += ": no X server (display) for the window tests; `scripts/install-deps.sh test` "
                  "installs it";
    return reason;
}

std::unique_ptr<XServer> XServer::start(const fs::path& dir, std::string& error,
                                        const std::string& screen) {
    const std::string xvfb = findProgram("Xvfb"), xauth = findProgram("xauth");
    if (xvfb.empty() || xauth.empty()) {
        error = "Xvfb or xauth is not installed";
        return nullptr;
    }
    std::random_device rd;
    std::mt19937 rng(rd() ^ std::uint32_t(getpid()));
    char cookie[33];
    for (int i = 0; i < 16; ++i) std::snprintf(cookie + 2 * i, 3, "%02x", unsigned(rng() & 0xFF));
    auto server = std::unique_ptr<XServer>(new XServer());
    server->m_authFile = dir / "xauthority";
    for (int attempt = 0; attempt < 20; ++attempt) {
        const int n = 100 + int(rng() % 800);
        if (fs::exists("/tmp/.X" + std::to_string(n) + "-lock") ||
            fs::exists("/tmp/.X11-unix/X" + std::to_string(n)))
            continue;
        const std::string display = ":" + std::to_string(n);
        fs::remove(server->m_authFile);
        const ProcessResult added =
            runProcess({xauth, "-q", "-f", server->m_authFile.string(), "add", display, ".", cookie});
        if (added.exitCode != 0) {
            error = "xauth failed: " + added.err;
            return nullptr;
        }
        auto process = ChildProcess::start(
            {xvfb, display, "-screen", "0", screen, "-auth", server->m_authFile.string(),
             "-nolisten", "tcp", "-noreset"},
            {}, dir / "xvfb.out", dir / "xvfb.err");
        if (!process) continue;
        server->m_display = display;
        server->exportToThisProcess();
        const auto deadline = std::chrono::steady_clock::now() + 15s;
        bool up = false;
        while (std::chrono::steady_clock::now() < deadline && process->running()) {
            if (Display* d = XOpenDisplay(display.c_str())) {
                XCloseDisplay(d);
                up = true;
                break;
            }
            std::this_thread::sleep_for(50ms);
        }
        if (up) {
            server->m_process = std::move(process);
            return server;
        }
        process->stop();  // display taken meanwhile, or Xvfb failed: try another
    }
    error = "could not start Xvfb on a free display (see " + (dir / "xvfb.err").string() + ")";
    return nullptr;
}

XServer::~XServer() {
    if (m_process) m_process->stop();
    std::error_code ec;
    fs::remove(m_authFile, ec);
}

std::vector<std::string> XServer::environment() const {
    return {"DISPLAY=" + m_display, "XAUTHORITY=" + m_authFile.string()};
}

void XServer::exportToThisProcess() const {
    ::setenv("DISPLAY", m_display.c_str(), 1);
    ::setenv("XAUTHORITY", m_authFile.c_str(), 1);
}

std::optional<std::string> XServer::xdotool(const std::vector<std::string>& args) const {
    std::vector<std::string> full{"xdotool"};
    full.insert(full.end(), args.begin(), args.end());
    const ProcessResult r = runProcess(full, environment(), 30.0);
    if (r.exitCode != 0) return std::nullopt;
    return r.out;
}

std::optional<std::string> XServer::waitForWindow(const std::string& pattern,
                                                  std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        if (auto out = xdotool({"search", "--onlyvisible", "--name", pattern})) {
            std::stringstream ss(*out);
            std::string id;
            if (ss >> id) return id;
        }
        std::this_thread::sleep_for(100ms);
    }
    return std::nullopt;
}

std::optional<XImageRgb> XServer::grab(unsigned long window) const {
    Display* d = XOpenDisplay(m_display.c_str());
    if (!d) return std::nullopt;
    std::optional<XImageRgb> result;
    XWindowAttributes wa{};
    if (XGetWindowAttributes(d, window, &wa) && wa.width > 0 && wa.height > 0) {
        if (XImage* img = XGetImage(d, window, 0, 0, unsigned(wa.width), unsigned(wa.height),
                                    AllPlanes, ZPixmap)) {
            XImageRgb out;
            out.width = wa.width;
            out.height = wa.height;
            out.rgb.resize(std::size_t(wa.width) * std::size_t(wa.height) * 3);
            auto channel = [](unsigned long pixel, unsigned long mask) {
                int shift = 0;
                while (mask && !(mask & 1)) {
                    mask >>= 1;
                    ++shift;
                }
                return std::uint8_t(((pixel >> shift) & mask) * 255 / (mask ? mask : 1));
            };
            for (int y = 0; y < wa.height; ++y)
                for (int x = 0; x < wa.width; ++x) {
                    const unsigned long p = XGetPixel(img, x, y);
                    std::uint8_t* o = &out.rgb[(std::size_t(y) * std::size_t(wa.width) + std::size_t(x)) * 3];
                    o[0] = channel(p, img->red_mask);
                    o[1] = channel(p, img->green_mask);
                    o[2] = channel(p, img->blue_mask);
                }
            XDestroyImage(img);
            result = std::move(out);
        }
    }
    XCloseDisplay(d);
    return result;
}

} // namespace lantern::test
