// The timing harness and output helpers shared by `lantern bench accuracy` and `lantern bench
// speed`: interleaved rounds with warm-up and medians (numerics.md sections 5 and 7.4).
#include "bench/BenchHarness.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace lantern::cli {

Result<void> timeInterleaved(Renderer& renderer, std::vector<TimedConfig>& configs,
                             const TimingPlan& plan, bool quiet, bool* usedGpuClock) {
    bool gpuClock = true;
    for (int round = 0; round < plan.rounds; ++round) {
        const auto roundStart = std::chrono::steady_clock::now();
        for (std::size_t ci = 0; ci < configs.size(); ++ci) {
            TimedConfig& c = configs[ci];
            std::vector<double> timed;
            Image last;
            for (int f = 0; f < plan.warmup + plan.frames; ++f) {
                const auto t0 = std::chrono::steady_clock::now();
                auto image = renderer.render(*c.scene, c.options, 0.0);
                if (!image) return std::move(image).error();
                const double wall = msSince(t0);
                const FrameStats& stats = renderer.lastFrameStats();
                c.nonFinite += stats.nonFinite;
                if (round == 0 && f == 0) {
                    c.firstFrameMs = wall;
                    c.pipelinesCreated = stats.pipelinesCreated;
                }
                if (f < plan.warmup) continue;
                if (stats.gpuMs < 0.0) gpuClock = false;
                const double ms = stats.gpuMs >= 0.0 ? stats.gpuMs : wall;
                timed.push_back(ms);
                c.frameMs.push_back(ms);
                c.wallMs.push_back(wall);
                c.clusterTriangles = stats.clusterTriangles;
                c.clusterTrianglesDrawn = stats.clusterTrianglesDrawn;
                if (f == plan.warmup + plan.frames - 1) last = std::move(*image);
            }
            c.roundMedians.push_back(median(timed));
            if (round == 0 && c.inspect) LANTERN_TRY(c.inspect(last));
            if (!quiet && round == 0)
                std::fprintf(stderr, "  [%zu/%zu] %-48s %9.2f ms (first frame %.0f ms)\n", ci + 1,
                             configs.size(), c.label.c_str(), c.roundMedians.back(),
                             c.firstFrameMs);
        }
        if (!quiet)
            std::fprintf(stderr, "round %d of %d done in %.1f s\n", round + 1, plan.rounds,
                         msSince(roundStart) / 1000.0);
    }
    if (usedGpuClock) *usedGpuClock = gpuClock;
    return {};
}

void TimingOptions::add(CLI::App& app, const std::string& quickHelp,
                        const std::string& outputHelp) {
    m_rounds = app.add_option("--rounds", plan.rounds, "Interleaved rounds")
                   ->capture_default_str()
                   ->check(CLI::Range(1, 1000));
    m_frames = app.add_option("--frames", plan.frames, "Timed frames per configuration and round")
                   ->capture_default_str()
                   ->check(CLI::Range(1, 10000));
    app.add_option("--warmup", plan.warmup,
                   "Untimed frames before them (at least 1: the first is JIT)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    app.add_flag("--quick", quick, quickHelp + " (options given explicitly win)");
    app.add_flag("-q,--quiet", quiet, "No progress and no summary on the terminal");
    app.add_option("-o,--output", output, outputHelp)->capture_default_str();
}

void TimingOptions::applyQuick(int rounds, int frames) {
    if (!quick) return;
    if (!m_rounds->count()) plan.rounds = rounds;
    if (!m_frames->count()) plan.frames = frames;
}

Result<void> makeOutputFolder(const std::string& path) {
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    if (ec || !std::filesystem::is_directory(path))
        return makeError(ErrorCode::IoError, "cannot create the output folder", "--output", path);
    return {};
}

double TimedConfig::roundSpread() const {
    if (roundMedians.empty() || !(ms() > 0.0)) return 0.0;
    const auto [lo, hi] = std::minmax_element(roundMedians.begin(), roundMedians.end());
    return (*hi - *lo) / ms();
}

std::string spreadSentence(std::vector<double> spreads) {
    return "Round-to-round spread of a configuration's median (slowest minus fastest round, over "
           "the median), median over the configurations: " +
           num(100.0 * median(std::move(spreads)), "%.0f") + " %.";
}

ColdShaderCache::ColdShaderCache() {
    if (std::getenv("MESA_SHADER_CACHE_DISABLE") || std::getenv("MESA_SHADER_CACHE_DIR")) return;
    std::string pattern =
        (std::filesystem::temp_directory_path() / "lantern-bench-shader-cache-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) {
        setenv("MESA_SHADER_CACHE_DISABLE", "true", 1); // cold, the other way
        return;
    }
    m_dir = pattern;
    setenv("MESA_SHADER_CACHE_DIR", m_dir.c_str(), 1);
}

ColdShaderCache::~ColdShaderCache() {
    if (m_dir.empty()) return;
    std::error_code ec;
    std::filesystem::remove_all(m_dir, ec);
}

std::string machineDescription(const Renderer& renderer) {
    std::string cpu = "unknown CPU";
    std::ifstream info("/proc/cpuinfo");
    for (std::string line; std::getline(info, line);)
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    const char* threads = std::getenv("LP_NUM_THREADS");
    const char* off = std::getenv("MESA_SHADER_CACHE_DISABLE");
    const char* dir = std::getenv("MESA_SHADER_CACHE_DIR");
    const std::string cache =
        off   ? std::string("off (MESA_SHADER_CACHE_DISABLE=") + off + ")"
        : dir ? (std::string(dir).find("lantern-bench-shader-cache-") != std::string::npos
                     ? std::string("on, in a new empty folder")
                     : std::string("MESA_SHADER_CACHE_DIR=") + dir)
              : std::string("Mesa's default");
    std::ostringstream s;
    s << "CPU " << cpu << ", " << std::thread::hardware_concurrency()
      << " cores, LP_NUM_THREADS=" << (threads ? threads : "(unset: one per core)")
      << ", shader cache " << cache << "; device " << renderer.device().name << " ("
      << renderer.device().driver << ")";
    return s.str();
}

std::string commandLine() {
    std::string out;
    for (const std::string& arg : processArguments())  // argv[0] as "lantern"
        out += out.empty() ? std::filesystem::path(arg).filename().string() : " " + arg;
    return out;
}

Result<void> checkRange(const std::vector<int>& values, int lo, int hi, const std::string& option) {
    if (values.empty()) return makeError(ErrorCode::InvalidInput, "the list is empty", option);
    for (int v : values)
        if (v < lo || v > hi)
            return makeError(ErrorCode::InvalidInput,
                             std::to_string(v) + " is outside " + std::to_string(lo) + ".." +
                                 std::to_string(hi),
                             option);
    return {};
}

Result<std::vector<ShadingMode>> parseShadingList(const std::vector<std::string>& names,
                                                  const std::string& option) {
    std::vector<ShadingMode> modes;
    for (const std::string& n : names) {
        auto m = parseShadingMode(n);
        if (!m)
            return makeError(ErrorCode::InvalidInput,
                             "\"" + n + "\" is not a shading mode (flat, gouraud, phong)", option);
        modes.push_back(*m);
    }
    if (modes.empty()) return makeError(ErrorCode::InvalidInput, "the list is empty", option);
    return modes;
}

std::string num(double value, const char* format) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char b[64];
    std::snprintf(b, sizeof b, format, value);
    return b;
}


} // namespace lantern::cli
