// Test support: paths, the shared renderer, process running, image comparison.
#include "TestSupport.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <limits>
#include <mutex>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>

namespace lantern::test {
namespace {

std::filesystem::path envPath(const char* name, const std::filesystem::path& fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::filesystem::path(v) : fallback;
}

std::mutex g_logMutex;
std::vector<std::string> g_log;

// The suite never writes into the user's own cache folder: ctest sets LANTERN_CACHE_DIR for
// every test (cmake/LanternTesting.cmake), and a test binary run by hand gets the build
// tree's folder here, before any renderer exists.
[[maybe_unused]] const bool g_pipelineCacheInBuildTree = [] {
    const std::string folder = std::string(LANTERN_TEST_BINARY_DIR) + "/tests/pipeline-cache";
    return ::setenv("LANTERN_CACHE_DIR", folder.c_str(), 0) == 0;
}();

} // namespace

std::filesystem::path sourceDir() { return envPath("LANTERN_SOURCE_DIR", LANTERN_TEST_SOURCE_DIR); }
std::filesystem::path sharedDir() { return envPath("LANTERN_SHARED_DIR", sourceDir() / ".." / "shared"); }
std::filesystem::path binaryDir() { return envPath("LANTERN_BINARY_DIR", LANTERN_TEST_BINARY_DIR); }
std::filesystem::path cliPath() { return envPath("LANTERN_CLI", binaryDir() / "apps/lantern/lantern"); }

std::filesystem::path testOutputDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "test";
    for (char& c : name)
        if (c == '/') c = '_';
    const auto dir = binaryDir() / "tests" / "output" / name;
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    std::filesystem::create_directories(dir);
    return dir;
}

namespace {
void logToStderr(LogLevel level, std::string_view message) {
    if (level < LogLevel::Warning) return;
    std::lock_guard lock(g_logMutex);
    std::cerr << "[lantern " << logLevelName(level) << "] " << message << "\n";
}

struct Shared {
    std::unique_ptr<Renderer> renderer;
    std::string reason;
};
Shared& shared() {
    static Shared s = [] {
        Shared r;
        RendererDesc desc;
        desc.validation = true;
        desc.log = logToStderr;
        auto created = Renderer::create(desc);
        if (created)
            r.renderer = std::make_unique<Renderer>(std::move(*created));
        else
            r.reason = created.error().describe();
        return r;
    }();
    return s;
}

// The engine's own device, for tests that look inside the renderer (frames, draw lists, ids):
// made on first use, with validation on, beside the public renderer.
std::shared_ptr<gpu::Device>& sharedDeviceSlot() {
    static std::shared_ptr<gpu::Device> device;
    return device;
}
} // namespace

Renderer* sharedRenderer() { return shared().renderer.get(); }

gpu::Device* sharedDevice() {
    std::shared_ptr<gpu::Device>& device = sharedDeviceSlot();
    if (!device && sharedRenderer()) {
        gpu::DeviceDesc desc;
        desc.validation = true;
        desc.log = logToStderr;
        auto created = gpu::Device::create(desc);
        if (created) device = std::move(*created);
    }
    return device.get();
}

namespace {
std::uint64_t deviceValidationCount() {
    const auto& device = sharedDeviceSlot();
    return device ? device->validationMessageCount() : 0;
}
} // namespace

std::string noDeviceReason() { return shared().reason; }

void GpuTest::SetUp() {
    m_renderer = sharedRenderer();
    if (!m_renderer) GTEST_SKIP() << "no Vulkan device: " << noDeviceReason();
    if (!m_renderer->device().validationEnabled)
        std::cerr << "note: VK_LAYER_KHRONOS_validation is not installed; validation not checked\n";
    m_validationBefore = m_renderer->validationMessageCount() + deviceValidationCount();
}

void GpuTest::TearDown() {
    if (!m_renderer) return;
    EXPECT_EQ(m_renderer->validationMessageCount() + deviceValidationCount(), m_validationBefore)
        << "the Vulkan validation layer reported messages during this test (see stderr)";
}

gpu::Device& GpuTest::device() {
    gpu::Device* d = sharedDevice();
    if (!d) {
        ADD_FAILURE() << "the engine's device could not be created beside the renderer";
        std::abort();
    }
    return *d;
}

void execChild(const std::vector<std::string>& args, const std::vector<std::string>& environment) {
    for (const std::string& e : environment) putenv(strdup(e.c_str()));
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    std::fprintf(stderr, "exec %s: %s\n", argv[0], std::strerror(errno));
    _exit(127);
}

ProcessResult runProcess(const std::vector<std::string>& args, const std::vector<std::string>& environment,
                         double timeoutSeconds) {
    ProcessResult result;
    int outPipe[2], errPipe[2];
    if (pipe(outPipe) != 0 || pipe(errPipe) != 0) return result;
    const pid_t pid = fork();
    if (pid < 0) return result;
    if (pid == 0) {
        dup2(outPipe[1], 1);
        dup2(errPipe[1], 2);
        close(outPipe[0]);
        close(errPipe[0]);
        execChild(args, environment);
    }
    close(outPipe[1]);
    close(errPipe[1]);
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::milliseconds(long(timeoutSeconds * 1000));
    pollfd fds[2] = {{outPipe[0], POLLIN, 0}, {errPipe[0], POLLIN, 0}};
    int open = 2;
    char buf[65536];
    bool killed = false;
    while (open > 0) {
        const int r = poll(fds, 2, 200);
        if (std::chrono::steady_clock::now() > deadline && !killed) {
            kill(pid, SIGKILL);
            killed = true;
        }
        if (r <= 0) continue;
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            const ssize_t n = read(fds[i].fd, buf, sizeof buf);
            if (n <= 0) {
                close(fds[i].fd);
                fds[i].fd = -1;
                --open;
            } else {
                (i == 0 ? result.out : result.err).append(buf, std::size_t(n));
            }
        }
    }
    int status = 0;
    waitpid(pid, &status, 0);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return result;
}

ProcessResult runLantern(const std::vector<std::string>& args, const std::vector<std::string>& environment) {
    std::vector<std::string> full{cliPath().string()};
    full.insert(full.end(), args.begin(), args.end());
    return runProcess(full, environment);
}

std::string findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        std::size_t end = dirs.find(':', start);
        if (end == std::string::npos) end = dirs.size();
        const std::string dir = dirs.substr(start, end - start);
        const auto candidate = std::filesystem::path(dir) / program;
        if (!dir.empty() && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
        start = end + 1;
    }
    return {};
}

std::string missingProgram(const std::string& program, const std::string& debianPackage) {
    if (!findOnPath(program).empty()) return {};
    return program + " is not installed (Debian package " + debianPackage + ")";
}

std::string missingVulkanDevice() {
    if (sharedRenderer()) return {};
    return "no Vulkan device: " + noDeviceReason();
}

std::vector<std::string> validationFlag() {
    if (sharedRenderer() && sharedRenderer()->device().validationEnabled) return {"--validation"};
    std::cerr << "note: VK_LAYER_KHRONOS_validation is not installed; validation not checked\n";
    return {};
}

std::string missingUserNamespaceMount(const std::vector<std::string>& environment) {
    // Mounted over /tmp inside the private namespace, so nothing outside it sees the mount.
    const auto r = runProcess({"unshare", "-rm", "sh", "-c",
                               "mount -t tmpfs -o size=64k tmpfs /tmp || exit 77"},
                              environment, 30.0);
    if (r.exitCode == 0) return {};
    std::string said = r.err;
    while (!said.empty() && (said.back() == '\n' || said.back() == ' ')) said.pop_back();
    if (r.exitCode == 127)
        return "unshare is not installed (Debian package util-linux): " + said;
    if (r.exitCode == 77)
        return "no tmpfs can be mounted in an unprivileged user namespace here (`unshare -rm` "
               "then mount: " + said + ")";
    return "no unprivileged user namespace can be created here (`unshare -rm`: " + said +
           "); Linux refuses one in a chroot, and Docker's default seccomp profile in a "
           "container";
}

float maxAbsDifference(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
        return std::numeric_limits<float>::infinity();
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
    return worst;
}

std::size_t countNonFinite(const Image& image) {
    std::size_t n = 0;
    for (float v : image.rgba) n += !std::isfinite(v);
    for (float v : image.depth) n += !std::isfinite(v);
    for (float v : image.normal) n += !std::isfinite(v);
    return n;
}

std::size_t countCovered(const Image& image, float threshold) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < image.pixelCount(); ++i) n += image.rgba[i * 4 + 3] > threshold;
    return n;
}

std::string saveComparison(const Image& actual, const Image& expected, const std::string& name) {
    const auto dir = binaryDir() / "tests" / "output" / "comparisons";
    std::filesystem::create_directories(dir);
    Image diff(actual.width, actual.height);
    if (actual.rgba.size() == expected.rgba.size())
        for (std::size_t i = 0; i < actual.rgba.size(); ++i)
            diff.rgba[i] = (i % 4 == 3) ? 1.0f : std::abs(actual.rgba[i] - expected.rgba[i]);
    const auto a = dir / (name + ".actual.exr"), e = dir / (name + ".expected.exr"),
               d = dir / (name + ".diff.exr");
    (void)writeExr(a, actual);
    (void)writeExr(e, expected);
    (void)writeExr(d, diff);
    return "images: " + a.string() + " " + e.string() + " " + d.string();
}

Scene SimpleScene::build() const {
    Scene s;
    s.sourcePath = "test";
    s.meshes.push_back(Mesh{"mesh", {primitive}});
    s.meshes[0].primitives[0].material = 0;
    s.materials.push_back(material);
    Node object;
    object.name = "object";
    object.mesh = 0;
    object.matrix = model;
    s.nodes.push_back(object);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        s.lights.push_back(lights[i].first);
        Node n;
        n.name = "light " + std::to_string(i);
        n.light = int(i);
        n.matrix = lights[i].second;
        s.nodes.push_back(n);
    }
    Camera cam;
    cam.name = "test camera";
    cam.projection = projection;
    cam.lookAt = lookAt;
    s.cameras.push_back(cam);
    SceneRoot root;
    for (int i = 0; i < int(s.nodes.size()); ++i) root.nodes.push_back(i);
    root.lighting = lighting;
    s.roots.push_back(root);
    return s;
}

} // namespace lantern::test
