// BenchHarness.h: what `lantern bench accuracy` and `lantern bench speed` share: timing many
// render configurations interleaved (ABCABC..., numerics.md section 7.4), the machine's
// description, option-list parsing, and CSV / markdown output helpers.
#pragma once

#include "bench/Bench.h"
#include "common/CliSupport.h"
#include "common/TextFile.h"

#include <cstdint>
#include <functional>
#include <lantern/Lantern.h>
#include <string>
#include <vector>

namespace lantern::cli {

/// How each configuration is timed: in every round, each configuration renders `warmup`
/// untimed frames (re-warming caches and the frame slots' targets after the previous
/// configuration) and then `frames` timed ones; a round's median is one sample, and the result
/// is the median of the rounds' medians. The very first frame of a configuration is timed
/// apart (it compiles the pipeline variants the configuration needs for the first time).
struct TimingPlan {
    int rounds = 3;
    int warmup = 2;
    int frames = 5;
};

/// The options every timed benchmark shares: --rounds, --frames, --warmup, --quick, --quiet and
/// --output.
struct TimingOptions {
    TimingPlan plan;
    bool quick = false, quiet = false;
    std::string output;

    void add(CLI::App& app, const std::string& quickHelp, const std::string& outputHelp);
    /// With --quick: these rounds and frames unless the command line gave them.
    void applyQuick(int rounds, int frames);

private:
    CLI::Option *m_rounds = nullptr, *m_frames = nullptr;
};

/// Creates the output folder (IoError naming --output when it cannot be made).
Result<void> makeOutputFolder(const std::string& path);

/// One configuration to time, and what timing it found.
struct TimedConfig {
    std::string label; ///< for progress lines
    const PreparedScene* scene = nullptr;
    RenderOptions options;
    /// Called once with the last timed frame of the first round (the accuracy sweep measures
    /// its error there); may return an error to stop the run.
    std::function<Result<void>(const Image&)> inspect;

    double firstFrameMs = 0.0;        ///< wall time of the first render() (JIT of new variants)
    std::size_t pipelinesCreated = 0; ///< variants that first frame compiled
    std::vector<double> roundMedians; ///< per round: the median of its timed frames (ms)
    std::vector<double> frameMs;      ///< every timed frame (ms)
    std::vector<double> wallMs;       ///< every timed frame's render() wall time, with readback
    std::uint64_t nonFinite = 0;      ///< NaN/Inf values the renderer replaced (FrameStats)
    /// The last timed frame's clustered triangles and those it drew (FrameStats).
    std::uint64_t clusterTriangles = 0, clusterTrianglesDrawn = 0;

    double ms() const { return median(roundMedians); } ///< median of the round medians
    double minMs() const { return minimum(frameMs); }
    double msWall() const { return median(wallMs); }
    /// (slowest - fastest round median) / ms(): how much the machine drifted during the run.
    double roundSpread() const;
};

/// Times every configuration in interleaved rounds on `renderer`. The frame time is the GPU
/// render-pass time from timestamps (FrameStats::gpuMs) when the device has them, else the wall
/// time of render(); `usedGpuClock` says which. Progress goes to stderr unless `quiet`.
Result<void> timeInterleaved(Renderer& renderer, std::vector<TimedConfig>& configs,
                             const TimingPlan& plan, bool quiet, bool* usedGpuClock);

/// The median of configurations' round spreads (TimedConfig::roundSpread), as a sentence.
std::string spreadSentence(std::vector<double> spreads);

/// Gives Mesa a new, empty on-disk shader cache for this process (MESA_SHADER_CACHE_DIR in a
/// fresh temporary folder, removed when the object goes), unless the environment already
/// chooses (MESA_SHADER_CACHE_DISABLE or MESA_SHADER_CACHE_DIR set). A first frame then shows
/// the whole JIT cost, as numerics.md section 7.4 asks, while later frames run as they do for
/// a user, whose cache is on: lavapipe re-compiles some pipelines' draw-time variants on every
/// frame (S2's per-vertex modes), and with the cache off each of those costs a full LLVM
/// compile (120 ms per 480x270 frame instead of 3). Construct before Renderer::create.
class ColdShaderCache {
public:
    ColdShaderCache();
    ~ColdShaderCache();
    ColdShaderCache(const ColdShaderCache&) = delete;
    ColdShaderCache& operator=(const ColdShaderCache&) = delete;

private:
    std::string m_dir; ///< the folder made here (empty: the environment chose)
};

/// A markdown paragraph describing the machine: CPU, cores, LP_NUM_THREADS, shader cache,
/// device, driver.
std::string machineDescription(const Renderer& renderer);

/// This process's command line, arguments joined by spaces (for "reproduced with").
std::string commandLine();

/// Refuses a list that is empty or has a value outside [lo, hi]; the error names `option`.
Result<void> checkRange(const std::vector<int>& values, int lo, int hi, const std::string& option);

/// Parses the shading-mode names of a list; the error names `option`.
Result<std::vector<ShadingMode>> parseShadingList(const std::vector<std::string>& names,
                                                  const std::string& option);

/// A number for CSV and markdown: %.4g, "inf" and "nan" spelled out.
std::string num(double value, const char* format = "%.4g");

// Reports are written whole or not at all by cli::writeTextFile (common/TextFile.h).

} // namespace lantern::cli
