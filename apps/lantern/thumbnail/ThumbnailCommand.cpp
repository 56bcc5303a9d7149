// `lantern thumbnail [-s SIZE] INPUT OUTPUT`: a freedesktop thumbnailer. A file manager runs it
// on every model a user browses past, hostile ones included, so it works within budgets: the
// file's size and the memory its load may hold (--max-size, checked before anything is read,
// then charged by the loader before each allocation), the process's address space
// (--memory-limit, RLIMIT_AS) and the wall time (--time-limit, a watchdog). Over a budget: no
// thumbnail, exit 1, fast. The picture: SIZE x SIZE PNG, transparent background, the automatic
// three-quarter view, written atomically.
#include "common/CliSupport.h"
#include "common/Commands.h"

#include <lantern/Lantern.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <sys/resource.h>
#include <thread>
#include <unistd.h>

namespace lantern::cli {
namespace {

struct ThumbnailArgs {
    std::string input, output;
    int size = 256;
    std::uint64_t maxBytes = 100ull << 20;  ///< F3D's thumbnailer cap (its PR 401)
    double timeLimit = 10.0;
    std::uint64_t memoryLimitMiB = 2048;
    DeviceOptions device;
};

// Ends the process with an error when the time budget runs out before the output is being
// written (a write in progress finishes: the file appears whole or not at all).
class Watchdog {
public:
    Watchdog(double seconds, std::string input) : m_input(std::move(input)) {
        m_thread = std::thread([this, seconds] {
            std::unique_lock lock(m_mutex);
            if (m_done.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return m_stop; }))
                return;
            if (m_writing.load()) return;
            std::fprintf(stderr, "lantern: error: %s: no thumbnail: it took longer than the time "
                                 "budget of %g s (--time-limit)\n", m_input.c_str(), seconds);
            std::fflush(stderr);
            _exit(kRefused);
        });
    }
    ~Watchdog() {
        {
            std::lock_guard lock(m_mutex);
            m_stop = true;
        }
        m_done.notify_all();
        m_thread.join();
    }
    Watchdog(const Watchdog&) = delete;
    Watchdog& operator=(const Watchdog&) = delete;
    /// From here on the budget no longer ends the process.
    void writing() { m_writing = true; }

private:
    std::string m_input;
    std::mutex m_mutex;
    std::condition_variable m_done;
    bool m_stop = false;
    std::atomic<bool> m_writing{false};
    std::thread m_thread;
};

// The address-space budget. Sanitizer builds reserve terabytes of shadow memory, so there the
// load budget alone applies (LANTERN_ASAN and LANTERN_TSAN: cmake/LanternSanitizers.cmake; clang
// 14 defines no __SANITIZE_ADDRESS__).
void limitMemory(std::uint64_t mib) {
#if defined(LANTERN_ASAN) || defined(LANTERN_TSAN)
    (void)mib;
#else
    const rlimit limit{rlim_t(mib) << 20, rlim_t(mib) << 20};
    setrlimit(RLIMIT_AS, &limit);
#endif
}

Result<void> checkInput(const ThumbnailArgs& a) {
    std::error_code ec;
    const auto status = std::filesystem::status(a.input, ec);
    if (ec || !std::filesystem::is_regular_file(status))
        return makeError(ErrorCode::IoError, "no thumbnail: not a readable file", {}, a.input);
    const std::uint64_t bytes = std::filesystem::file_size(a.input, ec);
    if (!ec && bytes > a.maxBytes)
        return makeError(ErrorCode::InvalidInput,
                         "no thumbnail: the file has " + std::to_string(bytes) +
                             " bytes, more than the budget of " + std::to_string(a.maxBytes) +
                             " (--max-size)",
                         {}, a.input);
    if (std::filesystem::path(a.output).extension() != ".png")
        return makeError(ErrorCode::Usage, "a thumbnail is a .png file", "OUTPUT", a.output);
    return {};
}

// The picture, within the load and address-space budgets.
Result<Image> thumbnail(const ThumbnailArgs& a) {
    LoadOptions load;
    load.maxBytes = a.maxBytes;
    auto scene = loadScene(a.input, load);
    if (!scene) return std::move(scene).error();
    auto renderer = Renderer::create(a.device.desc());
    if (!renderer) return std::move(renderer).error();
    RenderOptions options;
    options.width = options.height = a.size;
    options.background = glm::vec4(0.0f);
    options.camera = CameraSpec::framed(ViewDirection::ThreeQuarter);
    return renderer->render(*scene, options, 0.0);
}

int run(const ThumbnailArgs& a) {
    if (auto c = checkInput(a); !c) return report(c.error());
    limitMemory(a.memoryLimitMiB);
    Watchdog watchdog(a.timeLimit, a.input);
    auto image = thumbnail(a);
    if (!image) {
        Error e = std::move(image).error();
        if (e.file.empty()) e.file = a.input;
        e.message = "no thumbnail: " + e.message + " (within --memory-limit " +
                    std::to_string(a.memoryLimitMiB) + " MiB)";
        return report(e);
    }
    watchdog.writing();
    if (auto w = writeImage(a.output, *image, ExrOptions{}); !w) return report(w.error());
    return kOk;
}

} // namespace

Runner addThumbnailCommand(CLI::App& app) {
    auto a = std::make_shared<ThumbnailArgs>();
    CLI::App* cmd = app.add_subcommand(
        "thumbnail", "Write a PNG thumbnail of a scene file within time, memory and size budgets "
                     "(a freedesktop thumbnailer)");
    cmd->add_option("input", a->input, "Scene file (glTF, GLB, OBJ, PLY, STL, OFF)")->required();
    cmd->add_option("output", a->output, "The PNG to write")->required();
    cmd->add_option("-s,--side", a->size, "Thumbnail side in pixels")
        ->capture_default_str()
        ->check(CLI::Range(8, 4096));
    cmd->add_option("--max-size", a->maxBytes,
                    "Budget in bytes for the file, and for what its load may hold in memory")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 40));
    cmd->add_option("--time-limit", a->timeLimit, "Budget in seconds, from start to the write")
        ->capture_default_str()
        ->check(CLI::Range(0.001, 3600.0));
    cmd->add_option("--memory-limit", a->memoryLimitMiB,
                    "Budget in MiB for the process's address space (driver included)")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(64), std::uint64_t(1) << 24));
    a->device.add(*cmd);
    return [a, cmd]() { return cmd->parsed() ? run(*a) : -1; };
}

} // namespace lantern::cli
