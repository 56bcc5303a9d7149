// Farm.h: `lantern farm`: a sequence spread over a cluster as a job array (Slurm) or an
// Indexed Job (Kubernetes), each task running `lantern render --shard I/N`. Holds the
// submission record that `farm check` and `farm submit --resume` read, the check of which
// frames exist and can be read, and the scheduler back ends. Public API only.
#pragma once

#include <filesystem>
#include <lantern/Lantern.h>
#include <string>
#include <vector>

#include "common/TextFile.h"

namespace lantern::cli::farm {

/// One submission, as `farm submit` was asked for it: enough to write its job again, to check
/// its frames and to resubmit the missing ones. Stored beside the outputs (recordPath()).
struct Submission {
    std::string scheduler = "slurm";  ///< "slurm" or "k8s"
    std::string lantern;              ///< the `lantern` the jobs run (absolute, or a name on PATH)
    std::string scene;                ///< absolute path, or builtin:NAME
    FrameRange range;                 ///< the whole sequence
    int tasks = 1;                    ///< tasks of the first job
    std::vector<std::string> outputs; ///< absolute '#' patterns
    std::vector<std::string> renderArgs; ///< further `lantern render` arguments, verbatim
    std::vector<std::string> setup;      ///< shell lines run before the render (module load ...)
    std::string jobName;
    // Resources (both schedulers; empty or 0: the scheduler's default).
    std::string partition, time, mem;
    int cpusPerTask = 0;
    int gpus = 0;
    std::vector<std::string> sbatchArgs; ///< extra `#SBATCH` arguments
    // Kubernetes only.
    std::string image, k8sNamespace, pvc;
    /// Jobs submitted for it, oldest first: the scheduler's id (empty when only written) and
    /// the script or manifest.
    struct Job {
        std::string id;
        std::string frames; ///< "A-B" or a frame list
        std::string script;
    };
    std::vector<Job> jobs;
};

/// Where the files of a submission whose first output is `pattern` live: beside the outputs,
/// named after the pattern without its '#' run and extension (out/frame_####.exr ->
/// out/frame.farm, out/frame.sbatch, out/frame.k8s.yaml, out/frame-logs/).
std::filesystem::path recordPath(const std::string& pattern);
std::filesystem::path scriptPath(const std::string& pattern, const std::string& scheduler,
                                 int resume);
std::filesystem::path logFolder(const std::string& pattern);

Result<void> writeRecord(const Submission& s);
Result<Submission> readRecord(const std::filesystem::path& path);

// Text files are written whole or not at all by cli::writeTextFile (common/TextFile.h).
using cli::writeTextFile;

/// Quotes a word for a POSIX shell (single quotes; safe for any byte but NUL).
std::string shellQuote(const std::string& word);

/// A frame that is not there: its file is absent, or present but unreadable (for EXR: OpenEXR
/// cannot open it; for PNG: not a complete PNG). `why` is empty for an absent file.
struct MissingFrame {
    int frame = 0;
    std::string path;
    std::string why;
};

/// Checks every frame of `frames` in each output pattern; frames missing from any output are
/// reported once per output. Reads the files on all cores.
std::vector<MissingFrame> checkFrames(const std::vector<std::string>& outputs,
                                      const std::vector<int>& frames);
/// Frames of `frames` whose files exist in every output (does not read them; for progress).
int countPresent(const std::vector<std::string>& outputs, const std::vector<int>& frames);

/// The work of one job: which frames and how many tasks.
struct JobWork {
    std::vector<int> frames; ///< the frames the job renders (ascending)
    bool wholeRange = true;  ///< true: `--frames A-B`; false: `--frame-list` of `frames`
    int tasks = 1;
    std::filesystem::path script;
};

/// The `lantern render` command line of every task of a job, without its --shard (which the
/// scheduler's task index gives).
std::vector<std::string> renderCommand(const Submission& s, const JobWork& work);
/// True when the render arguments already set `option` (e.g. "--encoder-threads").
bool hasRenderOption(const Submission& s, const std::string& option);

// --- Slurm ---------------------------------------------------------------------------------

/// The sbatch script of a job (readable; resubmittable as it is with `sbatch SCRIPT`).
std::string slurmScript(const Submission& s, const JobWork& work);
/// Runs `sbatch --parsable [--hold] SCRIPT` and returns the job id.
Result<std::string> slurmSubmit(const std::filesystem::path& script, bool hold);
/// Tasks of the jobs in `ids` named `jobName` that are pending or running (0 when the
/// scheduler forgot them).
Result<int> slurmActiveTasks(const std::vector<std::string>& ids, const std::string& jobName);
/// Follows job `id` to its end with a progress line on stderr (tasks done, frames present);
/// returns the final state of each task the scheduler still knew ("COMPLETED", ...).
Result<std::vector<std::string>> slurmFollow(const std::string& id, const Submission& s,
                                             const JobWork& work);

// --- Kubernetes ----------------------------------------------------------------------------

/// The Indexed Job manifest of a job (YAML).
Result<std::string> k8sManifest(const Submission& s, const JobWork& work);

} // namespace lantern::cli::farm
