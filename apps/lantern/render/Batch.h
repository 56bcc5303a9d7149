// Batch.h: `lantern render` over many files times many views (docs/sequences.md, "Batches"):
// the scenes named by paths, globs and list files, the views of --views, the output templates
// ({scene}, {index}, {view}, {frame}), the jobs and their shard, and the run that renders them on one
// device, skipping finished outputs and going on past a file that fails.
#pragma once

#include "common/CliSupport.h"

#include <CLI/CLI.hpp>
#include <lantern/Lantern.h>
#include <lantern/Sequence.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lantern::cli {

/// One scene of a batch. `problem` is set when the entry was refused before loading (a list
/// entry leading outside its list's folder): the file then fails at its turn, like a bad one.
struct BatchScene {
    std::string path;  ///< what loadScene reads: a path, or builtin:NAME
    std::string stem;  ///< {scene}: the file name without its extension, or the builtin's NAME
    std::optional<Error> problem;
};

/// One view of a batch: its {view} name and its camera (none: the camera options' own).
struct BatchView {
    std::string name;
    std::optional<CameraSpec> camera;
};

/// One instant of a batch: the frame number ({frame}, '#' runs) and its time in seconds.
struct BatchFrame {
    int number = 0;
    double time = 0.0;
};

/// One image of a batch: a scene seen from a view at a frame, written to `outputs`.
struct BatchJob {
    std::size_t scene = 0, view = 0, frame = 0;
    std::vector<std::string> outputs;
};

/// Everything `lantern render` hands a batch: the parsed options, already checked.
struct BatchRequest {
    std::vector<std::string> scenes;  ///< positional: paths, globs, @LIST files
    std::vector<std::string> lists;   ///< --list FILE
    std::string views;                ///< --views
    std::vector<std::string> outputs; ///< -o templates
    std::vector<BatchFrame> frames;   ///< the frames every (scene, view) renders
    std::optional<Shard> shard;
    int processes = 1;       ///< --processes: renderers in flight (0: one per core)
    bool overwrite = false;  ///< --overwrite: render even when the outputs exist
    bool dryRun = false;
    bool writeCamera = false;  ///< --write-camera: each image's camera JSON beside it, first
    RenderOptions options;   ///< the camera options' camera when --views is not given
    ExrOptions exr;
    LoadOptions load;
    RendererDesc device;
    bool verbose = false;
    /// Refuses options the device lacks (--msaa): checked once, before the first render.
    std::function<Result<void>(const DeviceInfo&)> checkDevice;
};

/// The batch options of `lantern render` (--list, --views, --overwrite).
struct BatchCliArgs {
    std::vector<std::string> lists;
    std::string views;
    bool overwrite = false;
    int processes = 1;  ///< --processes (0: one per core)
    void add(CLI::App& app);
};

/// Refuses (Usage) what a batch cannot do: `single` (an option that concerns one picture, such
/// as --compare; null when none is given), and with --views any option that chooses a camera.
Result<void> checkBatchOptions(const BatchCliArgs& batch, const CameraOptions& camera,
                               const char* single);

/// The frames of a batch: the range or list (every frame; --shard splits jobs, not frames), or
/// the one frame of --frame N (time N / fps) or --time T (frame round(T x fps)).
Result<std::vector<BatchFrame>> batchFrames(const std::string& range, const std::string& list,
                                            double fps, std::optional<int> frame, double time);

/// True when the command line asks for a batch: several scenes, a glob, a list, --views, or an
/// output template. A single scene without these renders as before (never skipped).
bool wantsBatch(const std::vector<std::string>& scenes, const std::vector<std::string>& lists,
                const std::string& views, const std::vector<std::string>& outputs);

/// True when `arg` is a glob (has *, ? or [ and is not an existing file nor builtin:).
bool isGlob(const std::string& arg);

/// The scenes, in order: each path as given, each glob's scene files sorted (confined
/// to the glob's folder and `allowed`), each list's entries in order (relative to the list's
/// folder). Usage error for a glob that matches nothing; IoError for an unreadable list.
Result<std::vector<BatchScene>> expandScenes(const std::vector<std::string>& args,
                                             const std::vector<std::string>& lists,
                                             const std::vector<std::filesystem::path>& allowed,
                                             std::uint64_t maxBytes);

/// --views: comma-separated orbit:N, turntable:N, view names (three-quarter, front, ...) and
/// .json pose files. Empty text: one view, "default", with the camera options' camera.
Result<std::vector<BatchView>> parseViews(const std::string& text, std::uint64_t maxBytes);

/// A pose file: a JSON array of {"name", "look_at": {"eye", "center", "up"}} or
/// {"name", "camera_to_world": 16 numbers, row-major}, optional "yfov_deg", "near", "far".
Result<std::vector<BatchView>> readPoseFile(const std::string& path, std::uint64_t maxBytes);

/// What the placeholders of an output template stand for in one job.
struct TemplateValues {
    std::string scene;  ///< {scene}: the scene's stem
    std::string index;  ///< {index}: the scene's position in the batch, zero-padded
    std::string view;   ///< {view}: the view's name
    int frame = 0;      ///< {frame}, and '#' runs zero-padded to their length
};

/// Replaces {scene}, {index}, {view} and {frame} (and '#' runs, by the frame) in `pattern`; a
/// brace that starts no known placeholder is a usage error.
Result<std::string> expandOutputTemplate(const std::string& pattern, const TemplateValues& v);

/// The most jobs (scenes x views x frames) one batch plans: 262 144. The plan is held whole
/// (about 300 bytes and 1.7 microseconds a job), so that two jobs writing one file are refused
/// before anything renders. A longer sequence of one scene is a plain sequence (an output
/// with '#' and no '{', up to 16 777 216 frames, planned one frame at a time).
inline constexpr std::uint64_t kMaxBatchJobs = std::uint64_t(1) << 18;

/// Every job of the batch in its order (scene, then view, then frame); a usage error when two
/// of them would write the same file, refused input when there are more than kMaxBatchJobs.
Result<std::vector<BatchJob>> planJobs(const std::vector<BatchScene>& scenes,
                                       const std::vector<BatchView>& views,
                                       const std::vector<BatchFrame>& frames,
                                       const std::vector<std::string>& outputs);

/// Runs the batch: exit 0 when every job of the shard was rendered or skipped, 1 when any
/// failed (each reported as it happens, a summary line at the end), 2 on usage errors.
int runBatch(const BatchRequest& request);

/// The processes a render runs as (--processes): 1 in a process that runProcesses started
/// (LANTERN_BATCH_WORKER=J/N in its environment), one per core for 0, else `asked`.
int processCount(int asked);

/// In a process that runProcesses started: its part of `outer` (positions k with k mod N == J
/// within the shard given, or of everything). Elsewhere: `outer`.
Result<std::optional<Shard>> workerShard(std::optional<Shard> outer);

/// Runs this program `count` times with this command line, each told its part, and waits for
/// them (BatchProcesses.cpp), passing SIGINT and SIGTERM on: the worst of their exit codes.
int runProcesses(int count);

} // namespace lantern::cli
